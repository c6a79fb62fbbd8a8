/* opt_parse.c: one parser for every command's options, and --help, both
 * from the table of opt_table.c (see opt_table.h).
 *
 * getopt_long is given every option of the table, whichever command it
 * belongs to, so that an option of another command is recognised (its
 * argument taken) and refused by name rather than reported as unknown. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "opt.h"
#include "opt_arch.h"
#include "opt_table.h"

enum {
  VAL0 = 256,      /* getopt_long's value of row i: VAL0 + i (above any letter) */
  HELP_WIDTH = 79, /* --help's lines are at most this wide */
  HELP_COL_MAX = 22 /* the help text starts at most in this column */
};

static int takes_arg(const aq_opt_row *r)
{
  return r->kind != AQ_ARG_FLAG && r->kind != AQ_ARG_FLAG_OFF;
}

/* The spelling of row r in messages: "-j" for an option with a letter (as
 * the values' messages have always named it), else "--name". */
static const char *spelling(const aq_opt_row *r, char *buf, size_t n)
{
  if (r->short_name)
    snprintf(buf, n, "-%c", r->short_name);
  else
    snprintf(buf, n, "--%s", r->name);
  return buf;
}

/* Check arg and store it where row r says. */
static void store(const aq_opt_row *r, char *arg, aq_opts *o, int *nerr)
{
  char *base = (char *)o;
  void *dst = base + r->dest;
  char name[64];
  spelling(r, name, sizeof name);
  switch (r->kind) {
  case AQ_ARG_FLAG:
    *(int *)dst = 1;
    break;
  case AQ_ARG_FLAG_OFF:
    *(int *)dst = 0;
    break;
  case AQ_ARG_DOUBLE:
    aq_opt_double(name, arg, r->lo, r->hi, dst, nerr);
    break;
  case AQ_ARG_DOUBLE_GT:
    aq_opt_double_gt(name, arg, r->lo, r->hi, dst, nerr);
    break;
  case AQ_ARG_LONG:
    aq_opt_long(name, arg, (long)r->lo, (long)r->hi, dst, nerr);
    break;
  case AQ_ARG_INT: {
    long v = *(int *)dst;
    aq_opt_long(name, arg, (long)r->lo, (long)r->hi, &v, nerr);
    *(int *)dst = (int)v;
    break;
  }
  case AQ_ARG_SIZE: {
    long v = (long)*(size_t *)dst;
    aq_opt_long(name, arg, (long)r->lo, (long)r->hi, &v, nerr);
    *(size_t *)dst = (size_t)v;
    break;
  }
  case AQ_ARG_LIST:
    aq_opt_list_range(name, arg, r->lo, r->hi, r->hi_open, dst,
                      (size_t *)(void *)(base + r->dest_n), nerr);
    break;
  case AQ_ARG_CHOICE:
    aq_opt_choice(name, arg, r->choices, dst, nerr);
    break;
  case AQ_ARG_STRING:
    *(const char **)dst = arg;
    break;
  case AQ_ARG_CUSTOM:
    break;
  }
  if (r->read_fn) /* a reading option's own handler */
    r->read_fn(arg, &o->read, nerr);
  if (r->orient_fn) /* an orientation option's */
    r->orient_fn(arg, &o->orient, nerr);
  if (r->fn) /* the handler of a custom option, or what follows a value */
    r->fn(arg, o, nerr);
}

/* "the main job, pulse, domain and capacity": the commands in mask; plot's
 * figures as "plot" when all of them are in it. */
static void command_list(unsigned mask, char *buf, size_t n)
{
  const char *names[AQ_CMD_N];
  size_t k = 0, len = 0;
  unsigned figures = 0;
  for (int c = AQ_CMD_PLOT + 1; c < AQ_CMD_N; c++)
    figures |= 1u << c;
  int all_figures = (mask & figures) == figures;
  for (int c = 0; c < AQ_CMD_N; c++) {
    if (!(mask >> c & 1u) || c == AQ_CMD_PLOT)
      continue;
    if (all_figures && (figures >> c & 1u)) {
      if (c == AQ_CMD_PLOT + 1)
        names[k++] = aq_opt_commands[AQ_CMD_PLOT].title;
      continue;
    }
    names[k++] = aq_opt_commands[c].title;
  }
  buf[0] = '\0';
  for (size_t i = 0; i < k && len < n; i++) {
    int w = snprintf(buf + len, n - len, "%s%s", i == 0 ? "" : i + 1 < k ? ", " : " and ",
                     names[i]);
    if (w > 0)
      len += (size_t)w;
  }
}

/* Option id, known to the table, does not apply to cmd: one line naming it
 * as typed (short: "-q") and the commands it belongs to. */
static void refuse(aq_cmd cmd, int id, int as_short, int *nerr)
{
  const aq_opt_row *r = &aq_opt_rows[id];
  const aq_opt_command *c = &aq_opt_commands[cmd];
  unsigned owners = 0; /* every row of this spelling */
  for (int i = 0; i < AQ_OPT_N; i++)
    if (as_short ? aq_opt_rows[i].short_name == r->short_name
                 : strcmp(aq_opt_rows[i].name, r->name) == 0)
      owners |= aq_opt_rows[i].cmds;
  char list[256], typed[64];
  command_list(owners, list, sizeof list);
  if (as_short)
    snprintf(typed, sizeof typed, "-%c", r->short_name);
  else
    snprintf(typed, sizeof typed, "--%s", r->name);
  int figure = AQ_CMD_IS_FIGURE(cmd);
  fprintf(stderr, "archquake: %s%s%s: not an option of this %s (only of %s)\n", c->name,
          c->name[0] ? ": " : "", typed, figure ? "figure" : "command", list);
  (*nerr)++;
}

/* 1 if row r's value in o asks for nothing (its .zero_is_off, at 0). */
static int off(const aq_opt_row *r, const aq_opts *o)
{
  const char *base = (const char *)o;
  return r->zero_is_off && (r->kind == AQ_ARG_DOUBLE || r->kind == AQ_ARG_DOUBLE_GT) &&
         *(const double *)(const void *)(base + r->dest) == 0;
}

/* Row r, given to cmd: its rules with the other options cmd takes (see
 * aq_opt_row), one line for each that is broken. */
static void rules(aq_cmd cmd, const aq_opt_row *r, const aq_opts *o, int *nerr)
{
  const char *base = (const char *)o;
  char me[64], other[64], why[256] = "";
  spelling(r, me, sizeof me);
  if (r->why)
    snprintf(why, sizeof why, " (%s)", r->why);
  const int *const lists[] = {r->requires, r->conflicts, r->not_below, r->not_above};
  for (int kind = 0; kind < 4; kind++)
    for (const int *j = lists[kind]; j && *j >= 0; j++) {
      const aq_opt_row *q = &aq_opt_rows[*j];
      if (!aq_opt_applies((aq_opt_id)*j, cmd))
        continue;
      spelling(q, other, sizeof other);
      if (kind == 0 && !o->given[*j])
        fprintf(stderr, "archquake: %s: expected %s as well%s\n", me, other, why);
      else if (kind == 1 && o->given[*j] && !off(r, o) && !off(q, o))
        fprintf(stderr, "archquake: %s: expected no %s with it%s, got both\n", me, other,
                why);
      else if (kind >= 2) {
        double mine = *(const double *)(const void *)(base + r->dest);
        double bound = *(const double *)(const void *)(base + q->dest);
        if (isnan(mine) || isnan(bound) || (kind == 2 ? mine >= bound : mine <= bound))
          continue;
        fprintf(stderr, "archquake: %s: expected a value %s %s (%g), got %g\n", me,
                kind == 2 ? ">=" : "<=", other, bound, mine);
      } else
        continue;
      (*nerr)++;
    }
}

int aq_opts_parse(aq_cmd cmd, int argc, char **argv, aq_opts *o, int *nerr)
{
  /* one getopt entry per name and per letter: the row that applies to
   * cmd if there is one, else the first */
  struct option lo[AQ_OPT_N + 1];
  int by_letter[128];
  char shorts[2 + 2 * AQ_OPT_N] = ":";
  size_t n = 0, ns = 1;
  for (int i = 0; i < 128; i++)
    by_letter[i] = -1;
  for (int i = 0; i < AQ_OPT_N; i++) {
    const aq_opt_row *r = &aq_opt_rows[i];
    int mine = aq_opt_applies((aq_opt_id)i, cmd);
    size_t k = 0;
    while (k < n && strcmp(lo[k].name, r->name) != 0)
      k++;
    if (k == n || (mine && !aq_opt_applies((aq_opt_id)(lo[k].val - VAL0), cmd))) {
      lo[k] = (struct option){r->name, takes_arg(r) ? required_argument : no_argument, NULL,
                              VAL0 + i};
      n += k == n;
    }
    unsigned char ch = (unsigned char)r->short_name;
    if (ch && ch < 128 && (by_letter[ch] < 0 || (mine && !aq_opt_applies(
                                                            (aq_opt_id)by_letter[ch], cmd))))
      by_letter[ch] = i;
  }
  lo[n] = (struct option){NULL, 0, NULL, 0};
  for (int ch = 1; ch < 128; ch++)
    if (by_letter[ch] >= 0) {
      shorts[ns++] = (char)ch;
      if (takes_arg(&aq_opt_rows[by_letter[ch]]))
        shorts[ns++] = ':';
    }
  shorts[ns] = '\0';

  const char *help_name = aq_opt_commands[cmd].help_cmd;
  int c;
  opterr = 0;
  optind = 0; /* glibc: start afresh, whatever a previous parse left */
  while ((c = getopt_long(argc, argv, shorts, lo, NULL)) != -1) {
    int as_short = c > 0 && c < 128 && c != '?' && c != ':';
    int id = as_short ? by_letter[c] : c >= VAL0 ? c - VAL0 : -1;
    if (id < 0) { /* unknown, or a value missing */
      aq_opt_unknown(help_name, argv, optind, optopt, nerr);
      continue;
    }
    if (!aq_opt_applies((aq_opt_id)id, cmd)) {
      if (!aq_opt_dash_file(help_name, argv, optind, c, nerr))
        refuse(cmd, id, as_short, nerr);
      continue;
    }
    if (id == AQ_OPT_HELP) { /* the main job's is archquake --help */
      if (cmd == AQ_CMD_RUN)
        aq_opts_main_help(stdout);
      else
        aq_opts_help(cmd, stdout);
      return 1;
    }
    if (id == AQ_OPT_VERSION) {
      printf("archquake %s\n", AQ_VERSION);
      return 1;
    }
    if (o->given[id] < UINT8_MAX)
      o->given[id]++;
    store(&aq_opt_rows[id], optarg, o, nerr);
  }
  /* the main job: a word naming a command, and no file, is a command word
   * put after options (archquake --no-cache mechanism ...): refused, not
   * read as a record (README, "Commands") */
  for (int i = optind; cmd == AQ_CMD_RUN && i < argc; i++) {
    const aq_opt_command *w = aq_opt_command_named(argv[i]);
    if (w && access(argv[i], F_OK) != 0) {
      fprintf(stderr, "archquake: %s: expected a RECORD, got a command word after options: "
                      "write the command first (archquake %s [OPTIONS] ...), or a record of "
                      "that name as ./%s\n", argv[i], w->name, argv[i]);
      (*nerr)++;
      break;
    }
  }
  o->operands = argv + optind;
  o->noperands = argc - optind;
  /* what the table says of cmd's options together */
  const aq_opt_command *k = &aq_opt_commands[cmd];
  for (int i = 0; i < AQ_OPT_N; i++) {
    const aq_opt_row *r = &aq_opt_rows[i];
    if (!aq_opt_applies((aq_opt_id)i, cmd))
      continue;
    if ((r->required >> cmd & 1u) && !o->given[i]) {
      char name[64];
      fprintf(stderr, "archquake: %s%sexpected %s%s%s, got none\n", k->name,
              k->name[0] ? ": " : "", spelling(r, name, sizeof name), r->meta ? " " : "",
              r->meta ? r->meta : "");
      (*nerr)++;
    }
    if (o->given[i])
      rules(cmd, r, o, nerr);
    if (r->check)
      r->check(o, nerr);
  }
  return 0;
}

/* "  -o, --output FILE.h5": an option's label in --help. */
static int label(const aq_opt_row *r, const char *meta, char *buf, size_t n)
{
  char s[8] = "";
  if (r->short_name)
    snprintf(s, sizeof s, "-%c, ", r->short_name);
  int w = snprintf(buf, n, "  %s--%s%s%s", s, r->name, meta ? " " : "", meta ? meta : "");
  return w < 0 ? 0 : w;
}

/* label, then text from column col, its words wrapped at HELP_WIDTH (two
 * spaces after a sentence are kept within a line). */
void aq_opt_help_entry(FILE *f, const char *lab, const char *text, const char *note, int col)
{
  int at = fprintf(f, "%s", lab);
  if (at + 2 > col) {
    fputs("  ", f);
    at += 2;
  } else {
    for (; at < col; at++)
      fputc(' ', f);
  }
  int line_start = 1;
  for (int part = 0; part < 2; part++) {
    const char *p = part ? note : text;
    if (!p)
      continue;
    while (*p) {
      int gap = 0;
      while (*p == ' ') {
        gap++;
        p++;
      }
      size_t len = strcspn(p, " ");
      if (!len)
        break;
      if (part && line_start == 0 && gap == 0)
        gap = 1; /* between text and note */
      if (!line_start && at + (gap > 1 ? 2 : 1) + (int)len > HELP_WIDTH) {
        fputc('\n', f);
        for (at = 0; at < col; at++)
          fputc(' ', f);
        line_start = 1;
      }
      if (!line_start) {
        fputs(gap > 1 ? "  " : " ", f);
        at += gap > 1 ? 2 : 1;
      }
      fwrite(p, 1, len, f);
      at += (int)len;
      p += len;
      line_start = 0;
    }
  }
  fputc('\n', f);
}

void aq_opts_help(aq_cmd cmd, FILE *f)
{
  unsigned figures = 0;
  for (int c = AQ_CMD_PLOT + 1; c < AQ_CMD_N; c++)
    figures |= 1u << c;
  if (figures >> cmd & 1u) /* a figure's help is plot's */
    cmd = AQ_CMD_PLOT;
  unsigned mask = cmd == AQ_CMD_PLOT ? figures : 1u << cmd;
  const aq_opt_command *c = &aq_opt_commands[cmd];
  static const char *const headings[AQ_GROUP_N] = {NULL, "Reading:", "Orientation:",
                                                   "Processing:"};
  char lab[128];
  int col = 0;
  for (int i = 0; i < AQ_OPT_N; i++)
    if (aq_opt_rows[i].cmds & mask) {
      int w = label(&aq_opt_rows[i], aq_opt_rows[i].meta, lab, sizeof lab) + 2;
      col = w > col ? w : col;
    }
  col = col < HELP_COL_MAX ? col : HELP_COL_MAX;
  fputs(c->head, f);
  for (int g = 0; g < AQ_GROUP_N; g++) {
    int first = 1;
    for (int i = 0; i < AQ_OPT_N; i++) {
      const aq_opt_row *r = &aq_opt_rows[i];
      if (!(r->cmds & mask) || r->group != (aq_opt_group)g)
        continue;
      if (first) {
        const char *h = c->heading[g] ? c->heading[g] : headings[g];
        if (h)
          fprintf(f, "%s\n", h);
        first = 0;
      }
      /* plot: the figures an option is for, unless all */
      char note[160] = "";
      if (cmd == AQ_CMD_PLOT && (r->cmds & figures) != figures) {
        int nfig = 0;
        size_t k = 0;
        for (int x = AQ_CMD_PLOT + 1; x < AQ_CMD_N; x++)
          nfig += (int)(r->cmds >> x & 1u);
        for (int x = AQ_CMD_PLOT + 1; x < AQ_CMD_N; x++)
          if (r->cmds >> x & 1u) {
            int w = snprintf(note + k, sizeof note - k, "%s%s",
                             k ? ", " : nfig > 1 ? "(figures " : "(figure ",
                             aq_opt_commands[x].name + strlen("plot "));
            k += w > 0 ? (size_t)w : 0;
          }
        snprintf(note + k, sizeof note - k, ")");
      }
      label(r, r->meta, lab, sizeof lab);
      aq_opt_help_entry(f, lab, r->help, note[0] ? note : NULL, col);
      if (r->meta2) {
        label(r, r->meta2, lab, sizeof lab);
        aq_opt_help_entry(f, lab, r->help2, NULL, col);
      }
    }
  }
  fputs(c->tail, f);
}

void aq_opts_main_help(FILE *f)
{
  enum { SYNOPSIS_COL = 46 }; /* where the summaries start */
  aq_opts_help(AQ_CMD_RUN, f);
  fputs("Commands (each has --help; 'archquake help COMMAND' too):\n", f);
  char lab[160];
  for (int c = 0; c < AQ_CMD_N; c++) {
    const aq_opt_command *k = &aq_opt_commands[c];
    if (!k->summary)
      continue;
    snprintf(lab, sizeof lab, "  archquake %s", k->synopsis);
    aq_opt_help_entry(f, lab, k->summary, NULL, SYNOPSIS_COL);
  }
  aq_opt_arch_usage(f);
  const aq_opt_note *const notes[] = {aq_opt_environment, aq_opt_files};
  const char *const titles[] = {"Environment:", "Files:"};
  for (int t = 0; t < 2; t++) {
    fprintf(f, "%s\n", titles[t]);
    for (const aq_opt_note *e = notes[t]; e->name; e++) {
      snprintf(lab, sizeof lab, "  %s", e->name);
      aq_opt_help_entry(f, lab, e->help, NULL, HELP_COL_MAX);
    }
  }
}

int aq_opt_is(aq_opt_id id, const char *word)
{
  if ((unsigned)id >= AQ_OPT_N || !word || word[0] != '-')
    return 0;
  const aq_opt_row *r = &aq_opt_rows[id];
  if (word[1] == '-')
    return strcmp(word + 2, r->name) == 0;
  return r->short_name && word[1] == r->short_name && word[2] == '\0';
}

const aq_opt_command *aq_opt_command_named(const char *word)
{
  for (int c = 0; word && c < AQ_CMD_N; c++) {
    const aq_opt_command *k = &aq_opt_commands[c];
    if (!AQ_CMD_IS_FIGURE(c) && k->name[0] && strcmp(k->name, word) == 0)
      return k;
  }
  return NULL;
}

void aq_opt_command_names(char *buf, size_t n)
{
  size_t len = 0;
  buf[0] = '\0';
  for (int c = 0; c < AQ_CMD_N && len < n; c++) {
    const aq_opt_command *k = &aq_opt_commands[c];
    if (AQ_CMD_IS_FIGURE(c) || !k->name[0])
      continue;
    int w = snprintf(buf + len, n - len, "%s%s", len ? ", " : "", k->name);
    len += w > 0 ? (size_t)w : 0;
  }
}

int aq_opts_figure(const char *word)
{
  const char *prefix = aq_opt_commands[AQ_CMD_PLOT].name; /* "plot" */
  size_t np = strlen(prefix);
  const char *names[AQ_CMD_N + 1];
  int n = 0, out = -1, nerr = 0;
  for (int c = AQ_CMD_PLOT + 1; c < AQ_CMD_N; c++) /* "plot NAME": NAME */
    names[n++] = aq_opt_commands[c].name + np + 1;
  names[n] = NULL;
  aq_opt_choice(prefix, word, names, &out, &nerr);
  return nerr ? -1 : AQ_CMD_PLOT + 1 + out;
}
