/* h5_select.h: the file of `archquake select -o FILE.h5` (layout:
 * docs/hdf5-layout.md, "Select files"): the root (kind "select") and a
 * group /select with the target, the grid, the suite (its records, scales,
 * misfits, events and unscaled spectra), the checks and the pool's spectra;
 * written under a temporary name and renamed onto the target once
 * complete.  Read back for `plot spectrum` and `report`.  Reports through
 * aq_error, never prints; the caller keeps what it passes. */
#ifndef AQ_REPORT_H5_SELECT_H
#define AQ_REPORT_H5_SELECT_H

#include <stddef.h>

#include "../error.h"
#include "../select/choose.h"
#include "../signal/signal.h"

typedef struct {
  const aq_select_input *input;   /* the usable pool and what was asked */
  const aq_selection *sel;        /* what was chosen */
  const char *const *record;      /* input->nrec: each pool member's name */
  const char *const *channel;     /* its channel (or a pair's rule) */
  const char *const *event;       /* its event as the file states it */
  const char *const *comments;    /* the suite file's comment lines */
  size_t ncomments;
  const char *version, *build, *command_line, *created; /* the root's */
  const aq_signal_opts *proc;     /* processing of the pool */
  const char *peaks;              /* the spectra's peak convention */
  const char *pair_rule;          /* a pair's spectrum */
} aq_h5_select;

aq_status aq_h5_select_write(const char *target, const aq_h5_select *s, aq_error *err);

/* A select file read back (all arrays malloc'd; aq_h5_select_file_free). */
typedef struct {
  char target[256];          /* the SPEC */
  char description[512];     /* the target in words */
  char code[16];             /* ec8, asce7, none */
  char peaks[16];
  double damping, band, factor, misfit;
  double target0_g;          /* the zero-period rule's a_g S, g (0: none) */
  int conditions_hold;
  size_t nper;
  double *period_s, *target_g;  /* nper */
  size_t n;                  /* records of the suite */
  char **record, **channel, **event; /* n */
  double *scale, *misfit_one;   /* n */
  double *psa_g;             /* n x nper, unscaled */
  size_t nchecks;
  char **check_name, **check_detail;
  int *check_holds;
  char *comments;            /* the suite file's comment lines, one per line */
} aq_h5_select_file;

/* Read the select file at path.  AQ_EIO (cannot be opened), AQ_EFORMAT (no
 * /select group: err names the file), AQ_ENOMEM. */
aq_status aq_h5_select_read(const char *path, aq_h5_select_file *f, aq_error *err);
void aq_h5_select_file_free(aq_h5_select_file *f);

/* 1 if path is an HDF5 file with a /select group (0 otherwise, silently). */
int aq_h5_is_select(const char *path);

#endif
