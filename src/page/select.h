/* select.h: the report's section of a suite chosen by `archquake select`
 * (src/page/select.c): the target in words, the suite's spectra against it
 * (the figure of plot spectrum), the code's checks and whether each holds,
 * the suite's records with their scales, misfits and events, and how the
 * suite was found (the suite file's comment lines). */
#ifndef AQ_PAGE_SELECT_H
#define AQ_PAGE_SELECT_H

#include <stddef.h>

#include "../error.h"
#include "buf.h"

/* Append the section of select file path (the index-th extra input) to b;
 * its figure is drawn at tmp as figure number ++*nfig.  Returns AQ_OK, or
 * the file's failure to read (err names it). */
aq_status aq_page_select_section(aq_page_buf *b, const char *path, size_t index,
                                 const char *tmp, int *nfig, aq_error *err);

#endif
