/* range.h: the period range of a selection for an arch (src/select;
 * docs/select.md, "The period range for an arch").
 *
 * An arch has no elastic period to take 0.2 T1 to 2 T1 from.  Its range is
 * that of the spectral measure that best predicts its collapse: of the
 * arch's fits in a `capacity --fragility` file, the spectral one of lowest
 * rank (the smallest dispersion): Sa_avg over T1..T2 gives T1..T2, Sa(T)
 * gives 0.2 T to 2 T (the span EN 1998-1 3.2.3.1.2(4) puts around a
 * period).  Without a fragility file the range is 0.1 to 1 s.
 *
 * Nothing prints: errors fill the aq_error with the file, line and field. */
#ifndef AQ_SELECT_RANGE_H
#define AQ_SELECT_RANGE_H

#include <stddef.h>

#include "../error.h"

#define AQ_SELECT_T1_DEFAULT_S 0.1
#define AQ_SELECT_T2_DEFAULT_S 1.0

/* The range of the spectral measure named im ("sa_avg_0.1_1s_g",
 * "sa_0.2s_g"); 1 if it is one, else 0. */
int aq_select_range_of_im(const char *im, double *t1_s, double *t2_s);

/* The range of arch's best-ranked spectral measure in the fragility TSV at
 * path (arch NULL: the file's only arch), its name into im[nim].  Returns
 * AQ_OK; AQ_EIO; AQ_EFORMAT (not a fragility file: err names the line);
 * AQ_EVALUE (no such arch, several arches and none named, no fitted
 * spectral measure: field "--fragility" or "--fragility-arch"). */
aq_status aq_select_range_from_fragility(const char *path, const char *arch, double *t1_s,
                                         double *t2_s, char *im, size_t nim, aq_error *err);

#endif
