/* html_arch.c: the report page's section of each arch: its drawing, its
 * verdict table, the histories of its governing runs (html_int.h). */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/arch.h"
#include "html_int.h"

const char *aq_html_verdict(const aq_summary *s)
{
  return aq_summary_failed(s->status) ? "failed" : s->collapsed == 1 ? "collapse" : "survived";
}

/* Whether results file path keeps arch index's geometry (/geometry/NNN). */
static int has_geometry(const char *path, size_t index)
{
  char obj[64];
  snprintf(obj, sizeof obj, "/geometry/%03zu", index);
  int there = 0;
  H5E_BEGIN_TRY
  {
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) {
      there = H5Lexists(f, "/geometry", H5P_DEFAULT) > 0 && H5Lexists(f, obj, H5P_DEFAULT) > 0;
      H5Fclose(f);
    }
  }
  H5E_END_TRY;
  return there;
}

typedef struct {
  const aq_arch *arch;
  const char *results, *name; /* arch NULL: drawn from the results file's /geometry */
} arch_fig;
static aq_status draw_arch(void *ctx, const char *svg, aq_error *err)
{
  const arch_fig *a = ctx;
  if (!a->arch)
    return aq_plot_arch_h5(a->results, a->name, 0, svg, NULL, NULL, err);
  return aq_plot_arch(a->arch, 0, svg, NULL, NULL, err);
}

typedef struct {
  const aq_plot_run *run;
} hist_fig;
static aq_status draw_history(void *ctx, const char *svg, aq_error *err)
{
  const hist_fig *h = ctx;
  return aq_plot_history(h->run, svg, NULL, NULL, err);
}

/* The marks of a run that ran (docs/demand.md): 0 none, 1 slides, 2
 * beyond, 3 both. */
static int marks(const aq_summary *s)
{
  return (strstr(s->status, "slides") != NULL) | (strstr(s->status, "beyond") != NULL) << 1;
}

/* The history key of a run (as h5.c names /histories groups). */
static void history_key(const aq_h5_run *r, char *key, size_t cap)
{
  char az[32] = "";
  if (!isnan(r->s.azimuth_deg))
    snprintf(az, sizeof az, "_az%.6g", r->s.azimuth_deg);
  snprintf(key, cap, "%05lld_%03lld_%03lld%s%s", (long long)r->record_index,
           (long long)r->arch_index, (long long)r->scale_index,
           strcmp(r->s.polarity, "reversed") == 0 ? "r" : "", az);
}

static aq_status history_figure(aq_html_page *p, const aq_h5_run *r, const char *why)
{
  char key[96];
  history_key(r, key, sizeof key);
  aq_plot_run run;
  aq_error e;
  aq_page_buf *b = p->b;
  aq_page_puts(b, "<h4>");
  aq_page_esc(b, aq_html_base(r->s.record));
  aq_page_printf(b, " at scale %.4g, %s (%s)</h4>\n", r->s.scale, r->s.polarity, why);
  if (aq_plot_run_read(p->in->results, key, &run, &e) != AQ_OK) {
    aq_page_puts(b, "<p><i>History not stored: ");
    aq_page_esc(b, e.message);
    aq_page_puts(b, "</i></p>\n");
    return AQ_OK;
  }
  hist_fig h = {&run};
  char label[512];
  aq_text_fit(label, sizeof label, "history of %s on %s at scale %g", aq_html_base(r->s.record),
              r->s.arch, r->s.scale);
  aq_status st = aq_html_figure(p, label, draw_history, &h);
  aq_plot_run_free(&run);
  return st;
}

/* A run's place among its arch's: its record, scale and azimuth, whose
 * polarities (both, unless the arch is its own mirror image) make one group
 * in which the worse run governs. */
typedef struct {
  int64_t rec, scale;
  double az;
  size_t k;
} run_key;

static int run_key_cmp(const void *pa, const void *pb)
{
  const run_key *x = pa, *y = pb;
  if (x->rec != y->rec)
    return x->rec < y->rec ? -1 : 1;
  if (x->scale != y->scale)
    return x->scale < y->scale ? -1 : 1;
  int nx = isnan(x->az), ny = isnan(y->az);
  if (nx || ny)
    return nx - ny;
  if (x->az != y->az)
    return x->az < y->az ? -1 : 1;
  return x->k < y->k ? -1 : x->k > y->k;
}

/* The governing run of each group of arch a's runs (the worse polarity,
 * aq_summary_worst), in a new array of *ng; NULL when out of memory. */
static const aq_h5_run **governing_runs(const aq_h5_suite *S, size_t a, size_t *ng)
{
  size_t n = 0;
  for (size_t k = 0; k < S->nruns; k++)
    n += S->runs[k].arch_index == (int64_t)a;
  run_key *key = malloc((n ? n : 1) * sizeof *key);
  const aq_summary **row = malloc((n ? n : 1) * sizeof *row);
  const aq_h5_run **gov = malloc((n ? n : 1) * sizeof *gov);
  if (!key || !row || !gov) {
    free(key);
    free(row);
    free(gov);
    return NULL;
  }
  n = 0;
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index == (int64_t)a)
      key[n++] = (run_key){r->record_index, r->scale_index, r->s.azimuth_deg, k};
  }
  qsort(key, n, sizeof *key, run_key_cmp);
  *ng = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    for (; j < n && key[j].rec == key[i].rec && key[j].scale == key[i].scale &&
           (key[j].az == key[i].az || (isnan(key[j].az) && isnan(key[i].az)));
         j++)
      row[j - i] = &S->runs[key[j].k].s;
    gov[(*ng)++] = &S->runs[key[i + aq_summary_worst(row, j - i)].k];
    i = j;
  }
  free(key);
  free(row);
  return gov;
}

aq_status aq_html_section_arch(aq_html_page *p, size_t a, size_t *nrows)
{
  aq_page_buf *b = p->b;
  const aq_page_attrs *A = &p->r.arch[a];
  const char *name = aq_page_attr(A, "name");
  name = name ? name : "?";
  const aq_h5_suite *S = &p->r.suite;
  size_t ncol = 0, nsurv = 0, nfail = 0, any_az = 0, any_rev = 0, nslide = 0, nbeyond = 0;
  const aq_h5_run *strongest = NULL;
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index != (int64_t)a)
      continue;
    const char *v = aq_html_verdict(&r->s);
    ncol += v[0] == 'c';
    nsurv += v[0] == 's';
    nfail += v[0] == 'f';
    nslide += marks(&r->s) & 1;
    nbeyond += (marks(&r->s) & 2) >> 1;
    any_az += !isnan(r->s.azimuth_deg);
    any_rev += strcmp(r->s.polarity, "reversed") == 0;
  }
  /* the worse polarity of each record and scale governs */
  size_t ng = 0, gcol = 0, gsurv = 0;
  const aq_h5_run **gov = governing_runs(S, a, &ng);
  if (!gov)
    return aq_error_set(p->err, AQ_ENOMEM, p->target, -1, -1, NULL, "out of memory");
  for (size_t g = 0; g < ng; g++) {
    const char *v = aq_html_verdict(&gov[g]->s);
    gcol += v[0] == 'c';
    gsurv += v[0] == 's';
    if (v[0] == 's' && (!strongest || gov[g]->s.pga_g > strongest->s.pga_g))
      strongest = gov[g];
  }
  free(gov);
  aq_page_printf(b, "<h2 id=\"arch-%zu\">Arch ", a);
  aq_page_esc(b, name);
  aq_page_puts(b, "</h2>\n");
  aq_page_printf(b, "<p><b>%zu collapse%s</b>, %zu survived, %zu failed, of %zu runs.  "
                    "λ0 %.4g (primary), %.4g (reverse); q<sub>c</sub> %.4g rad, %.4g rad.</p>\n",
                 ncol, ncol == 1 ? "" : "s", nsurv, nfail, ncol + nsurv + nfail,
                 aq_page_attr_num(A, "primary_lambda0"), aq_page_attr_num(A, "reverse_lambda0"),
                 aq_page_attr_num(A, "primary_q_c_rad"), aq_page_attr_num(A, "reverse_q_c_rad"));
  if (any_rev)
    aq_page_printf(b, "<p>Each record and scale ran both ways (the polarity column), and the "
                      "worse governs: <b>%zu collapse%s</b>, %zu survived, %zu failed, of %zu."
                      "</p>\n",
                   gcol, gcol == 1 ? "" : "s", gsurv, ng - gcol - gsurv, ng);
  const char *control = aq_page_attr(A, "control");
  double mu = aq_page_attr_num(A, "friction");
  if (control && !strcmp(control, "free"))
    aq_page_puts(b, "<p>Hinges <b>free</b>: any joint may open, so each direction of ground "
                    "acceleration drives its own minimum mechanism (primary: along −x, "
                    "reverse: along +x).");
  else
    aq_page_printf(b, "<p>Hinges <b>fixed</b>%s: the hinge-controlled arch, whose mechanical "
                      "joints are the primary set's (the reverse set swaps their faces); every "
                      "other joint is taken to carry what the thrust demands, and every verdict "
                      "below assumes so.",
                   control ? "" : " (a file written before the control was recorded)");
  if (mu > 0)
    aq_page_printf(b, "  Joint friction μ = %.4g.", mu);
  else
    aq_page_puts(b, "  No joint friction given: sliding is not checked.");
  /* the friction the collapse states need (the figure's lower panel) */
  double need[2] = {aq_page_attr_num(A, "primary_mu_required"),
                    aq_page_attr_num(A, "reverse_mu_required")};
  double lf[2] = {aq_page_attr_num(A, "primary_lambda_friction"),
                  aq_page_attr_num(A, "reverse_lambda_friction")};
  static const char *const set_word[2] = {"primary", "reverse"};
  for (int k = 0; k < 2; k++) {
    if (isnan(need[k]))
      continue;
    aq_page_printf(b, "  At its λ0 the %s set needs μ = %.3g (joint %.0f)", set_word[k], need[k],
                   aq_page_attr_num(A, k ? "reverse_mu_joint" : "primary_mu_joint"));
    if (mu > 0 && need[k] > mu)
      aq_page_printf(b, ": <b>more than the arch's %.3g</b>, so a line of thrust stands only "
                        "up to λ = %.4g in that direction", mu, lf[k]);
    aq_page_puts(b, ".");
  }
  aq_page_puts(b, "</p>\n");
  if (nslide || nbeyond) {
    aq_page_puts(b, "<p><b>Beyond the four-hinge model:</b> ");
    if (nslide)
      aq_page_printf(b, "%zu run%s <b>slide%s</b> (the friction demand passed μ); ", nslide,
                     nslide == 1 ? "" : "s", nslide == 1 ? "s" : "");
    if (nbeyond)
      aq_page_printf(b, "in %zu run%s the thrust left a joint's section with free hinges "
                        "(<b>beyond</b>); ",
                     nbeyond, nbeyond == 1 ? "" : "s");
    aq_page_puts(b, "their verdicts are the four-hinge model's, which stops describing the "
                    "arch at the time given; follow them with <code>--model blocks</code>.</p>\n");
  }
  /* the arch */
  const char *cfg = aq_page_attr(A, "config");
  aq_arch *arch = NULL;
  aq_error e;
  /* from its .cfg as read; an arch the .cfg alone does not make (a joints
   * arch's files) from the geometry the results file keeps */
  /* the friction the runs used (--friction over the file's); the page reads no table */
  aq_arch_options ao = {.friction = mu};
  int loaded =
      cfg && aq_arch_load_string_opts(cfg, strlen(cfg), name, &ao, &arch, &e) == AQ_OK;
  if (loaded || has_geometry(p->in->results, a)) {
    arch_fig f = {arch, p->in->results, name};
    char label[200];
    snprintf(label, sizeof label, "arch %s to scale with its hinge sets", name);
    aq_status st = aq_html_figure(p, label, draw_arch, &f);
    aq_arch_free(arch);
    if (st != AQ_OK)
      return st;
    aq_html_read_note(b, "The arch to scale.  Filled circles are hinges at the extrados (outer "
                 "face), open circles at the intrados; blue the primary set, orange the "
                 "reverse set.  Below it, the friction each joint needs at the set's λ0 "
                 "(|T|/N of the force across it, from the hinge reactions), each set in its "
                 "colour, the arch's friction coefficient dashed: where a set's curve passes "
                 "it, that joint would slide before the set's hinges can turn.");
  } else {
    aq_page_puts(b, "<p><i>The arch's configuration could not be loaded: ");
    aq_page_esc(b, cfg ? e.message : "no config attribute");
    aq_page_puts(b, "</i></p>\n");
  }
  if (cfg) {
    aq_page_puts(b, "<details><summary>The arch file as read</summary><pre>");
    aq_page_esc(b, cfg);
    aq_page_puts(b, "</pre></details>\n");
  }
  /* a joints arch's files, as read: with the .cfg, what its SHA-256 covers */
  static const char *const data_attr[2][2] = {{"joints_csv", "Its joints file as read"},
                                              {"faces_csv", "Its faces file as read"}};
  for (int k = 0; k < 2; k++) {
    const char *text = aq_page_attr(A, data_attr[k][0]);
    if (!text)
      continue;
    aq_page_printf(b, "<details><summary>%s</summary><pre>", data_attr[k][1]);
    aq_page_esc(b, text);
    aq_page_puts(b, "</pre></details>\n");
  }
  /* the verdict table */
  aq_page_printf(b, "<h3 id=\"verdicts-%zu\">Verdicts</h3>\n", a);
  aq_html_read_note(b, "One row per run: a record, scaled, against this arch.  <b>COLLAPSE</b> "
               "rows are marked in words and bold as well as colour; <i>failed</i> runs "
               "have no verdict (their reason is in <a href=\"#failed\">Failed "
               "records</a> or the status).  The margin is in the last columns: the peak "
               "rotation as a fraction of q<sub>c</sub> (1 is collapse) and the PGA over "
               "λ0 g (below 1 the arch never moves).  The friction demand is the largest "
               "|T|/N at any joint over the run (∞: a joint pulled apart); for a run in which "
               "the arch never moves, the least friction with which a line of thrust stands "
               "at the record's peak (∞: none stands).  The thrust is the "
               "largest eccentricity of the line of thrust at a joint that is not a hinge "
               "(beyond 1 it leaves the section).  <b>slides</b>: a friction μ was given and "
               "the demand passed it; <b>beyond</b>: with free hinges the thrust left a "
               "section; each with the time, from which the four-hinge model of the verdict "
               "no longer describes the arch: follow such a run with <code>--model "
               "blocks</code>.  Click a column's head to sort; the boxes above the table "
               "hide a verdict.");
  aq_page_puts(b, "<table class=\"verdicts wide\"><thead><tr><th>record</th><th>scale</th>");
  if (any_rev)
    aq_page_puts(b, "<th>polarity</th>");
  if (any_az)
    aq_page_puts(b, "<th>azimuth (°)</th>");
  aq_page_puts(b, "<th>PGA (g)</th><th>verdict</th><th>collapse at (s)</th>"
                  "<th>peak rotation / q<sub>c</sub></th><th>peak rotation (rad)</th>"
                  "<th>PGA / λ0 g</th><th>impacts</th><th>friction demand</th>"
                  "<th>thrust eccentricity</th></tr></thead><tbody>\n");
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index != (int64_t)a)
      continue;
    const char *v = aq_html_verdict(&r->s);
    aq_page_printf(b, "<tr data-verdict=\"%s\">", v);
    aq_page_puts(b, "<td class=\"mono\" title=\"");
    aq_page_esc(b, r->s.record);
    aq_page_puts(b, "\">");
    aq_page_esc(b, aq_html_base(r->s.record));
    aq_page_puts(b, "</td>");
    aq_html_num_td(b, r->s.scale, "%.4g");
    if (any_rev)
      aq_html_text_td(b, r->s.polarity, 0);
    if (any_az)
      aq_html_num_td(b, r->s.azimuth_deg, "%.4g");
    aq_html_num_td(b, r->s.pga_g, "%.4g");
    if (v[0] == 'f') {
      aq_page_puts(b, "<td class=\"v-f\">⚠ failed: ");
      aq_page_esc(b, r->s.status);
    } else {
      /* the marks follow the verdict in its cell (a failed run has none) */
      aq_page_puts(b, v[0] == 'c' ? "<td class=\"v-c\">✖ COLLAPSE"
                                  : "<td class=\"v-s\">survived");
      int mk = marks(&r->s);
      if (mk & 1)
        aq_page_printf(b, "; slides at %.3f s", r->s.slide_time_s);
      if (mk & 2)
        aq_page_printf(b, "; beyond at %.3f s", r->s.thrust_ecc_time_s);
    }
    aq_page_puts(b, "</td>");
    aq_html_num_td(b, r->s.collapse_time_s, "%.3f");
    aq_html_num_td(b, r->s.peak_rotation_over_qc, "%.3f");
    aq_html_num_td(b, r->s.peak_rotation_rad, "%.3g");
    aq_html_num_td(b, r->s.pga_over_lambda0, "%.3g");
    aq_html_num_td(b, r->s.impacts < 0 ? NAN : (double)r->s.impacts, "%.0f");
    aq_html_num_td(b, r->s.mu_demand, "%.3g");
    aq_html_num_td(b, r->s.thrust_ecc_max, "%.3g");
    aq_page_puts(b, "</tr>\n");
    (*nrows)++;
  }
  aq_page_puts(b, "</tbody></table>\n");
  /* histories */
  aq_page_puts(b, "<h3>Responses</h3>\n");
  if (!p->r.have_histories) {
    aq_page_puts(b, "<p><i>No histories in this results file (the suite was run without "
                    "<code>--history</code>): the responses of the collapsed runs and of "
                    "the strongest surviving one are not drawn.</i></p>\n");
    return AQ_OK;
  }
  aq_html_read_note(b, "The response of each collapsed run and of the surviving run with the "
               "largest PGA: the ground acceleration with ±λ0 g (where the arch starts to "
               "move), the rotation with ±q<sub>c</sub>, and the energies; impacts green, "
               "the collapse red.");
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index == (int64_t)a && strcmp(aq_html_verdict(&r->s), "collapse") == 0) {
      aq_status st = history_figure(p, r, "collapse");
      if (st != AQ_OK)
        return st;
    }
  }
  if (strongest)
    return history_figure(p, strongest, "the strongest surviving run");
  return AQ_OK;
}

