/* opt_table.c: the table of every option (see opt_table.h for how to add
 * one); the commands and the defaults are opt_commands.c's, the options
 * that are more than a value and the checks across options
 * opt_handlers.c's. */
#define _POSIX_C_SOURCE 200809L
#include "opt_table_impl.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../arch/arch.h"
#include "../arch/stepper.h"
#include "../blocks/blocks.h"
#include "../capacity/capacity.h"
#include "../select/misfit.h"
#include "../signal/spectrum.h"
#include "app.h"
#include "opt.h"
#include "opt_arch.h"
#include "opt_record.h"

_Static_assert(sizeof(aq_detrend) == sizeof(int), "--detrend is stored as an int");
_Static_assert(sizeof(aq_spectrum_peaks) == sizeof(int), "--peaks is stored as an int");

static const char *const detrends[] = {"mean", "linear", "none", NULL}; /* aq_detrend */
static const char *const impacts[] = {"cor", "momentum", NULL};
static const char *const x_axes[] = {"qc", "rad", NULL};
static const char *const y_axes[] = {"scale", "pga", NULL};
static const char *const papers[] = {"a4", "letter", NULL}; /* aq_plot_paper */
static const char *const checks[] = {"blocks", NULL}; /* --check */

const aq_opt_row aq_opt_rows[AQ_OPT_N] = {
    [AQ_OPT_ARCHES] = {.name = "arch", .kind = AQ_ARG_CUSTOM, .meta = "FILE", .fn = aq_opth_add_arch,
                       .cmds = SUITES,
                       .help = "an arch (.cfg), or an installed arch by name (oppenheim); "
                               "repeatable",
                       .required = SUITES},
    [AQ_OPT_ARCH] = {.name = "arch", .kind = AQ_ARG_CUSTOM, .meta = "FILE", .fn = aq_opth_one_arch,
                     .cmds = C(MECHANISM) | C(PULSE) | C(DOMAIN) | C(PLOT_DOMAIN),
                     .help = "the arch file (.cfg), or an installed arch by name (oppenheim)",
                     .required = C(MECHANISM) | C(PULSE) | C(DOMAIN) | C(PLOT_DOMAIN)},
    [AQ_OPT_ARCH_NAME] = {.name = "arch", .kind = AQ_ARG_STRING, .meta = "NAME", DEST(arch),
                          .cmds = C(PLOT_CAPACITY),
                          .help = "the arch of the capacity file to draw, by its name "
                                  "(default: the file's first)"},
    [AQ_OPT_ARCH_DRAWN] = {.name = "arch", .kind = AQ_ARG_STRING, .meta = "ARCH", DEST(arch),
                           .cmds = C(PLOT_ARCH),
                           .help = "the arch file (.cfg), or an installed arch by name; with "
                                   "a results file (RESULTS.h5 before the options), the name "
                                   "of its arch to draw (default: its first)"},
    [AQ_OPT_ACCEL_G] = {.name = "accel-g", .kind = AQ_ARG_DOUBLE, .lo = -100, .hi = 100,
                        .meta = "A", DEST(accel_g), .cmds = C(PULSE),
                        .help = "pulse amplitude, g (signed, |A| <= 100: its sign is the "
                                "polarity, so pulse takes no --polarity)",
                        .required = C(PULSE)},
    [AQ_OPT_DURATION] = {.name = "duration", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                         .meta = "S", DEST(duration_s), .cmds = C(PULSE),
                         .help = "pulse duration, s (0 < S <= 3600)",
                         .required = C(PULSE)},
    [AQ_OPT_END] = {.name = "end", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 86400, .meta = "S",
                    DEST(end_s), .cmds = C(PULSE),
                    .help = "stop at t = S (>= duration).  Default: run until rest or "
                            "collapse: end_s is the first duration + k s (k = 0, 1, 2, ...) "
                            "at which the arch has collapsed or is at rest (s = 0, no "
                            "kinetic energy, by the stepper's rest criterion); the row "
                            "equals that of --end end_s.  Motion that never rests (COR 1) "
                            "stops at the cap, --max-end, with a note on stderr (exit 0)",
                    .not_below = OPTS(AQ_OPT_DURATION)},
    [AQ_OPT_MAX_END] = {.name = "max-end", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 86400,
                        .meta = "S", DEST(max_end_s), .cmds = C(PULSE),
                        .help = "the cap of the default end, s (default duration + 3600 s, "
                                "and at most 5e6 steps of --dt)",
                        .conflicts = OPTS(AQ_OPT_END), .not_below = OPTS(AQ_OPT_DURATION),
                        .why = "it caps the default end"},
    [AQ_OPT_PULSE_DT] = {.name = "dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                         .meta = "S", DEST(pulse_dt_s), .cmds = C(PULSE),
                         .help = "constant steps of at most S seconds (default 0.01)"},
    [AQ_OPT_RATIOS] = {.name = "ratios", .kind = AQ_ARG_LIST, .lo = 1, .hi = 1000,
                       .meta = "LIST", DEST_LIST(ratios, nratios),
                       .cmds = C(DOMAIN) | C(PLOT_DOMAIN),
                       .help = "comma-separated ratios r > 1 (at most 1000) of the "
                               "pulse to lambda0 g (default 1.05,1.1,1.2,1.5,2,3,4; plot domain: "
                               "1.02,1.05,1.1,1.2,1.35,1.5,1.75,2,2.5,3,4,5)"},
    [AQ_OPT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                       .meta = "FILE.h5", DEST(output),
                       .cmds = SUITES | C(SPECTRUM) | C(SELECT), .check = aq_opth_output_names_hdf5,
                       .help = "write the HDF5 results file (docs/hdf5-layout.md; capacity: "
                               "its results in a `capacity` group; spectrum: the spectra "
                               "in a `spectra` group; select: a `select` group)"},
    [AQ_OPT_PLOT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                            .meta = "FILE", DEST(output), .cmds = PLOT_ALL,
                            .help = "the figure (.png .svg .pdf)",
                            .required = PLOT_ALL},
    [AQ_OPT_REPORT_OUTPUT] = {.name = "output", .short_name = 'o', .kind = AQ_ARG_STRING,
                              .meta = "FILE.html", DEST(output), .cmds = C(REPORT),
                              .help = "the page",
                              .required = C(REPORT)},
    [AQ_OPT_TEXT] = {.name = "text", .kind = AQ_ARG_STRING, .meta = "FILE", DEST(text),
                     .cmds = SUITES | C(SELECT), .check = aq_opth_text_names_text,
                     .help = "write the TSV to FILE instead of stdout"},
    [AQ_OPT_FRAGILITY] = {.name = "fragility", .kind = AQ_ARG_STRING, .meta = "FILE",
                          DEST(fragility), .cmds = C(CAPACITY), .check = aq_opth_fragility_names_text,
                          .help = "lognormal fragility fits, one row per (arch, IM)"},
    [AQ_OPT_DATA] = {.name = "data", .kind = AQ_ARG_STRING, .meta = "FILE.csv", DEST(data),
                     .cmds = PLOT_ALL,
                     .help = "also write the plotted data (columns carry units)"},
    [AQ_OPT_PAPER] = {.name = "paper", .kind = AQ_ARG_CHOICE, .choices = papers,
                      .meta = "a4|letter", DEST(paper), .cmds = PLOT_ALL,
                      .help = "the page of a PDF (default: the locale's paper, LC_PAPER, else "
                              "A4); the figure is scaled to fit"},
    [AQ_OPT_RUN] = {.name = "run", .kind = AQ_ARG_STRING, .meta = "KEY", DEST(run),
                    .cmds = C(PLOT_HISTORY) | C(PLOT_ARCH),
                    .help = "the run to draw: a group under /histories, e.g. "
                            "00000_000_000 (default: the first run with histories; plot "
                            "arch: a run of --model blocks, every voussoir as its history "
                            "has it, at --at)"},
    [AQ_OPT_RECORD] = {.name = "record", .kind = AQ_ARG_STRING, .meta = "NAME", DEST(record),
                       .cmds = C(PLOT_SPECTRUM),
                       .help = "the record (or --components pair) of a spectrum file to draw, "
                               "as its record column says or by file name (default: all)"},
    [AQ_OPT_ROTATION] = {.name = "rotation", .kind = AQ_ARG_DOUBLE, .lo = -10, .hi = 10,
                         .meta = "RAD", DEST(rotation_rad), .cmds = C(PLOT_ARCH),
                         .conflicts = OPTS(AQ_OPT_RUN),
                         .help = "draw the mechanism deformed at that rotation of body 1: "
                                 "the primary set if RAD > 0, the reverse set if RAD < 0, "
                                 "|RAD| <= q_c"},
    [AQ_OPT_AT] = {.name = "at", .kind = AQ_ARG_LIST, .lo = -1e3, .hi = 1e5, .meta = "LIST",
                   DEST_LIST(at_s, nat), .cmds = C(PLOT_ARCH), .requires = OPTS(AQ_OPT_RUN),
                   .help = "with --run: the record times (s) to draw the voussoirs at, at "
                           "most 6, e.g. 1.2,1.5 (within the run's history; default: the "
                           "time of voussoir 0's largest |rotation|); the last is filled"},
    [AQ_OPT_IM] = {.name = "im", .kind = AQ_ARG_STRING, .meta = "IM", DEST(im),
                   .cmds = C(PLOT_CAPACITY),
                   .help = "the intensity measure of the fragility: pga_g (default), "
                           "pgv_m_s, pgd_m, arias_m_s, cav_m_s, pga_lambda0, or a spectral "
                           "measure the file's fits hold (capacity's --im-periods and "
                           "--sa-avg: sa_0.2s_g, sa_avg_0.1_1s_g)"},
    [AQ_OPT_X] = {.name = "x", .kind = AQ_ARG_CHOICE, .choices = x_axes, .meta = "qc|rad",
                  DEST(x_rad), .cmds = C(PLOT_CAPACITY),
                  .help = "the peak rotation over q_c (qc, the default) or in rad (rad)"},
    [AQ_OPT_Y] = {.name = "y", .kind = AQ_ARG_CHOICE, .choices = y_axes, .meta = "scale|pga",
                  DEST(y_pga), .cmds = C(PLOT_CAPACITY),
                  .help = "the scale factor (scale, the default) or the PGA in g (pga)"},
    [AQ_OPT_SCALE] = {.name = "scale", .kind = AQ_ARG_LIST, .lo = 0, .hi = INFINITY,
                      .meta = "LIST", DEST_LIST(scales, nscale), .cmds = C(RUN),
                      .help = "run each record scaled by each factor, e.g. 0.5,1,2 "
                              "(default 1)"},
    [AQ_OPT_SCALE_TO_PGA] = {.name = "scale-to-pga", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 100,
                             .meta = "G", DEST(scale_to_pga_g), .cmds = C(RUN),
                             .help = "scale each processed record to a PGA of G g instead",
                             .conflicts = OPTS(AQ_OPT_SCALE),
                             .why = "one scaling rule per run"},
    [AQ_OPT_SCALE_TO_LAMBDA0] = {.name = "scale-to-lambda0", .kind = AQ_ARG_DOUBLE_GT,
                                 .lo = 0, .hi = 100, .meta = "K", DEST(scale_to_lambda0),
                                 .cmds = C(RUN),
                                 .help = "scale each processed record, for each arch, to a "
                                         "PGA of K lambda0 g, lambda0 the arch's static "
                                         "collapse multiplier (the smaller of its two hinge "
                                         "sets'), so that one suite shakes arches of unlike "
                                         "strength alike",
                                 .conflicts = OPTS(AQ_OPT_SCALE, AQ_OPT_SCALE_TO_PGA),
                                 .why = "one scaling rule per run"},
    [AQ_OPT_SCALE_MAX] = {.name = "scale-max", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 1e6,
                          .meta = "S", DEST(scale_max), .cmds = C(CAPACITY),
                          .help = "highest scale (default: PGA = 20 lambda0 g)"},
    [AQ_OPT_RESOLUTION] = {.name = "resolution", .kind = AQ_ARG_DOUBLE,
                           .lo = AQ_SCAN_RESOLUTION_MIN, .hi = AQ_SCAN_RESOLUTION_MAX,
                           .meta = "R", DEST(resolution), .cmds = C(CAPACITY),
                           .help = "relative scan step: no window of either verdict wider "
                                   "than R is missed (default 0.01; 1e-4 to 1)"},
    [AQ_OPT_SCAN_TOL] = {.name = "tol", .kind = AQ_ARG_DOUBLE, .lo = AQ_SCAN_TOL_MIN, .hi = 1,
                         .meta = "T", DEST(scan_tol), .cmds = C(CAPACITY),
                         .help = "relative tolerance of each change (default 1e-6; 1e-12 "
                                 "to R)",
                         .not_above = OPTS(AQ_OPT_RESOLUTION)},
    [AQ_OPT_DOMAIN_TOL] = {.name = "tol", .kind = AQ_ARG_DOUBLE, .lo = AQ_DOMAIN_TOL_MIN_S,
                           .hi = 1, .meta = "S", DEST(domain_tol_s), .cmds = C(DOMAIN),
                           .help = "bisection tolerance on the duration, s, 1e-12..1 "
                                   "(default 1e-9; at most --max-duration)",
                           .not_above = OPTS(AQ_OPT_MAX_DURATION)},
    [AQ_OPT_MAX_DURATION] = {.name = "max-duration", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                             .hi = 3600, .meta = "S", DEST(max_duration_s), .cmds = C(DOMAIN),
                             .help = "give up above this duration, s (default 100)"},
    [AQ_OPT_JOBS] = {.name = "jobs", .short_name = 'j', .kind = AQ_ARG_LONG, .lo = 1,
                     .hi = AQ_MAX_THREADS, .meta = "N", DEST(threads),
                     .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                     .help = "worker threads (default: the number of cores); the results "
                             "are the same for every N"},
    [AQ_OPT_MODEL] = {.name = "model", .kind = AQ_ARG_CHOICE, .choices = aq_model_names,
                      .meta = "M", DEST(model), .cmds = DYNAMICS,
                      .help = "workpath (default), ode (reference), paper, workpath-quad, "
                              "blocks (rigid voussoirs in frictional contact; docs/blocks.md)",
                      .check = aq_opth_blocks_model_applies},
    [AQ_OPT_COR] = {.name = "cor", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 1, .meta = "C",
                    DEST(cor), .cmds = DYNAMICS | C(PLOT_DOMAIN), .check = aq_opth_cor_not_blocks,
                    .help = "kinetic-energy ratio kept at an impact, 0..1 (default: each "
                            "arch's [dynamics] cor; refused for an arch whose impact is "
                            "momentum, which uses none)"},
    [AQ_OPT_FRICTION] = {.name = "friction", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 1e3,
                         .meta = "MU", DEST(friction),
                         .cmds = DYNAMICS | C(MECHANISM) | C(PLOT_ARCH),
                         .help = "the Coulomb friction coefficient of every joint, springings "
                                 "included, 0 < MU <= 1000 (default: each arch's [contact] "
                                 "friction; none if it has none)"},
    [AQ_OPT_BLOCKS_DT] = {.name = "blocks-dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 0.1,
                          .meta = "S", DEST(blocks_dt_s), .cmds = C(PULSE) | SUITES,
                          .help = "the block model's time step, s (default 0.002; only with "
                                  "--model blocks or --check blocks)",
                          .check = aq_opth_blocks_dt_needs_blocks},
    [AQ_OPT_CHECK] = {.name = "check", .kind = AQ_ARG_CHOICE, .choices = checks,
                      .meta = "blocks", DEST(check_blocks), .cmds = C(RUN),
                      .check = aq_opth_check_not_blocks,
                      .help = "re-run under --model blocks every run whose status the "
                              "four-hinge model marks (slides, beyond): the block model's "
                              "verdict in the columns check_blocks (agrees, differs, failed; "
                              "- for a run not checked), check_collapsed, "
                              "check_collapse_time_s, check_peak_rotation_rad, and what it "
                              "saw in max_slip_m, hinges_observed, hinges_first_s, "
                              "mechanism_changed_s (docs/blocks.md)"},
    [AQ_OPT_IMPACT] = {.name = "impact", .kind = AQ_ARG_CHOICE, .choices = impacts,
                       .meta = "RULE", DEST(impact), .cmds = C(PULSE),
                       .help = "cor | momentum (default: the arch file's)",
                       .check = aq_opth_momentum_takes_no_cor},
    [AQ_OPT_ODE_RTOL] = {.name = "ode-rtol", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 0.1,
                         .meta = "R", DEST(ode_rtol), .cmds = C(PULSE) | C(DOMAIN),
                         .help = "ode model tolerance (default 1e-10; only with --model ode)",
                         .check = aq_opth_ode_rtol_needs_ode},
    [AQ_OPT_HISTORY] = {.name = "history", .kind = AQ_ARG_FLAG, DEST(history), .cmds = C(RUN),
                        .help = "write histories (step ends, turning points, impacts) to the "
                                "HDF5 file (with -o), with each record's processed ground "
                                "motion (as --store-records), which plot history draws",
                        .requires = OPTS(AQ_OPT_OUTPUT),
                        .why = "histories are written only to the results file"},
    [AQ_OPT_HISTORY_FILE] = {.name = "history", .kind = AQ_ARG_STRING, .meta = "FILE",
                             DEST(history_file), .cmds = C(PULSE),
                             .help = "write the history as CSV (step ends, turning points, "
                                     "impacts)"},
    [AQ_OPT_STORE_RECORDS] = {.name = "store-records", .kind = AQ_ARG_FLAG, DEST(store_records),
                              .cmds = C(RUN),
                              .help = "write the processed records to the HDF5 file (with -o)",
                              .requires = OPTS(AQ_OPT_OUTPUT),
                              .why = "processed records are written only to the results file"},
    [AQ_OPT_RESUME] = {.name = "resume", .kind = AQ_ARG_FLAG, DEST(resume), .cmds = C(RUN),
                       .help = "continue an interrupted run of this same command (with -o): "
                               "every record done is kept in FILE.h5.journal until the "
                               "results file is complete; the outputs equal an "
                               "uninterrupted run's (not with --history or --store-records)",
                       .requires = OPTS(AQ_OPT_OUTPUT),
                       .conflicts = OPTS(AQ_OPT_HISTORY, AQ_OPT_STORE_RECORDS),
                       .why = "the journal beside the results file holds rows and record "
                              "metadata, not datasets"},
    [AQ_OPT_POLARITY] = {.name = "polarity", .kind = AQ_ARG_CHOICE,
                         .choices = aq_opt_polarity_names, .meta = "P", DEST(polarity),
                         .cmds = SUITES,
                         .help = "normal (the record as read), reversed (negated) or both "
                                 "(each record both ways; the polarity column says which: a "
                                 "hinge-controlled arch's response depends on the sign); "
                                 "default both, the worse governing every summary, or normal "
                                 "alone when every arch has free hinges and is its own mirror "
                                 "image (it answers a record and its negation alike) or every "
                                 "subject is a ground motion at azimuths in opposite pairs "
                                 "(--azimuth all)"},
    [AQ_OPT_TABLE] = {.name = "table", .kind = AQ_ARG_FLAG, DEST(table), .cmds = C(MECHANISM),
                      .help = "add, after a blank line, the work path of each admissible set "
                              "at N points over [0, q_c] (the data of the paper's Figs 4-7)"},
    [AQ_OPT_POINTS] = {.name = "points", .kind = AQ_ARG_LONG, .lo = 2, .hi = 100000,
                       .meta = "N", DEST(points), .cmds = C(MECHANISM),
                       .help = "rows per set in --table (2..100000, default 101)",
                       .requires = OPTS(AQ_OPT_TABLE),
                       .why = "the number of rows of the table"},
    [AQ_OPT_RTOL] = {.name = "rtol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 1, .meta = "R",
                     DEST(rtol), .cmds = C(COMPARE), .help = "relative tolerance (default 1e-9)"},
    [AQ_OPT_ATOL] = {.name = "atol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = HUGE_VAL,
                     .meta = "A", DEST(atol), .cmds = C(COMPARE),
                     .help = "absolute tolerance in each field's units (default 0)"},
    [AQ_OPT_IGNORE] = {.name = "ignore", .kind = AQ_ARG_CUSTOM, .meta = "NAME", .fn = aq_opth_ignore,
                       .cmds = C(COMPARE),
                       .help = "leave out a setting or a field (repeatable, or a comma "
                               "list), e.g. --ignore model to compare two models' numbers; "
                               "record_sha256 / arch_sha256 match records by file name / "
                               "arches by name alone"},
    [AQ_OPT_QUIET] = {.name = "quiet", .short_name = 'q', .kind = AQ_ARG_FLAG, DEST(quiet),
                      .cmds = C(RUN),
                      .help = "no progress line (it is shown only on a terminal)"},
    [AQ_OPT_PERIODS] = {.name = "periods", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1e4,
                        .meta = "LIST", DEST_LIST(periods, nperiods), .cmds = C(SPECTRUM),
                        .help = "oscillator periods, s, comma-separated, each > 0 (default: "
                                "PEER's 111 periods of the NGA-West2 flatfile, 0.01-20 s)"},
    /* each in (0, 1): critical damping (1) leaves no oscillation for a spectrum */
    [AQ_OPT_DAMPING] = {.name = "damping", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1, .hi_open = 1,
                        .meta = "LIST", DEST_LIST(dampings, ndampings),
                        .cmds = C(SPECTRUM),
                        .help = "damping ratios, comma-separated, each in (0, 1) (default "
                                "0.05)"},
    [AQ_OPT_TARGET] = {.name = "target", .kind = AQ_ARG_STRING, .meta = "SPEC", DEST(target),
                       .cmds = C(SELECT) | C(PLOT_SPECTRUM),
                       .help = "the target spectrum: ec8:KEY=VALUE,... with type=1|2, "
                               "ground=A..E, ag=G (a_gR in g) and optionally importance=GAMMA, "
                               "damping=ZETA (EN 1998-1:2004 3.2.2.2); asce7:sds=G,sd1=G,tl=S "
                               "and optionally ,mcer (ASCE/SEI 7-22, the design or MCE_R "
                               "spectrum); or a CSV file period_s,psa_g of your own "
                               "(docs/select.md)",
                       .required = C(SELECT)},
    [AQ_OPT_COUNT] = {.name = "count", .kind = AQ_ARG_SIZE, .lo = 1, .hi = 1000, .meta = "N",
                      DEST(count), .cmds = C(SELECT),
                      .help = "records (or --components pairs) in the suite, 1..1000",
                      .required = C(SELECT)},
    [AQ_OPT_SELECT_PERIODS] = {.name = "periods", .kind = AQ_ARG_CUSTOM, .meta = "T1,T2",
                               .fn = aq_opth_select_periods, .cmds = C(SELECT),
                               .help = "the period range, s, 0 < T1 < T2 (default: the range "
                                       "of the best-ranked spectral measure of --fragility, "
                                       "else 0.1,1; docs/select.md)"},
    [AQ_OPT_PERIOD_GRID] = {.name = "period-grid", .kind = AQ_ARG_LIST, .lo = 0, .hi = 1e4,
                            .meta = "LIST", DEST_LIST(period_grid, nperiod_grid),
                            .cmds = C(SELECT),
                            .help = "the periods, s, at which the suite is matched and checked "
                                    "(those within the range; default: PEER's 111 periods "
                                    "within the range, and T1 and T2)"},
    [AQ_OPT_SCALE_RANGE] = {.name = "scale-range", .kind = AQ_ARG_CUSTOM, .meta = "LO,HI",
                            .fn = aq_opth_scale_range, .cmds = C(SELECT),
                            .help = "each record's scale factor within LO..HI, 0 < LO <= HI "
                                    "(default 0.25,4)"},
    [AQ_OPT_MAX_PER_EVENT] = {.name = "max-per-event", .kind = AQ_ARG_SIZE, .lo = 1,
                              .hi = 1000, .meta = "K", DEST(max_per_event), .cmds = C(SELECT),
                              .help = "at most K records of one event, where the files name "
                                      "their event (default: no limit)"},
    [AQ_OPT_BEST_EFFORT] = {.name = "best-effort", .kind = AQ_ARG_FLAG, DEST(best_effort),
                            .cmds = C(SELECT),
                            .help = "when no suite meets the conditions within the scale "
                                    "range, write the one closest to them anyway (its file "
                                    "says which fail; exit status 1)"},
    [AQ_OPT_FRAGILITY_IN] = {.name = "fragility", .kind = AQ_ARG_STRING, .meta = "FILE",
                             DEST(fragility_in), .cmds = C(SELECT),
                             .help = "capacity's --fragility fits: the period range is that of "
                                     "the arch's best-ranked spectral measure (Sa_avg T1..T2, "
                                     "or 0.2T..2T of Sa(T))",
                             .conflicts = OPTS(AQ_OPT_SELECT_PERIODS),
                             .why = "both give the period range"},
    [AQ_OPT_ARCH_FRAGILITY] = {.name = "fragility-arch", .kind = AQ_ARG_STRING, .meta = "NAME",
                               DEST(arch), .cmds = C(SELECT),
                               .help = "the arch of the --fragility file, by name (default: "
                                       "its only arch)",
                               .requires = OPTS(AQ_OPT_FRAGILITY_IN),
                               .why = "it names an arch of that file"},
    [AQ_OPT_SUITE] = {.name = "suite", .kind = AQ_ARG_STRING, .meta = "FILE", DEST(suite),
                      .cmds = SUITES,
                      .help = "the records of a suite file of select, each at its scale "
                              "(capacity: its scale 1)",
                      .conflicts = OPTS(AQ_OPT_SCALE_TO_PGA, AQ_OPT_SCALE_TO_LAMBDA0),
                      .why = "the suite gives each record its scale"},
    [AQ_OPT_HELP] = {.name = "help", .short_name = 'h', .kind = AQ_ARG_FLAG, .cmds = ALL_CMDS,
                     .help = "this text"},
    [AQ_OPT_VERSION] = {.name = "version", .kind = AQ_ARG_FLAG, .cmds = C(RUN),
                        .help = "the version, and nothing else"},

    [AQ_OPT_UNITS] = {.name = "units", .kind = AQ_ARG_CUSTOM, .meta = "U", .fn = aq_opth_units,
                      .cmds = READS, .group = AQ_GROUP_READING,
                      .help = "values of records that state no units are U: g, g/10, gal, "
                              "cm/s2, mm/s2, m/s2, nm/s2 or counts (divided by the "
                              "sensitivity the file states, e.g. SAC SCALE)",
                      .meta2 = "GLOB=U",
                      .help2 = "records whose path matches GLOB are read as U, even over "
                               "units the file states (reported), e.g. '*.SAC=counts' "
                               "(repeatable; the last matching rule wins)"},
    [AQ_OPT_READ_DT] = {.name = "dt", .kind = AQ_ARG_DOUBLE_GT, .lo = 0, .hi = 3600,
                        .meta = "S", DEST(read.dt_s), .cmds = READS,
                        .group = AQ_GROUP_READING,
                        .help = "sample interval (s) of text records without time column"},
    [AQ_OPT_COLUMN] = {.name = "column", .kind = AQ_ARG_SIZE, .lo = 1, .hi = 64, .meta = "N",
                       DEST(read.column), .cmds = READS, .group = AQ_GROUP_READING,
                       .help = "column N (1-based) of a text record is the acceleration"},
    [AQ_OPT_COMPONENT] = {.name = "component", .kind = AQ_ARG_CUSTOM, .meta = "GLOB=CH",
                          .read_fn = aq_opt_component, .cmds = READS, .group = AQ_GROUP_READING,
                          .help = "channel CH of multi-channel files matching GLOB (or name "
                                  "one record as FILE#CH)"},
    [AQ_OPT_ACCEPT_IMPLAUSIBLE] = {.name = "accept-implausible", .kind = AQ_ARG_FLAG,
                                   DEST(read.accept_implausible), .cmds = READS,
                                   .group = AQ_GROUP_READING,
                                   .help = "keep records whose PGA is outside 1e-5..10 g"},
    [AQ_OPT_ACCEPT_VERTICAL] = {.name = "accept-vertical", .kind = AQ_ARG_FLAG,
                                DEST(read.accept_vertical), .cmds = READS,
                                .group = AQ_GROUP_READING,
                                .help = "run channels the file identifies as vertical"},
    [AQ_OPT_RESPONSE] = {.name = "response", .kind = AQ_ARG_CUSTOM, .meta = "FILE.xml",
                         .read_fn = aq_opt_response, .cmds = READS, .group = AQ_GROUP_READING,
                         .help = "StationXML giving the sensitivity of miniSEED records (a "
                                 "StationXML given as a RECORD does the same)"},

    [AQ_OPT_COMPONENTS] = {.name = "components", .kind = AQ_ARG_CUSTOM, .meta = "H1,H2[,V]",
                           .orient_fn = aq_opt_components,
                           .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                           .group = AQ_GROUP_ORIENTATION,
                           .help = "one ground motion from two orthogonal horizontal "
                                   "component records (and the vertical V); repeatable.  The "
                                   "arch feels a_x = a1 cos(theta - phi1) + a2 cos(theta - "
                                   "phi2).  The components must share dt and start time; the "
                                   "samples they share are run (spectrum: their RotD50, "
                                   "RotD100 and GeoMean)",
                           .check = aq_opth_orientation},
    [AQ_OPT_AZIMUTHS] = {.name = "azimuths", .kind = AQ_ARG_CUSTOM, .meta = "A1,A2",
                         .orient_fn = aq_opt_azimuths,
                         .cmds = SUITES | C(SPECTRUM) | C(SELECT),
                         .group = AQ_GROUP_ORIENTATION,
                         .help = "azimuths phi1, phi2 (deg from north) of the preceding "
                                 "--components (default: from the files, e.g. PEER's GIL067 "
                                 "is 67 deg)"},
    [AQ_OPT_AZIMUTH] = {.name = "azimuth", .kind = AQ_ARG_CUSTOM, .meta = "DEG",
                        .orient_fn = aq_opt_azimuth,
                        .cmds = SUITES, .group = AQ_GROUP_ORIENTATION,
                        .help = "the arch's +x azimuth theta, deg from north (default 0)",
                        .requires = OPTS(AQ_OPT_COMPONENTS),
                        .why = "a plain RECORD is already the arch's in-plane component",
                        .meta2 = "all[:STEP]",
                        .help2 = "every theta 0, STEP, ... < 360 (default STEP 5); the TSV "
                                 "shows the worst azimuth per (motion, arch, scale): a failed "
                                 "run, else a collapse (the earliest), else the largest "
                                 "peak_rotation_over_qc; the HDF5 file has all"},
    [AQ_OPT_ALL_AZIMUTHS] = {.name = "all-azimuths", .kind = AQ_ARG_FLAG,
                             DEST(orient.all_azimuths), .cmds = C(RUN),
                             .group = AQ_GROUP_ORIENTATION,
                             .help = "with --azimuth all: every azimuth's row in the TSV"},
    [AQ_OPT_VERTICAL] = {.name = "vertical", .kind = AQ_ARG_FLAG, DEST(orient.vertical),
                         .cmds = SUITES, .group = AQ_GROUP_ORIENTATION,
                         .help = "run the vertical component V too (without it a V is "
                                 "ignored, with a warning); a step with g + a_v <= 0 stops "
                                 "the run: status run:eliftoff"},

    [AQ_OPT_DETREND] = {.name = "detrend", .kind = AQ_ARG_CHOICE, .choices = detrends,
                        .meta = "D", DEST(proc.detrend), .cmds = READS,
                        .group = AQ_GROUP_PROCESSING,
                        .help = "remove the least-squares line (linear, default), the mean "
                                "(mean) or nothing (none)"},
    [AQ_OPT_TAPER] = {.name = "taper", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 0.5,
                      .zero_is_off = 1, /* --taper 0: no taper, as --no-filter gives */
                      .meta = "FRAC", DEST(proc.taper_frac), .cmds = READS,
                      .group = AQ_GROUP_PROCESSING,
                      .help = "Hann taper over FRAC of the record at each end, 0-0.5 "
                              "(default 0: only the zero pads' junctions are tapered)"},
    [AQ_OPT_HIGHPASS] = {.name = "highpass", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                         .hi = AQ_OPT_FREQ_MAX_HZ, .meta = "HZ", DEST(proc.highpass_hz),
                         .fn = aq_opth_highpass_given, .cmds = READS, .group = AQ_GROUP_PROCESSING,
                         .help = "acausal Butterworth high-pass corner (default 0.03 Hz, or "
                                 "1/duration for a record shorter than 33.3 s)"},
    [AQ_OPT_ORDER] = {.name = "order", .kind = AQ_ARG_INT, .lo = 1, .hi = AQ_OPT_ORDER_MAX,
                      .meta = "N", DEST(proc.order), .cmds = READS,
                      .group = AQ_GROUP_PROCESSING,
                      .help = "Butterworth order, 1-20 (default 4)"},
    [AQ_OPT_LOWPASS] = {.name = "lowpass", .kind = AQ_ARG_DOUBLE_GT, .lo = 0,
                        .hi = AQ_OPT_FREQ_MAX_HZ, .meta = "HZ", DEST(proc.lowpass_hz),
                        .cmds = READS, .group = AQ_GROUP_PROCESSING,
                        .help = "acausal Butterworth low-pass corner (default off)",
                        .check = aq_opth_lowpass_above_highpass},
    [AQ_OPT_IM_PERIODS] = {.name = "im-periods", .kind = AQ_ARG_CUSTOM, .meta = "LIST",
                           .fn = aq_opth_im_periods, .cmds = RECORDS, .group = AQ_GROUP_PROCESSING,
                           .help = "intensity measures Sa(T), 5 % damping, at these periods, "
                                   "s, comma-separated, at most 8, or none (default "
                                   "0.2,0.5,1 in info and capacity, none in the main job)"},
    [AQ_OPT_SA_AVG] = {.name = "sa-avg", .kind = AQ_ARG_CUSTOM, .meta = "T1,T2",
                       .fn = aq_opth_sa_avg, .cmds = RECORDS, .group = AQ_GROUP_PROCESSING,
                       .help = "intensity measure Sa_avg: the geometric mean of Sa at 10 "
                               "periods evenly spaced from T1 to T2 s (Eads et al. 2015), "
                               "or none (default 0.1,1 in info and capacity, none in the main job)"},
    [AQ_OPT_PEAKS] = {.name = "peaks", .kind = AQ_ARG_CHOICE,
                      .choices = aq_spectrum_peaks_names, .meta = "RULE", DEST(proc.peaks),
                      .cmds = READS, .group = AQ_GROUP_PROCESSING,
                      .help = "where each oscillator's peak is taken, for the spectra and "
                              "the spectral measures: peer (default: at the samples and at "
                              "N - 1 points between each two, N = ceil(10 dt / T), as PEER "
                              "computes the NGA-West2 spectra), exact (over continuous time, "
                              "the record linear between samples) or samples (at the samples "
                              "only); docs/spectrum.md"},
    [AQ_OPT_SAMPLED_PEAKS] = {.name = "sampled-peaks", .kind = AQ_ARG_FLAG,
                              DEST(sampled_peaks), .cmds = READS,
                              .group = AQ_GROUP_PROCESSING,
                              .help = "the same as --peaks samples",
                              .conflicts = OPTS(AQ_OPT_PEAKS),
                              .why = "it is --peaks samples",
                              .check = aq_opth_sampled_peaks_alias},
    [AQ_OPT_NO_FILTER] = {.name = "no-filter", .kind = AQ_ARG_FLAG_OFF, DEST(proc.filter),
                          .cmds = READS, .group = AQ_GROUP_PROCESSING,
                          .help = "no taper, pads or filter (detrend still applies; "
                                  "--taper 0, no taper, may be given with it)",
                          /* an option that sets one of them would be ignored: refused,
                           * even at its default, unless it asks for none (--taper 0:
                           * .zero_is_off) */
                          .conflicts = OPTS(AQ_OPT_TAPER, AQ_OPT_HIGHPASS, AQ_OPT_ORDER,
                                            AQ_OPT_LOWPASS),
                          .why = "it applies no taper, pads or filter"},
    [AQ_OPT_MERGE_TOL] = {.name = "merge-tol", .kind = AQ_ARG_DOUBLE, .lo = 0, .hi = 10,
                          .meta = "G", DEST(merge_tol_g), .cmds = SUITES,
                          .group = AQ_GROUP_PROCESSING,
                          .help = "merge consecutive samples differing by less than G (g) "
                                  "into one constant-acceleration step (default 0: none)"},
    [AQ_OPT_NO_CACHE] = {.name = "no-cache", .kind = AQ_ARG_FLAG, DEST(no_cache),
                         .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                         .help = "neither read nor store processed records, built arches "
                                 "and spectra in the cache (results are the same either way; "
                                 "docs/cache.md)"},
    [AQ_OPT_CACHE_DIR] = {.name = "cache-dir", .kind = AQ_ARG_STRING, .meta = "DIR",
                          DEST(cache_dir), .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                          .help = "keep processed records, built arches and spectra in DIR (made "
                                  "if its parent exists; one that cannot be used stops the "
                                  "command before anything runs; default "
                                  "$XDG_CACHE_HOME/archquake, else ~/.cache/archquake, "
                                  "which, if it cannot be used, is a note and the run goes "
                                  "on)",
                          .check = aq_opth_cache_dir_needs_cache},
    [AQ_OPT_CACHE_MAX] = {.name = "cache-max", .kind = AQ_ARG_CUSTOM, .meta = "SIZE",
                          .fn = aq_opth_cache_max, .cmds = C(RUN) | C(SELECT), .group = AQ_GROUP_PROCESSING,
                          .help = "keep the cache directory under SIZE bytes, or K, M, G, T "
                                  "(1K = 1024), e.g. 2G (default 512M): a write that passes "
                                  "it removes other builds' entries, then the least "
                                  "recently used",
                          .conflicts = OPTS(AQ_OPT_NO_CACHE),
                          .why = "--no-cache uses no cache directory"},
};

