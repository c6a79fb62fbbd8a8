/* src/capacity: the scale factors at which an arch's verdict changes under
 * a record, and fragility fits of them.
 *
 * capacity.h: collapse capacity of an arch under a record scaled by a
 * factor (src/capacity), and lognormal fragility fits of the first-collapse
 * intensities.
 *
 * scan.c: every scale factor in (scale_lo, scale_hi] at which a verdict
 *   (collapse or not) changes, by a geometric scan of ratio 1 + resolution
 *   and a bisection of every change to a relative tolerance (the "fill" of
 *   Vamvatsikos & Cornell's hunt-and-fill, Earthquake Engng Struct. Dyn.
 *   31(3), 2002, with the hunt replaced by a scan that finds every window
 *   wider than the resolution: docs/capacity.md states the guarantee).  The
 *   verdict comes from a callback, so the scan knows no physics.
 * capacity.c: the verdict of one (subject at an azimuth, arch, polarity)
 *   at a scale (one run, job/run.h, on the subject's view), the exact scale
 *   at which the arch first moves (with a vertical too), the worst of a scan
 *   over azimuths, and many such jobs on threads (util/pool.h).
 * fragility.c: lognormal fit by maximum likelihood with right-censoring
 *   (Baker 2015, Earthquake Spectra 31(1), eq. 7, with the censored terms
 *   of his eq. 11 form) and a profile-likelihood confidence interval of the
 *   median.
 *
 * Scales are dimensionless factors on the processed record; intensities
 * are SI (m/s, m, m/s^2) except where named _g.  Results own their
 * interval and point arrays (aq_scan_result_free, aq_capacity_free;
 * NULL-safe): an aq_capacity holds every scale the scan ran, with the
 * run's peak rotation and verdict (aq_capacity_point).
 * Nothing here prints: errors fill an aq_error.
 */
#ifndef AQ_CAPACITY_H
#define AQ_CAPACITY_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../arch/stepper.h"
#include "../error.h"
#include "../job/job.h"
#include "../signal/signal.h"
#include "../util/bytes.h"

/* ---- scan.c ------------------------------------------------------------ */

/* Ranges accepted for the options (relative, dimensionless). */
#define AQ_SCAN_RESOLUTION_MIN 1e-4 /* finer: > 10^5 runs per decade */
#define AQ_SCAN_RESOLUTION_MAX 1.0  /* coarser: a factor of 2 between runs */
#define AQ_SCAN_TOL_MIN 1e-12       /* a few thousand ulps of a scale */
#define AQ_SCAN_RESOLUTION_DEFAULT 0.01
#define AQ_SCAN_TOL_DEFAULT 1e-6

typedef struct {
  double resolution; /* grid ratio 1 + resolution between runs */
  double tol;        /* bisect each change until hi - lo <= tol * lo (tol <= resolution) */
} aq_scan_opts;

/* The verdict at scale: *collapsed = 1 or 0.  A status other than AQ_OK
 * (err filled) stops the scan. */
typedef aq_status (*aq_scan_verdict_fn)(void *ctx, double scale,
                                        int *collapsed, aq_error *err);

/* One interval of collapse: collapse was observed at lo and at hi (both
 * within tol of a change of verdict, lo <= hi); hi = INFINITY when collapse
 * holds at scale_hi. */
typedef struct {
  double lo, hi;
} aq_scan_interval;

typedef struct {
  size_t ninterval;
  aq_scan_interval *interval; /* malloc'd, increasing; NULL when none */
  size_t runs;                /* verdicts asked: grid_runs + bisect_runs */
  size_t grid_runs;
  size_t bisect_runs;
} aq_scan_result;

/* Check opts: returns AQ_OK, or AQ_EOPTION with err naming the field
 * ("resolution" or "tol") and the range expected. */
aq_status aq_scan_check(const aq_scan_opts *o, aq_error *err);

/* Scan (scale_lo, scale_hi]: the verdict at scale_lo is taken to be
 * survival without a run (the arch does not move there).  Grid points
 * scale_lo (1 + resolution)^i, i >= 1, then scale_hi; each change of
 * verdict between neighbours is bisected (geometric mean) to tol.  Nothing
 * is run when scale_hi <= scale_lo.  *out is overwritten (free with
 * aq_scan_result_free, also after a failure). */
aq_status aq_scan_run(double scale_lo, double scale_hi, const aq_scan_opts *o,
                      aq_scan_verdict_fn verdict, void *ctx,
                      aq_scan_result *out, aq_error *err);
void aq_scan_result_free(aq_scan_result *r);

/* ---- capacity.c ---------------------------------------------------------- */

/* Default cap: the scale at which the record's PGA reaches this many lambda0 g. */
#define AQ_CAPACITY_CAP_LAMBDA0 20.0

/* One (subject, azimuth, polarity, arch) to analyse.  The pointers are
 * borrowed. */
typedef struct {
  const aq_view *view;   /* the subject at the azimuth, factor 1 (job/subject.h):
                            every run of the scan gives its factor to the
                            stepper (merged steps, --merge-tol, are made per run) */
  int reversed;          /* the polarity: every factor negated (the vertical
                            keeps its sign) */
  const aq_arch *arch;
  aq_model model;
  double cor;            /* kinetic-energy ratio at impact, or NAN: the arch's own */
  double merge_tol_mps2; /* as aq_steps_from_samples (0: one step per sample) */
  double scale_max;      /* cap, or NAN: AQ_CAPACITY_CAP_LAMBDA0 lambda0 g / PGA */
  aq_scan_opts scan;
  double blocks_dt_s;    /* model AQ_MODEL_BLOCKS: its step, s */
} aq_capacity_job;

typedef enum {
  AQ_CAPACITY_OK = 0,      /* scanned */
  AQ_CAPACITY_NEVER_MOVES, /* the arch does not move at any scale up to the cap */
  AQ_CAPACITY_FAILED       /* a run failed (err) */
} aq_capacity_status;

/* One run of the scan: a scale the search evaluated and what the run gave.
 * Plain data (no pointers), so a result's points can be sent as bytes. */
typedef struct {
  double scale;                 /* factor on the processed record */
  double peak_rotation_rad;     /* the run's max |q|, rad */
  double peak_rotation_over_qc; /* peak over q_c of the set it peaked in (0: never moved) */
  double collapse_time_s;       /* s in record time; NAN if it survived */
  int collapsed;                /* 1 or 0 */
  int marks;                    /* the run's marks (arch/result.h AQ_MARK_*): it
                                   slides, or its thrust leaves the section */
} aq_capacity_point;

typedef struct {
  aq_capacity_status status;
  aq_status run_status;        /* AQ_OK, or the failed run's code */
  aq_error err;                /* the failure, when status is FAILED */
  double lambda0;              /* smallest lambda0 of the arch's usable sets */
  double move_scale;           /* below and at it the arch never moves (INFINITY: never) */
  double scale_max;            /* cap used */
  double first_collapse_scale; /* interval[0].lo, or NAN */
  int resurrection;            /* 1: survives some scale above its first collapse */
  /* What the verdict rests on (docs/capacity.md, "Marks"): the marks of the
   * runs up to the first collapse (every run when it never collapses), and
   * the lowest scale of a marked run (NAN: none).  Followed when a mark can
   * apply: a friction given, or free hinges, under a four-hinge model but
   * paper (whose fits carry no joint forces); else 0 and NAN. */
  int marks;
  double first_mark_scale;
  aq_scan_result scan;
  size_t npoint;               /* = scan.runs (fewer only after a failed run) */
  aq_capacity_point *point;    /* malloc'd, by increasing scale; NULL when none */
} aq_capacity;

/* The scale at or below which no sample of sign * acc (n samples; sign
 * +1 or -1, the polarity) opens either set of arch, with a vertical
 * av_mps2 (NULL: none) scaled with the motion: at scale s a sample drives
 * set k if s act_sign_k a_i > lambda0_k (g + s av_i), so the scale is min
 * over usable sets k of lambda0_k g / max_i (act_sign_k a_i - lambda0_k
 * av_i) (INFINITY when no sample drives any set).  Exact for one step per
 * sample; merged steps (--merge-tol) are means of samples, so no merged
 * step moves the arch below it either.  *lambda0 (may be NULL) gets the
 * smallest lambda0 of the usable sets. */
double aq_capacity_move_scale(const aq_arch *arch, const double *acc_mps2,
                              const double *av_mps2, size_t n, double sign, double *lambda0);

/* Of n results of one (motion, arch, polarity) over azimuths: the index of
 * the worst (a failed run first, then the lowest first_collapse_scale; no
 * collapse ranks last; ties: the lowest index), and *fcs_min, *fcs_max the
 * range of first_collapse_scale over the azimuths where it collapses (NAN
 * when it collapses at none). */
size_t aq_capacity_worst(const aq_capacity *c, size_t n, double *fcs_min,
                         double *fcs_max);

/* Analyse one job.  Returns AQ_OK (out->status says what was found; a
 * failed run is AQ_CAPACITY_FAILED with out->err), or AQ_ENOMEM / the
 * stepper's allocation status (err filled).  Free out with aq_capacity_free. */
aq_status aq_capacity_pair(const aq_capacity_job *job, aq_capacity *out,
                           aq_error *err);
void aq_capacity_free(aq_capacity *c);

/* Analyse n jobs in order on the calling thread (one task's: a subject and
 * arch at every polarity and azimuth): out[i] as aq_capacity_pair's, or
 * FAILED with its err when the job cannot start. */
void aq_capacity_run_jobs(const aq_capacity_job *jobs, size_t n, aq_capacity *out);

/* A result as bytes, to travel between processes of one job
 * (util/bytes.h): every field of c, the error record, the intervals and the
 * scan's points included, so the decoded copy is equal bit for bit.
 * aq_capacity_encode appends c to w; aq_capacity_decode reads one result
 * from r into *out (free with aq_capacity_free) and returns AQ_OK, AQ_EFORMAT
 * (err: the byte offset and the field that ends early or is out of range)
 * or AQ_ENOMEM. */
void aq_capacity_encode(const aq_capacity *c, aq_bytes_out *w);
aq_status aq_capacity_decode(aq_bytes_in *r, aq_capacity *out, aq_error *err);

/* Analyse njob jobs on threads (>= 1) threads; out[i] is job i's result
 * whatever the number of threads, and the results do not depend on it.
 * A job that cannot start (out of memory, no stepper) is FAILED with its
 * err.  Returns AQ_OK, or AQ_ENOMEM when the threads cannot be made. */
aq_status aq_capacity_run_all(const aq_capacity_job *jobs, size_t njob,
                              long threads, aq_capacity *out, aq_error *err);

/* ---- fragility.c ---------------------------------------------------------- */

typedef struct {
  size_t n;         /* data used */
  size_t ncensored; /* right-censored among them */
  double median;    /* theta, in the unit of the data; NAN when it cannot be fitted */
  double beta;      /* lognormal standard deviation */
  double median_lo, median_hi; /* confidence interval of the median (INFINITY: unbounded) */
  double loglik;    /* maximised log-likelihood */
  int rank;         /* aq_fragility_fit_records_n: 1 for the measure of the
                       arch's smallest dispersion (per power of the scale,
                       aq_fragility_im_power), 2 the next...; 0 unfitted */
  size_t nmarked;   /* aq_fragility_fit_records_n: data whose row is marked
                       (docs/capacity.md, "Marks"): the polarity that collapses
                       first, or for a censored record either */
} aq_fragility;

#define AQ_FRAGILITY_CI_DEFAULT 0.90

/* Intensity measures of a scaled record for the fits: PGA (g), PGV (m/s),
 * PGD (m), Arias intensity (m/s), CAV (m/s), PGA / (lambda0 g). */
enum { AQ_FRAGILITY_NIM = 6 };
extern const char *const aq_fragility_im_names[AQ_FRAGILITY_NIM];
extern const char *const aq_fragility_im_units[AQ_FRAGILITY_NIM]; /* "g", "m/s", "m", ..., "1" */
/* IM number which of the record with measures im (scale 1) scaled by
 * scale, for an arch of smallest lambda0 (Arias grows as scale^2).  From
 * AQ_FRAGILITY_NIM on, the spectral measures: which - AQ_FRAGILITY_NIM is
 * aq_im_spectral_value's k (Sa(T), then Sa_avg; both grow as the scale). */
double aq_fragility_im_at(const aq_im *im, double lambda0, int which,
                          double scale);

/* Fit a lognormal CDF Phi(ln(x/theta)/beta) to n values x[i] > 0: a
 * collapse at x[i] when censored[i] == 0, or no collapse up to x[i] (right
 * censored) otherwise, by maximum likelihood (GSL's Nelder-Mead simplex on
 * (ln theta, ln beta)), and the profile-likelihood interval of the median
 * at level ci (0 < ci < 1): the theta whose profile deviance is within the
 * chi-square(1) quantile.  Fewer than two distinct collapse values leave
 * median, beta and the interval NAN (AQ_OK).  Returns AQ_EVALUE for a
 * value that is not finite and > 0, AQ_ENUMERIC if the optimiser fails. */
aq_status aq_fragility_fit(const double *x, const int *censored, size_t n,
                           double ci, aq_fragility *out, aq_error *err);

/* The fits of every IM for one arch over nrec records: record r's results
 * are cap[r * stride + p], p < npol (its polarities; the lowest first
 * collapse governs; none up to the cap: censored at the cap's intensity);
 * im[r] its measures at scale 1, or NULL to leave the record out, as is a
 * record one of whose pairs failed.  fits[AQ_FRAGILITY_NIM] are filled
 * (NAN where a fit is impossible or fails: the status and err say why). */
aq_status aq_fragility_fit_records(const aq_capacity *cap, size_t nrec, size_t stride,
                                   size_t npol, const aq_im *const *im, double ci,
                                   aq_fragility *fits, aq_error *err);

/* The power of the scale an IM grows with: 2 for Arias intensity, 1 for
 * the others.  Ranked, the dispersion of each is divided by it: ln IA at
 * collapse is twice as spread as ln sqrt(IA), which orders the records
 * alike; dividing compares how well each orders them. */
int aq_fragility_im_power(int which);

/* As aq_fragility_fit_records for the first nim measures (AQ_FRAGILITY_NIM
 * and the spectral ones after them, as aq_fragility_im_at numbers them),
 * filling fits[0..nim) and their rank by beta / power (the efficiency of
 * the measure for this arch, as Luco & Cornell 2007 judge a measure and
 * oq-vmtk ranks them). */
aq_status aq_fragility_fit_records_n(const aq_capacity *cap, size_t nrec, size_t stride,
                                     size_t npol, const aq_im *const *im, int nim,
                                     double ci, aq_fragility *fits, aq_error *err);

/* The negative log-likelihood of (theta, beta) for the data above (the
 * function fitted; exposed for tests and the bench). */
double aq_fragility_nll(const double *x, const int *censored, size_t n,
                        double theta, double beta);

#endif
