/* labels.h: what labels.c shares with the rest of src/plot (internal): the
 * size of the cairo drivers' text against PLplot's character height, and
 * a string's count of UTF-8 characters. */
#ifndef AQ_PLOT_LABELS_H
#define AQ_PLOT_LABELS_H

#include <stddef.h>

/* The cairo drivers draw text at a font size of 1.33 times PLplot's
 * character height (measured: 1.336 in a PDF through pdftotext's boxes,
 * 1.325 in an SVG's font-size); a line of text is the font's ascent and
 * descent, 1.164 em (2384/2048). */
static const double FONT_PER_HEIGHT = 1.33, LINE_EM = 1.164;

/* The UTF-8 characters of s (a stray byte counts as one). */
size_t aq_plot_utf8_chars(const char *s);

#endif
