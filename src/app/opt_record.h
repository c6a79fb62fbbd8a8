/* opt_record.h: the reader options whose argument is more than a number
 * (their rows in opt_table.c call these; they fill an aq_read_opts, no heap
 * memory):
 *   --units U          read every record's values as U (g, gal, cm/s2, m/s2,
 *                      nm/s2, counts; or "file": the file's own units)
 *   --units GLOB=U     read records whose path as given matches GLOB
 *                      (fnmatch, '*' also matches '/') as U; repeatable, the
 *                      last matching rule wins, rules win over plain --units
 *   --component GLOB=CH  read channel CH of multi-channel files matching GLOB
 *   --response FILE.xml  StationXML with the sensitivity of miniSEED records
 */
#ifndef AQ_APP_OPT_RECORD_H
#define AQ_APP_OPT_RECORD_H

#include <stdio.h>

#include "../io/record.h"

/* --units U or GLOB=U, --component GLOB=CH, --response FILE.xml: check
 * arg and store it in ro (a bad one: one line on stderr, *nerr += 1). */
void aq_opt_units(const char *arg, aq_read_opts *ro, int *nerr);
/* Print rec's notes (aq_record_note), one line each: "archquake: PATH:
 * TOPIC: TEXT". */
void aq_record_print_notes(const aq_record *rec, FILE *f);
void aq_opt_component(const char *arg, aq_read_opts *ro, int *nerr);
void aq_opt_response(const char *arg, aq_read_opts *ro, int *nerr);

#endif
