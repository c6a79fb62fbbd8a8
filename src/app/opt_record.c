/* opt_record.c: the reader options (see opt_record.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_record.h"

#include <stdio.h>
#include <string.h>

#include "opt.h"

const struct option aq_opt_record_longopts[] = {AQ_OPT_RECORD_LONGOPTS,
                                                {NULL, 0, NULL, 0}};

static int parse_units(const char *opt, const char *word, aq_units *u, int *nerr)
{
  if (strcmp(word, "file") == 0) {
    *u = AQ_UNITS_FILE;
    return 1;
  }
  if (aq_units_parse(word, u))
    return 1;
  fprintf(stderr,
          "archquake: %s: expected g, g/10, gal, cm/s2, mm/s2, m/s2, nm/s2, "
          "counts or file "
          "(optionally after GLOB=), got \"%s\"\n",
          opt, word);
  (*nerr)++;
  return 0;
}

int aq_opt_record_handle(int id, const char *arg, aq_read_opts *ro, int *nerr)
{
  switch (id) {
  case AQ_OPT_RECORD_UNITS: {
    const char *a = arg ? arg : "";
    const char *eq = strrchr(a, '=');
    aq_units u;
    if (!eq)
      return parse_units("--units", a, &ro->units, nerr), 1;
    size_t gl = (size_t)(eq - a);
    if (gl == 0 || gl >= AQ_UNITS_GLOB_MAX) {
      fprintf(stderr,
              "archquake: --units: expected GLOB=U with a pattern of 1 to %d "
              "characters, got \"%s\"\n",
              AQ_UNITS_GLOB_MAX - 1, a);
      (*nerr)++;
      return 1;
    }
    if (ro->nrules >= AQ_UNITS_RULES_MAX) {
      fprintf(stderr, "archquake: --units: expected at most %d GLOB=U rules, got "
                      "more (\"%s\")\n",
              AQ_UNITS_RULES_MAX, a);
      (*nerr)++;
      return 1;
    }
    if (!parse_units("--units", eq + 1, &u, nerr))
      return 1;
    memcpy(ro->rules[ro->nrules].glob, a, gl);
    ro->rules[ro->nrules].glob[gl] = '\0';
    ro->rules[ro->nrules].units = u;
    ro->nrules++;
    return 1;
  }
  case AQ_OPT_RECORD_COMPONENT: {
    const char *a = arg ? arg : "";
    const char *eq = strrchr(a, '=');
    size_t gl = eq ? (size_t)(eq - a) : 0;
    if (!eq || gl == 0 || gl >= AQ_UNITS_GLOB_MAX || !eq[1] ||
        strlen(eq + 1) >= sizeof ro->components[0].channel) {
      fprintf(stderr,
              "archquake: --component: expected GLOB=CHANNEL (pattern of 1 to %d "
              "characters, channel of 1 to %zu), got \"%s\"\n",
              AQ_UNITS_GLOB_MAX - 1, sizeof ro->components[0].channel - 1, a);
      (*nerr)++;
      return 1;
    }
    if (ro->ncomponents >= AQ_UNITS_RULES_MAX) {
      fprintf(stderr, "archquake: --component: expected at most %d rules, got more "
                      "(\"%s\")\n",
              AQ_UNITS_RULES_MAX, a);
      (*nerr)++;
      return 1;
    }
    memcpy(ro->components[ro->ncomponents].glob, a, gl);
    ro->components[ro->ncomponents].glob[gl] = '\0';
    snprintf(ro->components[ro->ncomponents].channel,
             sizeof ro->components[0].channel, "%s", eq + 1);
    ro->ncomponents++;
    return 1;
  }
  case AQ_OPT_RECORD_ACCEPT_IMPLAUSIBLE:
    ro->accept_implausible = 1;
    return 1;
  case AQ_OPT_RECORD_ACCEPT_VERTICAL:
    ro->accept_vertical = 1;
    return 1;
  case AQ_OPT_RECORD_RESPONSE:
    if (!arg || !arg[0] || strlen(arg) >= sizeof ro->response) {
      fprintf(stderr, "archquake: --response: expected a StationXML file name of 1 to "
                      "%zu characters, got \"%s\"\n",
              sizeof ro->response - 1, arg ? arg : "");
      (*nerr)++;
      return 1;
    }
    snprintf(ro->response, sizeof ro->response, "%s", arg);
    return 1;
  case AQ_OPT_RECORD_DT:
    aq_opt_double_gt("--dt", arg, 0, 3600, &ro->dt_s, nerr);
    return 1;
  case AQ_OPT_RECORD_COLUMN: {
    long col = (long)ro->column;
    aq_opt_long("--column", arg, 1, 64, &col, nerr);
    ro->column = (size_t)col;
    return 1;
  }
  }
  return 0;
}
