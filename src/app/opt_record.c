/* opt_record.c: the reader options (see opt_record.h). */
#define _POSIX_C_SOURCE 200809L
#include "opt_record.h"

#include <stdio.h>
#include <string.h>

#include "opt.h"

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

/* A GLOB=VALUE rule a for option opt (value of 1 to vmax - 1 characters,
 * at most AQ_UNITS_RULES_MAX rules, nrules so far): copies GLOB into glob and
 * returns VALUE, or reports one line, counts it in *nerr and returns NULL. */
static const char *glob_rule(const char *opt, const char *a, const char *what,
                             size_t vmax, size_t nrules, char *glob, int *nerr)
{
  const char *eq = strrchr(a, '=');
  size_t gl = eq ? (size_t)(eq - a) : 0;
  if (!eq || gl == 0 || gl >= AQ_UNITS_GLOB_MAX || !eq[1] || strlen(eq + 1) >= vmax) {
    fprintf(stderr,
            "archquake: %s: expected GLOB=%s (a pattern of 1 to %d characters, "
            "a value of 1 to %zu), got \"%s\"\n",
            opt, what, AQ_UNITS_GLOB_MAX - 1, vmax - 1, a);
    (*nerr)++;
    return NULL;
  }
  if (nrules >= AQ_UNITS_RULES_MAX) {
    fprintf(stderr, "archquake: %s: expected at most %d GLOB=%s rules, got more (\"%s\")\n",
            opt, AQ_UNITS_RULES_MAX, what, a);
    (*nerr)++;
    return NULL;
  }
  memcpy(glob, a, gl);
  glob[gl] = '\0';
  return eq + 1;
}

void aq_opt_units(const char *arg, aq_read_opts *ro, int *nerr)
{
  const char *a = arg ? arg : "", *v;
  aq_units u;
  if (!strchr(a, '=')) {
    parse_units("--units", a, &ro->units, nerr);
    return;
  }
  aq_units_rule *r = &ro->rules[ro->nrules < AQ_UNITS_RULES_MAX ? ro->nrules : 0];
  char glob[AQ_UNITS_GLOB_MAX];
  if ((v = glob_rule("--units", a, "U", 32, ro->nrules, glob, nerr)) &&
      parse_units("--units", v, &u, nerr)) {
    memcpy(r->glob, glob, sizeof glob);
    r->units = u;
    ro->nrules++;
  }
}

void aq_opt_component(const char *arg, aq_read_opts *ro, int *nerr)
{
  const char *a = arg ? arg : "", *v;
  char glob[AQ_UNITS_GLOB_MAX];
  size_t cap = sizeof ro->components[0].channel;
  if ((v = glob_rule("--component", a, "CHANNEL", cap, ro->ncomponents, glob, nerr))) {
    memcpy(ro->components[ro->ncomponents].glob, glob, sizeof glob);
    snprintf(ro->components[ro->ncomponents].channel, cap, "%s", v);
    ro->ncomponents++;
  }
}

void aq_opt_response(const char *arg, aq_read_opts *ro, int *nerr)
{
  if (!arg || !arg[0] || ro->nresponses >= AQ_RESPONSES_MAX) {
    fprintf(stderr, "archquake: --response: expected a StationXML file name (at most %d "
                    "of them), got \"%s\"\n",
            AQ_RESPONSES_MAX, arg ? arg : "");
    (*nerr)++;
    return;
  }
  ro->responses[ro->nresponses++] = arg; /* argv's string: lives as long as the command */
}

void aq_record_print_notes(const aq_record *rec, FILE *f)
{
  const char *topic, *text;
  for (size_t i = 0; (text = aq_record_note(rec, i, &topic)) != NULL; i++)
    fprintf(f, "archquake: %s: %s: %s\n", rec->path, topic, text);
}
