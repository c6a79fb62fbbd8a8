/* opt_record.h: the reader options shared by every command that reads
 * records (info, run):
 *   --units U          read every record's values as U (g, gal, cm/s2, m/s2,
 *                      nm/s2, counts; or "file": the file's own units)
 *   --units GLOB=U     read records whose path as given matches GLOB
 *                      (fnmatch, '*' also matches '/') as U; repeatable, the
 *                      last matching rule wins, rules win over plain --units
 *   --dt S             sample interval (s) of text records without a time column
 *   --column N         1-based column of a text record to read as acceleration
 *   --component GLOB=CH  read channel CH of multi-channel files matching GLOB
 *   --accept-implausible  keep a record whose PGA is outside 1e-5..10 g
 *   --accept-vertical  run channels the file identifies as vertical
 *   --response FILE.xml  StationXML with the sensitivity of miniSEED records
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
  AQ_OPT_RECORD_COLUMN = 1002,
  AQ_OPT_RECORD_COMPONENT = 1003,
  AQ_OPT_RECORD_ACCEPT_IMPLAUSIBLE = 1004,
  AQ_OPT_RECORD_ACCEPT_VERTICAL = 1005,
  AQ_OPT_RECORD_RESPONSE = 1006
};

/* The number of entries in AQ_OPT_RECORD_LONGOPTS. */
#define AQ_OPT_RECORD_NOPTS 7
#define AQ_OPT_RECORD_LONGOPTS                                                 \
  {"units", required_argument, NULL, AQ_OPT_RECORD_UNITS},                     \
      {"dt", required_argument, NULL, AQ_OPT_RECORD_DT},                       \
      {"column", required_argument, NULL, AQ_OPT_RECORD_COLUMN},               \
      {"component", required_argument, NULL, AQ_OPT_RECORD_COMPONENT},         \
      {"accept-implausible", no_argument, NULL, AQ_OPT_RECORD_ACCEPT_IMPLAUSIBLE}, \
      {"accept-vertical", no_argument, NULL, AQ_OPT_RECORD_ACCEPT_VERTICAL}, \
      {"response", required_argument, NULL, AQ_OPT_RECORD_RESPONSE}

/* The same entries as a NULL-terminated table. */
extern const struct option aq_opt_record_longopts[];

#define AQ_OPT_RECORD_USAGE                                                     \
  "  --units U       values of records that state no units are U: g, g/10,\n"  \
  "                  gal, cm/s2, mm/s2, m/s2, nm/s2 or counts (divided by the\n" \
  "                  sensitivity the file states, e.g. SAC SCALE)\n"            \
  "  --units GLOB=U  records whose path matches GLOB are read as U, even over\n" \
  "                  units the file states (reported), e.g. '*.SAC=counts'\n"  \
  "                  (repeatable; the last matching rule wins)\n"              \
  "  --dt S          sample interval (s) of text records without time column\n"  \
  "  --column N      column N (1-based) of a text record is the acceleration\n" \
  "  --component GLOB=CH  channel CH of multi-channel files matching GLOB\n"   \
  "                  (or name one record as FILE#CH)\n"                       \
  "  --accept-implausible  keep records whose PGA is outside 1e-5..10 g\n"     \
  "  --accept-vertical  run channels the file identifies as vertical\n"      \
  "  --response FILE.xml  StationXML giving the sensitivity of miniSEED\n"    \
  "                  records (a StationXML given as a RECORD does the same)\n"

/* --units U or GLOB=U, --component GLOB=CH, --response FILE.xml: check
 * arg and store it in ro (a bad one: one line on stderr, *nerr += 1). */
void aq_opt_units(const char *arg, aq_read_opts *ro, int *nerr);
void aq_opt_component(const char *arg, aq_read_opts *ro, int *nerr);
void aq_opt_response(const char *arg, aq_read_opts *ro, int *nerr);

/* Handle option id with argument arg: returns 1 if id is a reader option
 * (a bad value is reported on stderr as one line and counted in *nerr; ro
 * is left unchanged then), 0 if id is not one of them. */
int aq_opt_record_handle(int id, const char *arg, aq_read_opts *ro, int *nerr);

#endif
