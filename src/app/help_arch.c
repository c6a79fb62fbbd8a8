/* help_arch.c: `archquake help arch-file`, the arch file described from the
 * table its parser reads (src/arch/cfg_keys.h): the syntax, every section
 * and key with its unit, range, default and the shapes that take it, the
 * shapes, and the joints and faces files.  tools/man.sh puts it in the
 * manual page as ARCH FILE. */
#include <stdio.h>
#include <string.h>

#include "../arch/cfg_keys.h"
#include "opt_table.h"

enum { KEY_COL = 24 }; /* where a key's text starts */

/* "circular" or "pointed, elliptical, parabolic and catenary": the shapes
 * in mask, into buf[n]. */
static void shapes(unsigned mask, char *buf, size_t n)
{
  size_t len = 0, k = 0, count = 0;
  buf[0] = '\0';
  for (size_t s = 0; s < aq_cfg_nshapes; s++)
    count += mask >> s & 1u;
  for (size_t s = 0; s < aq_cfg_nshapes && len < n; s++)
    if (mask >> s & 1u) {
      k++;
      len += (size_t)snprintf(buf + len, n - len, "%s%s",
                              k == 1 ? "" : k == count ? " and " : ", ", aq_cfg_shape_names[s]);
    }
}

/* The words after a key's help: its choices, range, default or need, and
 * the shapes that take it. */
static void details(const aq_cfg_key *k, char *buf, size_t n)
{
  unsigned all = (1u << aq_cfg_nshapes) - 1;
  char range[64], list[256];
  size_t len = 0;
  buf[0] = '\0';
#define ADD(...) \
  (len += len < n ? (size_t)snprintf(buf + len, n - len, __VA_ARGS__) : 0)
  if (k->kind == AQ_CFG_CHOICE) {
    ADD(";");
    for (size_t i = 0; k->choices[i]; i++)
      ADD("%s%s", i == 0 ? " one of " : k->choices[i + 1] ? ", " : " or ", k->choices[i]);
  }
  aq_cfg_range_text(k, range, sizeof range);
  if (range[0])
    ADD("; %s%s", k->kind == AQ_CFG_MASS ? "MASS_KG in " : "", range);
  else if (k->unit && k->unit[0])
    ADD("; %s", k->unit);
  if (k->required && k->required == all)
    ADD("; required");
  else if (k->required) {
    shapes(k->required, list, sizeof list);
    ADD("; required for shape %s", list);
  } else if (k->shapes != all) {
    shapes(k->shapes, list, sizeof list);
    ADD("; shape %s only", list);
  }
  if (k->deflt)
    ADD("; default: %s", k->deflt);
#undef ADD
}

void aq_help_arch_file(FILE *f)
{
  static const char *const meta[] = {[AQ_CFG_TEXT] = "TEXT", [AQ_CFG_CHOICE] = "WORD",
                                     [AQ_CFG_PATH] = "FILE",  [AQ_CFG_REAL] = "NUMBER",
                                     [AQ_CFG_INT] = "N",      [AQ_CFG_HINGES] = "HINGES",
                                     [AQ_CFG_MASS] = "VOUSSOIR X_M Y_M MASS_KG"};
  fputs("The arch file (.cfg) that --arch takes: its sections and keys, as archquake\n"
        "reads them (docs/arch-file.md and docs/arch-shapes.md explain the model).\n", f);
  aq_opt_help_entry(f, "Syntax:", aq_cfg_syntax_help, NULL, 2);
  char lab[128], text[1024], more[512];
  for (size_t s = 0; s < aq_cfg_nsections; s++) {
    snprintf(lab, sizeof lab, "[%s]", aq_cfg_sections[s].name);
    aq_opt_help_entry(f, lab, aq_cfg_sections[s].help, NULL, 2);
    for (int i = 0; i < AQ_CFG_NKEYS; i++) {
      const aq_cfg_key *k = &aq_cfg_keys[i];
      if (strcmp(k->section, aq_cfg_sections[s].name) != 0)
        continue;
      snprintf(lab, sizeof lab, "  %s = %s", k->name, meta[k->kind]);
      details(k, more, sizeof more);
      snprintf(text, sizeof text, "%s%s", k->help, more);
      aq_opt_help_entry(f, lab, text, NULL, KEY_COL);
    }
  }
  fputs("Shapes (shape = NAME; the keys each takes besides density_kg_m3 and depth_m):\n", f);
  for (size_t s = 0; s < aq_cfg_nshapes; s++) {
    snprintf(lab, sizeof lab, "  %s", aq_cfg_shape_names[s]);
    aq_opt_help_entry(f, lab, aq_cfg_shape_help[s], NULL, 14);
  }
  snprintf(text, sizeof text, aq_cfg_joints_help, AQ_CFG_LENGTH_MIN_M, AQ_CFG_LENGTH_MAX_M,
           AQ_CFG_COORD_MAX_M);
  aq_opt_help_entry(f, "Joints file (joints_file):", text, NULL, 2);
  snprintf(text, sizeof text, aq_cfg_faces_help, AQ_CFG_COORD_MAX_M);
  aq_opt_help_entry(f, "Faces file (faces_file):", text, NULL, 2);
}
