/* src/page: the HTML report of a screening, one self-contained page from
 * results files and the plot stage's figures.
 *
 * page.h: the report of a screening as one self-contained HTML page
 * (`archquake report RESULTS.h5 [CAPACITY.h5 ...] -o report.html`).
 *
 * The page holds everything inline: the figures are SVG drawn by the plot
 * stage (src/plot, text kept as text), the style sheet and a small script
 * (sorting and filtering the verdict tables) are in the page, nothing is
 * fetched, and the page reads whole without the script and prints on A4
 * or Letter.  What it shows comes from the results file and the capacity
 * files: the run (command line, build, date, processing options, every
 * record and every arch), per arch its verdict table and figures (the arch
 * and its hinge sets, the suite's verdict map, the history of each
 * collapsed run and of the strongest surviving one when stored), the
 * capacity results (first collapse scales and intervals, the fragility
 * curves, the ranking of the intensity measures) and the failed records.
 *
 *   read.c    the results and capacity files as the page needs them: every
 *             root attribute, the /records table and the /arches groups as
 *             text, the runs (aq_h5_read_suite) and the capacity tables;
 *             each file's kind checked first (aq_page_file_kind)
 *   html.c    the page (its sections: html_run.c, html_arch.c,
 *             html_capacity.c, html_spectrum.c, select.c; html_int.h)
 *   figure.c  a figure of src/plot as inline SVG
 *
 * Uses PLplot (global state) and HDF5: call from one thread.  Nothing here
 * prints: failures fill aq_error.  The page is written to a temporary
 * beside the target and renamed onto it when complete; on failure no file
 * is left under the target's name. */
#ifndef AQ_PAGE_PAGE_H
#define AQ_PAGE_PAGE_H

#include <stddef.h>

#include "../error.h"

/* What an HDF5 file of archquake holds. */
typedef enum {
  AQ_PAGE_RESULTS = 0, /* the main job's results (/summary with runs) */
  AQ_PAGE_CAPACITY,    /* archquake capacity -o (/capacity) */
  AQ_PAGE_SELECT,      /* archquake select -o (/select): a suite and its target */
  AQ_PAGE_SPECTRUM,    /* archquake spectrum -o (/spectra) */
} aq_page_kind;

/* The kind of file at path, or an error naming the file and what it is
 * instead: not HDF5, HDF5 but not archquake's (no format_version), a
 * format_version this build cannot read (it names the versions it reads). */
aq_status aq_page_file_kind(const char *path, aq_page_kind *kind, aq_error *err);

/* The files of a page, each reported in a section of its kind: at most one
 * results file of the main job (its runs, arches and records; NULL: none),
 * and any capacity, select and spectrum files.  The run's section shows the
 * results file's command, options and records, or without one the first
 * other file's. */
typedef struct {
  const char *results;         /* the main job's results file, or NULL */
  const char *const *capacity; /* capacity, select and spectrum files (may be none) */
  size_t ncapacity;
  const char *command_line;    /* this report's command, shown at the end */
  const char *build;           /* this program's version and build */
} aq_page_input;

/* What the page took. */
typedef struct {
  size_t bytes;    /* the page's size */
  size_t figures;  /* inline SVG figures */
  size_t runs;     /* rows of the verdict tables */
  double build_s;  /* wall time, s */
} aq_page_stats;

/* Write the page to target.  Errors: an input of another kind than its
 * place (a results file among the others) or unreadable (AQ_EFORMAT,
 * naming the file), no file at all (AQ_EVALUE), the page cannot be
 * written (AQ_EIO).  stats may be NULL. */
aq_status aq_page_write(const aq_page_input *in, const char *target, aq_page_stats *stats,
                        aq_error *err);

#endif
