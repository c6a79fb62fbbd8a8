/* summary.c: the run summary and its field table (see report.h). */
#include "report.h"

#include <ctype.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define AQ_SF(name, kind, key) \
  {#name, kind, offsetof(aq_summary, name), sizeof(((aq_summary *)0)->name), key, 0}
#define AQ_SF_ADDED(name, kind, key) \
  {#name, kind, offsetof(aq_summary, name), sizeof(((aq_summary *)0)->name), key, 1}

const aq_summary_field aq_summary_fields[] = {
    AQ_SF(record, AQ_SF_STR, 1),
    AQ_SF(arch, AQ_SF_STR, 1),
    AQ_SF(model, AQ_SF_STR, 0),
    AQ_SF(scale, AQ_SF_DOUBLE, 1),
    AQ_SF(pga_g, AQ_SF_DOUBLE, 0),
    AQ_SF(status, AQ_SF_STR, 0),
    AQ_SF(collapsed, AQ_SF_INT, 0),
    AQ_SF(collapse_time_s, AQ_SF_DOUBLE, 0),
    AQ_SF(peak_rotation_rad, AQ_SF_DOUBLE, 0),
    AQ_SF(peak_displacement_m, AQ_SF_DOUBLE, 0),
    AQ_SF(max_kinetic_energy_j, AQ_SF_DOUBLE, 0),
    AQ_SF(impacts, AQ_SF_INT, 0),
    AQ_SF(energy_in_j, AQ_SF_DOUBLE, 0),
    AQ_SF(energy_dissipated_j, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(polarity, AQ_SF_STR, 1),
    AQ_SF_ADDED(lambda0_first, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(peak_rotation_over_qc, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(pga_over_lambda0, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(azimuth_deg, AQ_SF_DOUBLE, 1),
    AQ_SF_ADDED(control, AQ_SF_STR, 0),
    AQ_SF_ADDED(mu_demand, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(mu_demand_joint, AQ_SF_INT, 0),
    AQ_SF_ADDED(thrust_ecc_max, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(thrust_ecc_time_s, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(slide_time_s, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(max_slip_m, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(hinges_observed, AQ_SF_STR, 0),
    AQ_SF_ADDED(hinges_first_s, AQ_SF_STR, 0),
    AQ_SF_ADDED(mechanism_changed_s, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(check_blocks, AQ_SF_STR, 0),
    AQ_SF_ADDED(check_collapsed, AQ_SF_INT, 0),
    AQ_SF_ADDED(check_collapse_time_s, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(check_peak_rotation_rad, AQ_SF_DOUBLE, 0),
    AQ_SF_ADDED(friction_work_j, AQ_SF_DOUBLE, 0),
};
const size_t aq_summary_nfields =
    sizeof aq_summary_fields / sizeof aq_summary_fields[0];
_Static_assert(sizeof aq_summary_fields / sizeof aq_summary_fields[0] <= AQ_SUMMARY_FIELDS_MAX,
               "every field has a column in the fixed tables (text.h aq_text_layout)");

static void copy_str(char *dst, size_t n, const char *src)
{
  snprintf(dst, n, "%s", src ? src : "");
}

/* A comma-separated list into dst[n]: "-" when empty, cut at a comma with
 * ",..." when it does not fit. */
static void copy_list(char *dst, size_t n, const char *src)
{
  if (!src || !*src) {
    copy_str(dst, n, "-");
    return;
  }
  if (strlen(src) < n) {
    copy_str(dst, n, src);
    return;
  }
  size_t k = n - 5; /* room for ",..." and the NUL */
  while (k > 0 && src[k] != ',')
    k--;
  snprintf(dst, n, "%.*s,...", (int)k, src);
}

void aq_summary_fill(aq_summary *s, const char *record, const char *arch,
                     const char *model, double scale, double pga_g,
                     const char *status, const aq_result *res)
{
  memset(s, 0, sizeof *s);
  copy_str(s->record, sizeof s->record, record);
  copy_str(s->arch, sizeof s->arch, arch);
  copy_str(s->model, sizeof s->model, model);
  copy_str(s->status, sizeof s->status, status);
  copy_str(s->polarity, sizeof s->polarity, "normal");
  copy_str(s->control, sizeof s->control, "fixed"); /* files before it: hinge-controlled */
  s->scale = scale;
  s->pga_g = pga_g;
  s->lambda0_first = NAN; /* aq_summary_normalise fills them */
  s->peak_rotation_over_qc = NAN;
  s->pga_over_lambda0 = NAN;
  s->azimuth_deg = NAN;
  s->mu_demand = s->thrust_ecc_max = s->thrust_ecc_time_s = s->slide_time_s = NAN;
  s->mu_demand_joint = AQ_SUMMARY_INT_NONE;
  s->max_slip_m = s->mechanism_changed_s = NAN;
  s->friction_work_j = NAN;
  copy_str(s->hinges_observed, sizeof s->hinges_observed, "-");
  copy_str(s->hinges_first_s, sizeof s->hinges_first_s, "-");
  copy_str(s->check_blocks, sizeof s->check_blocks, "-");
  s->check_collapsed = AQ_SUMMARY_INT_NONE;
  s->check_collapse_time_s = s->check_peak_rotation_rad = NAN;
  if (res && res->bodies) {
    s->max_slip_m = res->bodies->max_slip_m;
    s->mechanism_changed_s = res->bodies->mechanism_changed_s;
    s->friction_work_j = res->bodies->friction_work_j;
    copy_list(s->hinges_observed, sizeof s->hinges_observed, res->bodies->hinges_observed);
    copy_list(s->hinges_first_s, sizeof s->hinges_first_s, res->bodies->hinges_first_s);
  }
  if (res && !isnan(res->mu_demand)) {
    s->mu_demand = res->mu_demand;
    s->mu_demand_joint = (int64_t)res->mu_demand_joint;
    s->thrust_ecc_max = res->thrust_ecc_max;
    s->thrust_ecc_time_s = res->thrust_ecc_time_s;
    s->slide_time_s = res->slide_time_s;
  }
  if (res) {
    s->collapsed = res->collapsed ? 1 : 0;
    s->collapse_time_s = res->collapsed ? res->collapse_time_s : NAN;
    s->peak_rotation_rad = res->peak_rotation_rad;
    s->peak_displacement_m = res->peak_displacement_m;
    s->max_kinetic_energy_j = res->max_kinetic_energy_j;
    s->impacts = (int64_t)res->impacts;
    s->energy_in_j = res->energy_in_j;
    s->energy_dissipated_j = res->energy_dissipated_j;
  } else {
    s->collapsed = AQ_SUMMARY_INT_NONE; /* no verdict: not "survived" */
    s->collapse_time_s = NAN;
    s->peak_rotation_rad = NAN;
    s->peak_displacement_m = NAN;
    s->max_kinetic_energy_j = NAN;
    s->impacts = AQ_SUMMARY_INT_NONE;
    s->energy_in_j = NAN;
    s->energy_dissipated_j = NAN;
  }
}

void aq_summary_normalise(aq_summary *s, const char *polarity, const aq_result *res,
                          const aq_path *primary, const aq_path *reverse)
{
  copy_str(s->polarity, sizeof s->polarity, polarity ? polarity : "normal");
  if (!res)
    return; /* a failed run: no verdict, the fields stay NAN */
  const aq_path *set[2] = {primary, reverse};
  for (int k = 0; k < 2; k++)
    if (set[k] && !set[k]->admissible)
      set[k] = NULL;
  const aq_path *first = res->first_set >= 0 ? set[res->first_set] : NULL;
  s->lambda0_first = first ? first->lambda0 : NAN;
  s->peak_rotation_over_qc = aq_result_peak_over_qc(res, primary, reverse);
  /* the set driven first, else the one the record would have to drive */
  double l0 = first ? first->lambda0 : NAN;
  for (int k = 0; !first && k < 2; k++)
    if (set[k] && !(set[k]->lambda0 >= l0))
      l0 = set[k]->lambda0;
  s->pga_over_lambda0 = s->pga_g / l0;
}

void aq_summary_mark(aq_summary *s, double friction, int free_control)
{
  if (strcmp(s->status, "ok") != 0)
    return;
  int marks = aq_result_marks(s->mu_demand, s->thrust_ecc_max, friction, free_control);
  if (marks)
    snprintf(s->status, sizeof s->status, "%s", aq_result_marks_name(marks));
}

void aq_summary_check(aq_summary *s, const aq_result *b)
{
  if (!b) {
    copy_str(s->check_blocks, sizeof s->check_blocks, "failed");
    return;
  }
  s->check_collapsed = b->collapsed ? 1 : 0;
  s->check_collapse_time_s = b->collapsed ? b->collapse_time_s : NAN;
  s->check_peak_rotation_rad = b->peak_rotation_rad;
  copy_str(s->check_blocks, sizeof s->check_blocks,
           s->check_collapsed == s->collapsed ? "agrees" : "differs");
  if (b->bodies) {
    s->max_slip_m = b->bodies->max_slip_m;
    s->mechanism_changed_s = b->bodies->mechanism_changed_s;
    s->friction_work_j = b->bodies->friction_work_j;
    copy_list(s->hinges_observed, sizeof s->hinges_observed, b->bodies->hinges_observed);
    copy_list(s->hinges_first_s, sizeof s->hinges_first_s, b->bodies->hinges_first_s);
  }
}

int aq_summary_failed(const char *status) { return strchr(status, ':') != NULL; }

void aq_summary_status(char *buf, size_t n, const char *stage, aq_status st)
{
  const char *name = "einternal";
  char low[32];
  switch (st) {
#define AQ_X_NAME(sym, code, text) \
  case sym:                        \
    name = &(#sym)[3];            \
    break;
    AQ_STATUS_LIST(AQ_X_NAME)
#undef AQ_X_NAME
  }
  size_t k = 0;
  for (; name[k] && k + 1 < sizeof low; k++)
    low[k] = (char)tolower((unsigned char)name[k]);
  low[k] = '\0';
  if (st == AQ_OK)
    snprintf(buf, n, "ok");
  else
    snprintf(buf, n, "%s:%s", stage ? stage : "run", low);
}

const char *aq_summary_units(const aq_summary_field *f)
{
  static const struct {
    const char *suffix, *units;
  } rule[] = {{"_s", "s"}, {"_rad", "rad"}, {"_m", "m"}, {"_j", "J"}, {"_g", "g"},
               {"_deg", "deg"}};
  if (f->kind == AQ_SF_STR)
    return "";
  if (strstr(f->name, "_over_")) /* a ratio (pga_over_lambda0: PGA / (lambda0 g)) */
    return "1";
  size_t n = strlen(f->name);
  for (size_t k = 0; k < sizeof rule / sizeof rule[0]; k++) {
    size_t m = strlen(rule[k].suffix);
    if (n > m && strcmp(f->name + n - m, rule[k].suffix) == 0)
      return rule[k].units;
  }
  return "1";
}

double aq_summary_get_double(const aq_summary *s, const aq_summary_field *f)
{
  double x;
  memcpy(&x, (const char *)s + f->offset, sizeof x);
  return x;
}

int64_t aq_summary_get_int(const aq_summary *s, const aq_summary_field *f)
{
  int64_t x;
  memcpy(&x, (const char *)s + f->offset, sizeof x);
  return x;
}

const char *aq_summary_get_str(const aq_summary *s, const aq_summary_field *f)
{
  return (const char *)s + f->offset;
}

/* 1 if run a is worse than run b (see aq_summary_worst). */
static int worse(const aq_summary *a, const aq_summary *b)
{
  int fa = aq_summary_failed(a->status), fb = aq_summary_failed(b->status);
  if (fa || fb)
    return fa && !fb;
  if (a->collapsed != b->collapsed)
    return a->collapsed > b->collapsed;
  if (a->collapsed == 1 && a->collapse_time_s != b->collapse_time_s)
    return a->collapse_time_s < b->collapse_time_s;
  return a->peak_rotation_over_qc > b->peak_rotation_over_qc;
}

size_t aq_summary_worst(const aq_summary *const *rows, size_t n)
{
  size_t w = 0;
  for (size_t i = 1; i < n; i++)
    if (worse(rows[i], rows[w]))
      w = i;
  return w;
}
