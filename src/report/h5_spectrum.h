/* h5_spectrum.h: the spectra of `archquake spectrum -o FILE.h5` (layout:
 * docs/hdf5-layout.md, "Spectrum files"): one compound table /spectra, a
 * row per (record, component, damping, period), written into a file opened
 * by aq_h5_open (root written with kind "spectrum") before aq_h5_finish,
 * which renames it onto the target, so the file appears complete or not at
 * all; and read back for `plot spectrum`.  Reports through aq_error, never
 * prints; the caller keeps ownership of what it passes. */
#ifndef AQ_REPORT_H5_SPECTRUM_H
#define AQ_REPORT_H5_SPECTRUM_H

#include <stddef.h>

#include "../error.h"
#include "../signal/spectrum.h"
#include "h5.h"

/* One spectral ordinate. */
typedef struct {
  const char *record;    /* as given: the file, or the --components argument */
  const char *component; /* the record's channel, or RotD50, RotD100, GeoMean */
  double damping;        /* ratio */
  double period_s;       /* s */
  double psa_g;          /* pseudo-spectral acceleration, g */
  double sd_m;           /* spectral displacement PSA / omega^2, m */
  double psv_m_s;        /* pseudo-velocity PSA / omega, m/s */
} aq_spectrum_row;

typedef struct {
  const aq_spectrum_row *row;
  size_t n;
  aq_spectrum_peaks peaks; /* where the peaks were taken (--peaks) */
  size_t n_angles;       /* RotD's angles over [0, 180) deg */
} aq_h5_spectra;

/* Write /spectra (its attributes: peaks "peer", "exact" or "samples",
 * peaks_text the rule in words, rotd_angles; a units_FIELD attribute per
 * column). */
aq_status aq_h5_write_spectra(aq_h5_writer *w, const char *target,
                              const aq_h5_spectra *s, aq_error *err);

/* The spectra read back: n rows, the strings copied. */
typedef struct {
  size_t n;
  char **record;    /* whole, as written */
  char **component;
  double *damping, *period_s, *psa_g, *sd_m, *psv_m_s;
  int peaks; /* an aq_spectrum_peaks (a file before --peaks: "continuous",
                EXACT), or -1: not stated */
} aq_h5_spectra_table;

/* Read /spectra of the file at path into *t (free with
 * aq_h5_spectra_table_free).  A file without it (not written by
 * `archquake spectrum`) is AQ_EFORMAT naming the file; AQ_EIO when it
 * cannot be opened. */
aq_status aq_h5_spectra_read(const char *path, aq_h5_spectra_table *t, aq_error *err);
void aq_h5_spectra_table_free(aq_h5_spectra_table *t);

#endif
