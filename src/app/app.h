/* src/app: the command line: dispatch, one file per command, the option
 * table, the main job's scheduler and ordered writer, and archquake-mpi.
 *
 * app.h: the command-line layer.  Each subcommand parses and checks all of
 * its options before touching any input, reports every bad option on stderr
 * (one line each) and returns an exit status:
 *   0  success
 *   1  something failed (a record or a run; compare: values differ)
 *   2  usage: bad or missing options, nothing was run
 *   3  output could not be written (no partial file is left)
 * Tabular output is TSV with a header row on stdout. */
#ifndef AQ_APP_H
#define AQ_APP_H

#include <stddef.h>

#define AQ_VERSION "0.1.0"

/* The exact build: "VERSION (git describe)" as embedded by the Makefile,
 * or VERSION alone when it was built outside a git checkout. */
const char *aq_build_string(void);

/* argv joined by spaces, words with shell-special characters in single
 * quotes (malloc'd; NULL when out of memory): a results file's
 * command_line, taken before getopt_long permutes argv. */
char *aq_app_command_line(int argc, char **argv);

/* The time now, ISO-8601 UTC ("2024-05-01T12:00:00Z"; "unknown" if the
 * clock cannot say), into buf[n]: a results file's created. */
void aq_app_now_utc(char *buf, size_t n);

enum { AQ_EXIT_OK = 0, AQ_EXIT_FAIL = 1, AQ_EXIT_USAGE = 2, AQ_EXIT_OUTPUT = 3 };

/* archquake's command line (dispatch.c): the command argv[1] names in the
 * table of commands (opt_table.h), else the main job (whose options
 * include --help and --version); a word that names neither a command nor
 * a file is refused in one line listing the commands.  Returns the exit
 * status.  main (src/main.c) and archquake-mpi's main (mpi.c) call it. */
int aq_app_main(int argc, char **argv);
/* 1 if argv runs a command whose tasks archquake-mpi spreads over the
 * ranks (the table's .farmed: the main job and capacity), not its --help
 * or --version; the other commands run on rank 0 alone. */
int aq_app_farms(int argc, char **argv);

/* The allocator policy of every command (heap.c): blocks of a record's
 * size are kept in the heap between records instead of being mapped and
 * handed back to the kernel each time.  main() sets it first; the suite
 * sets it too, for library callers.  Process-wide: idempotent. */
void aq_app_heap_policy(void);

int aq_cmd_run(int argc, char **argv);       /* archquake [OPTIONS] RECORD... --arch FILE */
int aq_cmd_info(int argc, char **argv);      /* archquake info */
int aq_cmd_mechanism(int argc, char **argv); /* archquake mechanism */
int aq_cmd_pulse(int argc, char **argv);     /* archquake pulse */
int aq_cmd_domain(int argc, char **argv);    /* archquake domain */
int aq_cmd_compare(int argc, char **argv);   /* archquake compare */
int aq_cmd_plot(int argc, char **argv);      /* archquake plot */
int aq_cmd_capacity(int argc, char **argv);  /* archquake capacity */
int aq_cmd_spectrum(int argc, char **argv);  /* archquake spectrum */
int aq_cmd_select(int argc, char **argv);    /* archquake select */
int aq_cmd_report(int argc, char **argv);    /* archquake report */
int aq_cmd_help(int argc, char **argv);      /* archquake help [COMMAND] */

/* With [hinges], warn on stderr (one line naming path and both sets) when
 * the arch's minimum-lambda0 set is lower than its primary: that mechanism
 * governs unless its joints are restrained; or, above the search's voussoir
 * limit, that whether the arch stands was not checked (cmd_mechanism.c). */
struct aq_arch;
void aq_mechanism_warn_minimum(const char *path, const struct aq_arch *a);

#endif
