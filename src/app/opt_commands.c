/* opt_commands.c: the table of every command (its name, title and help),
 * the environment and files the help names, and the options' defaults. */
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

static const char run_tail[] =
    "Output: TSV, one row per run (on a terminal: an aligned table with 6\n"
    "significant digits; pipe or redirect it, or use --text, for the TSV).\n"
    "Columns: record arch model scale pga_g status collapsed collapse_time_s\n"
    "  peak_rotation_rad peak_displacement_m max_kinetic_energy_j impacts\n"
    "  energy_in_j energy_dissipated_j  (status: ok, slides, beyond,\n"
    "  slides+beyond (below), or read:CODE, process:CODE,\n"
    "  arch:CODE, run:CODE; collapse_time_s is nan for an arch that survives;\n"
    "  then polarity (normal | reversed) lambda0_first (lambda0 of the set the\n"
    "  record drove first; nan if it never moved) peak_rotation_over_qc (the\n"
    "  largest |q| / q_c over both sets; 1 at collapse) pga_over_lambda0 (pga_g over\n"
    "  lambda0_first, or over the lower lambda0 if it never moved);\n"
    "  a run whose status is not ok has every result column nan, collapsed\n"
    "  included: no verdict; then azimuth_deg: the arch's azimuth for a\n"
    "  --components motion, nan for a RECORD; control: fixed or free, the\n"
    "  arch's hinge control, which its verdicts assume; then mu_demand (the\n"
    "  largest |T|/N at any joint over the run) mu_demand_joint (where)\n"
    "  thrust_ecc_max (the largest eccentricity of the thrust at a joint that\n"
    "  is not a hinge) thrust_ecc_time_s (when it first passed 1)\n"
    "  slide_time_s (when mu_demand first passed the friction given); when\n"
    "  the arch never moved, mu_demand is the least friction with which a\n"
    "  line of thrust stands at the record's peak and the thrust columns are\n"
    "  nan; status slides: a friction was given and\n"
    "  mu_demand passed it; beyond: free control, the thrust left a joint's\n"
    "  section; slides+beyond: both: the verdict holds for the four-hinge\n"
    "  model only up to that time, follow such a run with --model blocks);\n"
    "  last, with --model blocks: max_slip_m hinges_observed (the joints and\n"
    "  faces that opened, 0e,6i,...) hinges_first_s (when) mechanism_changed_s\n"
    "  (when the open joints left the arch's sets); nan and - otherwise;\n"
    "  then check_blocks check_collapsed check_collapse_time_s\n"
    "  check_peak_rotation_rad: with --check blocks, a marked run's verdict\n"
    "  under the block model (agrees, differs, failed) and its collapse and\n"
    "  peak, the block columns filled from it; - and nan for a run not checked;\n"
    "  last friction_work_j: the work the block model's joint friction took, J\n"
    "Exit status (the main job's; each command's --help gives its own):\n"
    "  0  every record read and every run done\n"
    "  1  some record or run failed, or a --check blocks re-run did (each\n"
    "     reported on stderr; the others ran)\n"
    "  2  bad or missing options, or an arch file that cannot be loaded:\n"
    "     nothing was run\n"
    "  3  an output file could not be written (no partial file is left; an\n"
    "     existing file of that name is untouched)\n"
    "  A run ended by SIGINT, SIGTERM, SIGHUP or SIGPIPE removes its\n"
    "  temporaries and ends with that signal.\n";

static const char plot_head[] =
    "usage: archquake plot FIGURE [INPUT] [OPTIONS] -o FILE\n"
    "Draw a figure with PLplot; the format is FILE's extension: .png, .svg or\n"
    ".pdf (cairo drivers).  No partial file is ever left under FILE.\n"
    "Figures:\n"
    "  history RESULTS.h5 [--run KEY]   one run of a results file written with\n"
    "        --history: ground acceleration (g) with +-lambda0 g, rotation (rad)\n"
    "        with +-q_c, kinetic and potential energy and the work put in (J);\n"
    "        impacts and collapse marked\n"
    "  arch --arch ARCH [--rotation RAD]   the arch to scale, its voussoirs and\n"
    "        both hinge sets; with --rotation the mechanism deformed at that\n"
    "        rotation of body 1\n"
    "  arch RESULTS.h5 --run KEY [--at LIST]   a run of --model blocks stored\n"
    "        with --history: every voussoir at those times over the arch\n"
    "  domain --arch ARCH [--ratios LIST] [--cor C]   the half-cycle collapse\n"
    "        domain: shortest collapsing pulse against a/(lambda0 g)\n"
    "  suite RESULTS.h5   record x arch map of the verdict (worst over scales\n"
    "        and polarities: collapse, or peak rotation / q_c)\n"
    "  capacity CAPACITY.h5 [--arch NAME] [--x qc|rad] [--y scale|pga] [--im IM]\n"
    "        a file of archquake capacity -o, one arch (default: the file's\n"
    "        first): a strip per record and polarity with the verdict at every\n"
    "        scanned scale (--y scale: the scale factor, the default; --y pga:\n"
    "        the PGA in g), shaded by the survived runs' peak rotation (--x qc:\n"
    "        over q_c, the default; --x rad), red and hatched where it\n"
    "        collapses, a tick at each change, its first collapse beside it\n"
    "        (R: it survives again above a collapse); below, the lognormal\n"
    "        fragility of IM (pga_g, pgv_m_s, pgd_m, arias_m_s, cav_m_s,\n"
    "        pga_lambda0, or a spectral measure the file's fits hold:\n"
    "        sa_0.2s_g, sa_avg_0.1_1s_g; default pga_g) over the empirical\n"
    "        fraction of first collapses, censored records at their cap, and\n"
    "        the band of the median's interval\n"
    "  spectrum SPECTRA.h5 [--record NAME]   a file of archquake spectrum -o:\n"
    "        pseudo-spectral acceleration (g) against period (s, log axis), one\n"
    "        curve per record, component and damping\n"
    "ARCH: an arch file (.cfg), or an installed arch by name (oppenheim).\n";

/* A figure of plot: its --help is plot's. */
#define FIGURE(n) {.name = "plot " n, .title = "plot " n, .help_cmd = "plot"}

const aq_opt_command aq_opt_commands[AQ_CMD_N] = {
    [AQ_CMD_RUN] =
        {.name = "",
         .farmed = 1,
         .title = "the main job",
         .help_cmd = "",
         .synopsis = "[OPTIONS] RECORD... --arch FILE",
         .summary = "run records against arches",
         .head = "usage: archquake [OPTIONS] RECORD... --arch FILE [--arch FILE ...]\n"
                 "       archquake [OPTIONS] --components H1,H2[,V] ... --arch FILE ...\n"
                 "Run every record against every arch (and every scale factor): each record\n"
                 "is read and processed once.  One TSV row per run on stdout.\n",
         .tail = run_tail},
    [AQ_CMD_INFO] =
        {.name = "info",
         .title = "info",
         .help_cmd = "info",
         .synopsis = "info [OPTIONS] RECORD...",
         .summary = "describe records",
         .head = "usage: archquake info [OPTIONS] RECORD...\n"
                 "Describe accelerograms: one TSV row per record on stdout.\n",
         .tail = "Columns: file format npts dt_s duration_s units pga_g pgv_m_s pgd_m\n"
                 "  arias_m_s d5_95_s cav_m_s channel vertical pgv_pga_s, then one column\n"
                 "  per --im-periods T, sa_Ts_g, and sa_avg_T1_T2s_g (--sa-avg) (npts,\n"
                 "  duration_s: the record as read; the measures: the processed record,\n"
                 "  pads included; --no-filter --detrend none gives the record as read)\n"
                 "Exit status: 0 all records read, 1 some record failed, 2 bad options.\n",
         .heading = {[AQ_GROUP_PROCESSING] = "Processing (intensity measures are computed "
                                             "on the processed record):"}},
    [AQ_CMD_MECHANISM] =
        {.name = "mechanism",
         .title = "mechanism",
         .help_cmd = "mechanism",
         .synopsis = "mechanism --arch FILE",
         .summary = "static analysis of an arch",
         .head = "usage: archquake mechanism --arch FILE [--table] [--points N]\n"
                 "The hinge sets of an arch: one TSV row per set: primary, reverse, and\n"
                 "minimum, the admissible set of lowest lambda0 over every joint (the\n"
                 "primary itself without [hinges]; with [hinges] a lower one is warned of\n"
                 "on stderr: it governs unless its joints are restrained).  An arch whose\n"
                 "minimum lambda0 is <= 0 cannot stand and is refused (exit 1), naming the set.\n",
         .tail = "Columns: set joints faces lambda0 q_c_rad admissible act_sign q_sign mass_kg\n"
                 "  impact_vel_ratio end table_n table_err thrust_ecc searched reason\n"
                 "  control mu_required mu_joint lambda_friction\n"
                 "  q_c_rad is the rotation of body 1 about H1 at collapse (magnitude;\n"
                 "  q = q_sign * s); act_sign is the sign of the ground acceleration along +x\n"
                 "  that drives the set; end is why the path ends (peak: lambda = 0, toggle,\n"
                 "  hinge: a hinge closes); table_err is the measured relative error of the\n"
                 "  interpolation tables against the exact kinematics; thrust_ecc is the\n"
                 "  largest eccentricity |r - R|/(t/2) of the line of thrust over the joints\n"
                 "  at q = 0 (<= 1: the thrust stays inside, lambda0 is also a lower bound).\n"
                 "  impact_vel_ratio is the set's velocity after an impact arriving from the\n"
                 "  other set over the velocity before (momentum rule); <= 0: the arch stops.\n"
                 "  control is the arch's hinges, fixed or free ([hinges] control).\n"
                 "  mu_required is the largest |T|/N (shear over normal force) over every\n"
                 "  joint in the set's collapse state at lambda0 (inf: the resultant pulls\n"
                 "  on some joint; nan: no collapse state), mu_joint that joint.\n"
                 "  lambda_friction, with a friction (--friction or [contact] friction;\n"
                 "  else nan), is the largest lambda of the set's direction at which a line\n"
                 "  of thrust lies inside the arch with |T| <= mu N at every joint: lambda0\n"
                 "  of that direction's minimum when mu >= its mu_required, less below.  An\n"
                 "  arch that needs more friction than given even at rest is refused (exit\n"
                 "  1), naming the joint.\n"
                 "Table columns: set s_rad q_rad lambda lambda_eq x_m y_m pe_j mgen_kgm2\n"
                 "  min_normal_n (lambda by virtual work and by the 9x9 equilibrium; pe_j =\n"
                 "  m_T g y; min_normal_n the smallest compressive hinge force; thrust_ecc\n"
                 "  as above, in the deformed arch at lambda(q)).\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded (the arch\n"
                 "is mechanism's input, as a record is info's), 2 bad options.\n"},
    [AQ_CMD_PULSE] =
        {.name = "pulse",
         .title = "pulse",
         .help_cmd = "pulse",
         .synopsis = "pulse --arch FILE --accel-g A --duration S",
         .summary = "one pulse",
         .head = "usage: archquake pulse --arch FILE --accel-g A --duration S [OPTIONS]\n"
                 "A rectangular ground-acceleration pulse of A g (signed along +x) from\n"
                 "t = 0 for S seconds, then zero; prints one TSV row (header + row).\n",
         .tail = "Columns: model accel_g duration_s end_s collapsed collapse_time_s\n"
                 "  peak_rotation_rad peak_displacement_m max_kinetic_energy_j impacts\n"
                 "  reversals energy_in_j energy_dissipated_j steps_moving evals, then\n"
                 "  under the four-hinge models status (ok, slides, beyond, slides+beyond:\n"
                 "  the main job's marks) mu_demand mu_demand_joint thrust_ecc_max\n"
                 "  thrust_ecc_time_s slide_time_s (docs/demand.md), under --model blocks\n"
                 "  max_slip_m hinges_observed hinges_first_s mechanism_changed_s\n"
                 "  friction_work_j (docs/blocks.md)\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded, or the run\n"
                 "failed, 2 bad options (or an option the arch makes ineffective, as --cor\n"
                 "with impact momentum), 3 the history could not be written.\n"},
    [AQ_CMD_DOMAIN] =
        {.name = "domain",
         .title = "domain",
         .help_cmd = "domain",
         .synopsis = "domain --arch FILE",
         .summary = "half-cycle collapse domain",
         .head = "usage: archquake domain --arch FILE [OPTIONS]\n"
                 "Half-cycle collapse domain: for each ratio r, the shortest rectangular\n"
                 "pulse of r lambda0 g (direction opening the primary set) that collapses\n"
                 "the arch, by bisection (the direction is the set's own, so domain takes no\n"
                 "--polarity).\n",
         .tail = "Columns: ratio accel_g min_duration_s (inf: no collapse up to\n"
                 "  --max-duration) status (the shortest collapsing pulse's run marked as\n"
                 "  the main job's: ok, slides with a friction given, beyond with free\n"
                 "  hinges, slides+beyond; - when none collapses)\n"
                 "Exit status: 0 success, 1 an arch file that cannot be loaded, or a run\n"
                 "failed, 2 bad options (or an option the arch makes ineffective, as --cor\n"
                 "with impact momentum).\n"},
    [AQ_CMD_COMPARE] =
        {.name = "compare",
         .title = "compare",
         .help_cmd = "compare",
         .synopsis = "compare A.h5 B.h5",
         .summary = "regression check",
         .head = "usage: archquake compare A.h5 B.h5 [--rtol R] [--atol A] [--ignore NAME]...\n"
                 "Compare two results files (archquake ... -o FILE.h5).  First their\n"
                 "configuration: processing options, model, cor, version (shown only), and\n"
                 "the content (sha256) of records and arches of one name.  Then run by run,\n"
                 "matched by identity: the record's content, the arch's name and .cfg\n"
                 "content, the scale and the polarity (however the files were spelt on the\n"
                 "command line).  Numbers agree when |a-b| <= A + R*max(|a|,|b|) (NaN equals\n"
                 "NaN); collapsed, impacts, model and status must be equal.\n",
         .tail = "Each difference is a TSV row on stdout: record arch scale polarity field a b\n"
                 "rel_diff.  Configuration rows come first, with * for what they are not\n"
                 "about (field = the setting, record_sha256 or arch_sha256); field \"present\"\n"
                 "marks a run found in only one file.  Records are named by file name.  A file\n"
                 "of the first format (no hashes) is read too: records and arches then match\n"
                 "by name.\n"
                 "Exit status: 0 all runs and settings agree (a different version alone is\n"
                 "shown but agrees), 1 some differ, 2 bad options or a file that cannot be\n"
                 "read as a results file.\n"},
    [AQ_CMD_CAPACITY] =
        {.name = "capacity",
         .farmed = 1,
         .title = "capacity",
         .help_cmd = "capacity",
         .synopsis = "capacity RECORD... --arch FILE",
         .summary = "collapse scales, fragility",
         .head = "usage: archquake capacity RECORD|--components H1,H2[,V]... --arch FILE "
                 "[--arch FILE ...] [OPTIONS]\n"
                 "For each record, arch and polarity, every scale factor at which the arch's\n"
                 "verdict (collapse or not) changes, from the scale at which it first moves\n"
                 "to --scale-max (docs/capacity.md).  One TSV row per (record, arch,\n"
                 "polarity) on stdout.\n",
         .tail = "Columns: record arch polarity status move_scale first_collapse_scale\n"
                 "  first_collapse_pga_g first_collapse_pgv_m_s collapse_intervals\n"
                 "  resurrection runs scale_max first_mark_scale, with --components also\n"
                 "  azimuth_deg first_collapse_scale_min first_collapse_scale_max (the range\n"
                 "  over the azimuths where it collapses)  (status: ok, never_moves,\n"
                 "  slides, beyond, slides+beyond, read:CODE, process:CODE, arch:CODE,\n"
                 "  run:CODE; intervals lo-hi;lo-hi, hi inf when collapse holds at the cap)\n"
                 "  slides: with a friction given, a run up to the first collapse (every\n"
                 "  run when none collapses) asked more of a joint; beyond: with free\n"
                 "  hinges, its thrust left a joint's section; first_mark_scale: the lowest\n"
                 "  scale of such a run (nan: none; --model blocks follows them)\n"
                 "Exit status: 0 all done, 1 some record or run failed (reported; the others\n"
                 "ran), 2 bad options or an arch file that cannot be loaded (nothing ran),\n"
                 "3 an output could not be written.\n",
         .heading = {[AQ_GROUP_ORIENTATION] =
                         "Orientation (--azimuth all: each row is the worst azimuth, lowest\n"
                         "first_collapse_scale, no collapse last, with the range over the\n"
                         "azimuths; --azimuth DEG gives one azimuth's; -o and --fragility\n"
                         "take plain RECORDs only):"}},
    [AQ_CMD_SPECTRUM] =
        {.name = "spectrum",
         .title = "spectrum",
         .help_cmd = "spectrum",
         .synopsis = "spectrum RECORD...",
         .summary = "response spectra, RotD50/RotD100",
         .head = "usage: archquake spectrum RECORD|--components H1,H2 ... [--periods LIST]\n"
                 "       [--damping LIST] [-o FILE.h5] [OPTIONS]\n"
                 "Elastic response spectra (pseudo-spectral acceleration, 5 % damping by\n"
                 "default) of processed records: for a RECORD its own, for two horizontal\n"
                 "components their RotD50, RotD100 (Boore 2010, 180 angles) and geometric\n"
                 "mean (docs/spectrum.md).  --no-filter --detrend none: the records as\n"
                 "read.  One TSV row per (record, component, damping, period) on stdout.\n",
         .tail = "Columns: record component damping period_s psa_g sd_m psv_m_s\n"
                 "  (component: the record's channel, or RotD50, RotD100, GeoMean for a\n"
                 "  pair; sd_m = PSA / omega^2, psv_m_s = PSA / omega).  Periods below 2 dt\n"
                 "  lie above a record's Nyquist frequency: they are computed for the\n"
                 "  record as linear between samples (PSA -> PGA as T -> 0), with a warning.\n"
                 "Exit status: 0 success; 1 a record could not be read or processed, or a\n"
                 "pair does not fit (each said in one line; nothing is written); 2 bad\n"
                 "options; 3 the output file could not be written.\n"},
    [AQ_CMD_SELECT] =
        {.name = "select",
         .title = "select",
         .help_cmd = "select",
         .synopsis = "select POOL... --target SPEC --count N",
         .summary = "choose and scale a suite to a target spectrum",
         .head = "usage: archquake select POOL... --target SPEC --count N [--periods T1,T2]\n"
                 "       [--scale-range LO,HI] [--max-per-event K] [--components H1,H2 ...]\n"
                 "       [--text SUITE.tsv] [-o SUITE.h5] [OPTIONS]\n"
                 "Choose N records of the pool (records, directories of records, or quoted\n"
                 "globs; or pairs with --components), each scaled to bring its spectrum\n"
                 "closest to the target in the log over the period range, whose mean\n"
                 "spectrum has the least misfit to the target and meets the code's\n"
                 "conditions: the mean nowhere below 90 % of the target over the range, for\n"
                 "Eurocode 8 the mean PGA at least a_g S, at most K records of one event.  A\n"
                 "suite that falls short is raised by one common factor within the scale\n"
                 "range.  Every suite is tried when the combinations are at most 2e6, else\n"
                 "greedy selection then swaps (Jayaram, Lin & Baker 2011) (docs/select.md).\n"
                 "The suite file (TSV: comment lines, then record channel scale misfit\n"
                 "event) goes to stdout or --text; the main job and capacity run it with\n"
                 "--suite.\n",
         .tail = "Exit status: 0 a suite that meets every condition was written; 1 some\n"
                 "pool member could not be used (each named; the suite is chosen from the\n"
                 "others), fewer than N usable, or no suite meets the conditions (how far\n"
                 "the best falls short, and where, is said; nothing is written unless\n"
                 "--best-effort); 2 bad options, target or range, or a pool of fewer than N\n"
                 "records; 3 an output could not be written (no partial file is left).\n",
         .heading = {[AQ_GROUP_PROCESSING] = "Processing (the pool is processed as the main "
                                             "job processes records):"}},
    [AQ_CMD_PLOT] = {.name = "plot",
                     .title = "plot",
                     .help_cmd = "plot",
         .synopsis = "plot FIGURE ... -o FILE",
         .summary = "figures (history arch domain suite capacity spectrum)",
                     .head = plot_head,
                     .tail = "Exit status: 0 drawn, 1 an input could not be read or drawn (a\n"
                             "results file, or an arch file that cannot be loaded), 2 bad\n"
                             "options, 3 the figure or the data could not be written.\n",
                     .heading = {[AQ_GROUP_MAIN] = "Options:"}},
    [AQ_CMD_HELP] =
        {.name = "help",
         .title = "help",
         .help_cmd = "help",
         .synopsis = "help [COMMAND|arch-file]",
         .summary = "a command's --help; the arch file's keys",
         .head = "usage: archquake help [COMMAND|arch-file]\n"
                 "Print COMMAND's --help (archquake COMMAND --help); without a COMMAND,\n"
                 "archquake --help; with arch-file, the arch file's sections and keys\n"
                 "(units, ranges, defaults), shapes, joints and faces files.\n",
         .tail = "Exit status: 0 printed, 2 an unknown COMMAND or bad options.\n",
         .heading = {[AQ_GROUP_MAIN] = "Options:"}},
    [AQ_CMD_PLOT_HISTORY] = FIGURE("history"),
    [AQ_CMD_PLOT_ARCH] = FIGURE("arch"),
    [AQ_CMD_PLOT_DOMAIN] = FIGURE("domain"),
    [AQ_CMD_PLOT_SUITE] = FIGURE("suite"),
    [AQ_CMD_PLOT_CAPACITY] = FIGURE("capacity"),
    [AQ_CMD_PLOT_SPECTRUM] = FIGURE("spectrum"),
    [AQ_CMD_REPORT] =
        {.name = "report",
         .title = "report",
         .help_cmd = "report",
         .synopsis = "report FILE.h5 ... -o F.html",
         .summary = "one HTML page to hand on",
         .head = "usage: archquake report FILE.h5 ... -o REPORT.html\n"
                 "One self-contained HTML page of a screening, to hand on: per arch its\n"
                 "verdict table (sortable, filterable by verdict) and figures (the arch\n"
                 "and its hinge sets, the suite's verdict map, the history of each\n"
                 "collapsed run and of the strongest surviving one when the results hold\n"
                 "histories), the capacity files' first collapses, collapse intervals,\n"
                 "fragility curves and the ranking of the intensity measures, the failed\n"
                 "records with their reasons, and the run: command line, build, date,\n"
                 "options, every record and every arch.  Figures are inline SVG, text as\n"
                 "text; nothing is fetched; it prints on A4 and Letter (docs/report.md).\n"
                 "Each FILE.h5 in its section, whatever their order: at most one\n"
                 "results file of the main job (archquake ... -o), and any files of\n"
                 "archquake capacity -o, select -o (its suite: the target, checks,\n"
                 "spectra, records) and spectrum -o (its spectra: a figure and a table);\n"
                 "without a results file, the run is the first file's.\n",
         .tail = "Exit status: 0 written, 1 an input could not be read, 2 bad options,\n"
                 "3 the page could not be written.  No partial file is left under FILE.\n",
         .heading = {[AQ_GROUP_MAIN] = "Options:"}},
};

const aq_opt_note aq_opt_environment[] = {
    {"XDG_CACHE_HOME", "the cache of processed records and built arches, and FFTW's wisdom, "
                       "are kept in $XDG_CACHE_HOME/archquake (an absolute path; "
                       "docs/cache.md)"},
    {"HOME", "without XDG_CACHE_HOME, the cache is ~/.cache/archquake; with neither "
             "there is none"},
    {"ARCHQUAKE_DATADIR", "--arch NAME looks for NAME.cfg in $ARCHQUAKE_DATADIR/arches "
                          "first (Arches, above)"},
    {"LC_PAPER", "plot: the page of a PDF without --paper, Letter or A4 (the locale's, as "
                 "LC_ALL, LC_PAPER and LANG set it)"},
    {NULL, NULL}};

const aq_opt_note aq_opt_files[] = {
    {"~/.cache/archquake/records/, arches/",
     "the cache (or under $XDG_CACHE_HOME/archquake, or --cache-dir): one entry per "
     "processed record and per built arch, for later runs of the same build; at most "
     "--cache-max (default 512M); removing it loses nothing but time"},
    {"~/.cache/archquake/fftw-wisdom", "FFTW's plans for record lengths the built-in "
                                       "wisdom lacks"},
    {"FILE.h5.journal", "beside a results file being written with -o: the records done, "
                        "until the file is complete (--resume reads it)"},
    {NULL, NULL}};

void aq_opts_init(aq_opts *o, aq_cmd cmd)
{
  memset(o, 0, sizeof *o);
  aq_signal_opts_default(&o->proc);
  aq_opt_orient_init(&o->orient);
  long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  o->threads = ncpu >= 1 ? (ncpu > AQ_MAX_THREADS ? AQ_MAX_THREADS : ncpu) : 1;
  o->model = AQ_MODEL_WORKPATH;
  o->cor = NAN;
  o->friction = NAN;
  o->blocks_dt_s = AQ_BLOCKS_DT_DEFAULT_S;
  o->cmd = (int)cmd;
  o->impact = -1;
  o->ode_rtol = 1e-10;
  o->polarity = AQ_POLARITY_AUTO; /* aq_opt_polarity_resolve, once the arches are loaded */
  if (cmd == AQ_CMD_RUN) { /* the main job: spectral measures only when named; their
                              13 periods over the padded records cost more than
                              everything else it does (docs/spectrum.md) */
    o->proc.im_nsa = 0;
    o->proc.sa_avg_lo_s = o->proc.sa_avg_hi_s = 0;
  }
  o->scale_to_pga_g = NAN;
  o->scale_max = NAN;
  o->resolution = AQ_SCAN_RESOLUTION_DEFAULT;
  o->scan_tol = AQ_SCAN_TOL_DEFAULT;
  o->points = 101;
  o->accel_g = o->duration_s = o->end_s = o->max_end_s = NAN;
  o->pulse_dt_s = 0.01;
  o->domain_tol_s = 1e-9;
  o->max_duration_s = 100;
  o->paper = -1;
  o->check_blocks = -1;
  o->rtol = AQ_COMPARE_RTOL_DEFAULT;
  o->range_s[0] = o->range_s[1] = NAN;
  o->scale_range[0] = AQ_SELECT_SCALE_LO_DEFAULT;
  o->scale_range[1] = AQ_SELECT_SCALE_HI_DEFAULT;
  o->atol = AQ_COMPARE_ATOL_DEFAULT;
}

void aq_opts_free(aq_opts *o)
{
  free(o->arches);
  free(o->scales);
  free(o->ratios);
  free(o->at_s);
  free(o->periods);
  free(o->dampings);
  free(o->period_grid);
  o->period_grid = NULL;
  o->nperiod_grid = 0;
  o->periods = o->dampings = NULL;
  o->nperiods = o->ndampings = 0;
  aq_opt_orient_free(&o->orient);
  o->arches = NULL;
  o->scales = o->ratios = NULL;
  o->narches = o->nscale = o->nratios = 0;
}

int aq_opt_applies(aq_opt_id id, aq_cmd cmd)
{
  return (unsigned)id < AQ_OPT_N && (unsigned)cmd < AQ_CMD_N &&
         (aq_opt_rows[id].cmds >> cmd & 1u);
}
