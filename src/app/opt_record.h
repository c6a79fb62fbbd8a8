/* opt_record.h: the reader options shared by every command that reads
 * records (info, run):
 *   --units U          read every record's values as U (g, gal, cm/s2, m/s2,
 *                      nm/s2, counts; or "file": the file's own units)
 *   --units GLOB=U     read records whose path as given matches GLOB
 *                      (fnmatch, '*' also matches '/') as U; repeatable, the
 *                      last matching rule wins, rules win over plain --units
 *   --dt S             sample interval (s) of text records without a time column
 *   --column N         1-based column of a text record to read as acceleration
 * A command puts AQ_OPT_RECORD_LONGOPTS into its getopt_long table, passes
 * every option id to aq_opt_record_handle(), and appends AQ_OPT_RECORD_USAGE
 * to its usage text.  The options fill an aq_read_opts (no heap memory).
 */
#ifndef AQ_APP_OPT_RECORD_H
#define AQ_APP_OPT_RECORD_H

#include <getopt.h>

#include "../io/record.h"

/* Option ids (the range 1000-1099 belongs to the reader options). */
enum {
  AQ_OPT_RECORD_UNITS = 1000,
  AQ_OPT_RECORD_DT = 1001,
  AQ_OPT_RECORD_COLUMN = 1002
};

#define AQ_OPT_RECORD_LONGOPTS                                  \
  {"units", required_argument, NULL, AQ_OPT_RECORD_UNITS},      \
      {"dt", required_argument, NULL, AQ_OPT_RECORD_DT},        \
      {"column", required_argument, NULL, AQ_OPT_RECORD_COLUMN}

/* The same entries as a NULL-terminated table. */
extern const struct option aq_opt_record_longopts[];

#define AQ_OPT_RECORD_USAGE                                                     \
  "  --units U       read the records' values as U: g, gal, cm/s2, m/s2,\n"    \
  "                  nm/s2 or counts (SAC: divided by SCALE, counts per m/s2)\n" \
  "  --units GLOB=U  the same for records whose path matches GLOB, e.g.\n"      \
  "                  --units '*.SAC=counts' (repeatable; the last matching\n"   \
  "                  rule wins, and rules win over --units U)\n"                \
  "  --dt S          sample interval (s) of text records without time column\n"  \
  "  --column N      column N (1-based) of a text record is the acceleration\n"

/* Handle option id with argument arg: returns 1 if id is a reader option
 * (a bad value is reported on stderr as one line and counted in *nerr; ro
 * is left unchanged then), 0 if id is not one of them. */
int aq_opt_record_handle(int id, const char *arg, aq_read_opts *ro, int *nerr);

#endif
