/* opt_table.h: every option of every command, declared once, in one table
 * (aq_opt_rows in opt_table.c): its name, the kind and range of its
 * argument, where its value goes (a field of aq_opts), the commands it
 * applies to and its help text.  One function parses every command's
 * options through it (opt_parse.c): a bad value, an unknown option and an
 * option of another command are each reported in one line, all of them,
 * before anything is read.  --help, `archquake help COMMAND` and the man
 * page (tools/man.sh reads --help) are written from the same table.
 *
 * To add an option:
 *   1. an id in aq_opt_id below (the order of the ids is the order of
 *      --help within a group);
 *   2. its row in aq_opt_rows[] (opt_table.c): name, short letter or 0,
 *      kind (AQ_ARG_*), metavariable, range lo..hi, destination
 *      (DEST(field) of aq_opts, or a handler for AQ_ARG_CUSTOM, in
 *      opt_handlers.c and declared in opt_table_impl.h), the
 *      commands it applies to (C(RUN) | C(CAPACITY) ...), group, help;
 *   3. its field in aq_opts, and its default in aq_opts_init
 *      (opt_commands.c) if not 0.
 *   The message of a bad value names the option as "--name", or "-x" if it
 *   has a letter.  .required: the commands that cannot run without it.
 *   .requires, .conflicts, .not_below, .not_above: the options it needs,
 *   cannot be given with, and whose values bound its own (--history needs
 *   -o; --scale-to-pga and --scale exclude each other; pulse --end >=
 *   --duration), each rule declared once, on one of its rows.  .check:
 *   a check against other options' values that those cannot say
 *   (--ode-rtol needs --model ode), made for every command it applies to.  The same name may have one row per meaning (--dt of text records and
 *   --dt of pulse), each for commands of its own: no command has two rows
 *   of one name (test_opt_table.c checks).  Checks that need the operands
 *   or the files stay in the command, after aq_opts_parse.
 *
 * To add a command:
 *   1. an id in aq_cmd (before AQ_CMD_PLOT: plot's figures stay last, in a
 *      row) and its row in aq_opt_commands[] (opt_commands.c): its name, title,
 *      synopsis and summary (archquake --help's list of commands), usage
 *      line and description, and the end of its --help (columns, exit
 *      status);
 *   2. its bit, C(NAME), in the rows of the options it takes (--help's row
 *      applies to every command already);
 *   3. in cmd_NAME.c:
 *        aq_opts o;
 *        aq_opts_init(&o, AQ_CMD_NAME);
 *        int nerr = 0;
 *        if (aq_opts_parse(AQ_CMD_NAME, argc, argv, &o, &nerr)) {  // --help
 *          aq_opts_free(&o);
 *          return AQ_EXIT_OK;
 *        }
 *        // operands: argv[optind .. argc); checks between options: nerr++
 *        if (nerr) { aq_opts_free(&o); return AQ_EXIT_USAGE; }
 *        ... o.field ...; aq_opts_free(&o);
 *   4. its entry point in dispatch.c's entry[] (dispatch.c runs it by
 *      name, and archquake --help lists it from its row's synopsis and
 *      summary; the table names no function of the commands, so calls run
 *      one way: dispatch -> cmd_*.c -> opt_*.c); .farmed if archquake-mpi
 *      spreads its tasks over the ranks (farm.h).
 */
#ifndef AQ_APP_OPT_TABLE_H
#define AQ_APP_OPT_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "../io/record.h"
#include "../signal/signal.h"
#include "opt_orient.h"

/* The commands (and plot's figures, which take options of their own). */
typedef enum {
  AQ_CMD_RUN = 0, /* archquake [OPTIONS] RECORD... --arch FILE: the main job */
  AQ_CMD_INFO,
  AQ_CMD_MECHANISM,
  AQ_CMD_PULSE,
  AQ_CMD_DOMAIN,
  AQ_CMD_COMPARE,
  AQ_CMD_CAPACITY,
  AQ_CMD_REPORT, /* archquake report RESULTS.h5 [CAPACITY.h5 ...] -o FILE.html */
  AQ_CMD_SPECTRUM, /* archquake spectrum RECORD... */
  AQ_CMD_SELECT,   /* archquake select POOL... --target SPEC --count N */
  AQ_CMD_HELP,     /* archquake help [COMMAND] */
  AQ_CMD_PLOT, /* plot's --help; its figures parse as the five below */
  AQ_CMD_PLOT_HISTORY,
  AQ_CMD_PLOT_ARCH,
  AQ_CMD_PLOT_DOMAIN,
  AQ_CMD_PLOT_SUITE,
  AQ_CMD_PLOT_CAPACITY,
  AQ_CMD_PLOT_SPECTRUM,
  AQ_CMD_N
} aq_cmd;
/* plot's figures: AQ_CMD_PLOT < cmd < AQ_CMD_N. */
#define AQ_CMD_IS_FIGURE(c) ((c) > AQ_CMD_PLOT && (c) < AQ_CMD_N)

/* The options, in the order --help lists them within a group. */
typedef enum {
  AQ_OPT_ARCHES = 0, /* --arch, repeatable (run, capacity) */
  AQ_OPT_ARCH,       /* --arch, one (mechanism, pulse, domain, plot) */
  AQ_OPT_ARCH_NAME,  /* --arch NAME of a capacity file (plot capacity) */
  AQ_OPT_ARCH_DRAWN, /* --arch FILE, or NAME with a results file (plot arch) */
  AQ_OPT_ACCEL_G,
  AQ_OPT_DURATION,
  AQ_OPT_END,
  AQ_OPT_MAX_END,
  AQ_OPT_PULSE_DT,
  AQ_OPT_RATIOS,
  AQ_OPT_OUTPUT,      /* -o FILE.h5 */
  AQ_OPT_PLOT_OUTPUT, /* -o FILE.png|svg|pdf */
  AQ_OPT_REPORT_OUTPUT, /* -o FILE.html */
  AQ_OPT_TEXT,
  AQ_OPT_FRAGILITY,
  AQ_OPT_DATA,
  AQ_OPT_PAPER,
  AQ_OPT_RUN,
  AQ_OPT_RECORD, /* plot spectrum */
  AQ_OPT_ROTATION,
  AQ_OPT_AT,       /* plot arch --run: the times */
  AQ_OPT_CHECK,    /* the main job: --check blocks */
  AQ_OPT_IM,
  AQ_OPT_X,
  AQ_OPT_Y,
  AQ_OPT_SCALE,
  AQ_OPT_SCALE_TO_PGA,
  AQ_OPT_SCALE_TO_LAMBDA0,
  AQ_OPT_SCALE_MAX,
  AQ_OPT_RESOLUTION,
  AQ_OPT_SCAN_TOL,
  AQ_OPT_DOMAIN_TOL,
  AQ_OPT_MAX_DURATION,
  AQ_OPT_JOBS,
  AQ_OPT_MODEL,
  AQ_OPT_COR,
  AQ_OPT_FRICTION,
  AQ_OPT_BLOCKS_DT,    /* --model blocks: its time step */
  AQ_OPT_IMPACT,
  AQ_OPT_ODE_RTOL,
  AQ_OPT_HISTORY,      /* the main job: histories into the results file */
  AQ_OPT_HISTORY_FILE, /* pulse: the history as CSV */
  AQ_OPT_STORE_RECORDS,
  AQ_OPT_RESUME,
  AQ_OPT_POLARITY,
  AQ_OPT_TABLE,
  AQ_OPT_POINTS,
  AQ_OPT_RTOL,
  AQ_OPT_ATOL,
  AQ_OPT_IGNORE,
  AQ_OPT_QUIET,
  AQ_OPT_PERIODS,       /* spectrum */
  AQ_OPT_DAMPING,
  AQ_OPT_IM_PERIODS,    /* the spectral intensity measures */
  AQ_OPT_SA_AVG,
  AQ_OPT_PEAKS,         /* where a spectral peak is taken */
  AQ_OPT_SAMPLED_PEAKS, /* --peaks samples */
  AQ_OPT_TARGET,        /* select, plot spectrum */
  AQ_OPT_COUNT,         /* select */
  AQ_OPT_SELECT_PERIODS,
  AQ_OPT_PERIOD_GRID,
  AQ_OPT_SCALE_RANGE,
  AQ_OPT_MAX_PER_EVENT,
  AQ_OPT_BEST_EFFORT,
  AQ_OPT_FRAGILITY_IN,
  AQ_OPT_ARCH_FRAGILITY,
  AQ_OPT_SUITE,         /* the main job and capacity: a suite file of select */
  AQ_OPT_HELP,
  AQ_OPT_VERSION,
  /* reading records */
  AQ_OPT_UNITS,
  AQ_OPT_READ_DT,
  AQ_OPT_COLUMN,
  AQ_OPT_COMPONENT,
  AQ_OPT_ACCEPT_IMPLAUSIBLE,
  AQ_OPT_ACCEPT_VERTICAL,
  AQ_OPT_RESPONSE,
  /* orientation */
  AQ_OPT_COMPONENTS,
  AQ_OPT_AZIMUTHS,
  AQ_OPT_AZIMUTH,
  AQ_OPT_ALL_AZIMUTHS,
  AQ_OPT_VERTICAL,
  /* processing */
  AQ_OPT_DETREND,
  AQ_OPT_TAPER,
  AQ_OPT_HIGHPASS,
  AQ_OPT_ORDER,
  AQ_OPT_LOWPASS,
  AQ_OPT_NO_FILTER,
  AQ_OPT_MERGE_TOL,
  AQ_OPT_NO_CACHE,  /* prepared records on disk (docs/cache.md) */
  AQ_OPT_CACHE_DIR,
  AQ_OPT_CACHE_MAX,
  AQ_OPT_N
} aq_opt_id;

/* The groups of --help, in this order; each but the first under a heading. */
typedef enum {
  AQ_GROUP_MAIN = 0,
  AQ_GROUP_READING,     /* "Reading:" */
  AQ_GROUP_ORIENTATION, /* "Orientation:" */
  AQ_GROUP_PROCESSING,  /* "Processing:" */
  AQ_GROUP_N
} aq_opt_group;

/* The kinds of argument and what the parser stores. */
typedef enum {
  AQ_ARG_FLAG,      /* no argument: int = 1 */
  AQ_ARG_FLAG_OFF,  /* no argument: int = 0 */
  AQ_ARG_DOUBLE,    /* double in [lo, hi] */
  AQ_ARG_DOUBLE_GT, /* double in (lo, hi] */
  AQ_ARG_LONG,      /* long in [lo, hi] */
  AQ_ARG_INT,       /* int in [lo, hi] */
  AQ_ARG_SIZE,      /* size_t in [lo, hi] */
  AQ_ARG_LIST,      /* distinct doubles each in (lo, hi]: double * (malloc'd)
                       at dest, their count (size_t) at dest_n */
  AQ_ARG_CHOICE,    /* one of choices: int = its index */
  AQ_ARG_STRING,    /* const char * = the argument (argv's own) */
  AQ_ARG_CUSTOM     /* fn(arg, opts, nerr) checks and stores */
} aq_arg_kind;

/* Every option value of every command; aq_opts_init sets the defaults.
 * Strings point into argv; what is malloc'd is freed by aq_opts_free. */
typedef struct aq_opts {
  unsigned char given[AQ_OPT_N]; /* how often each option was given (<= 255) */
  int cmd;                       /* the aq_cmd being parsed */
  char *const *operands;         /* after parsing: the operands (argv's own) */
  int noperands;
  /* arches */
  char **arches;    /* --arch, repeatable: resolved paths (the array is malloc'd) */
  size_t narches;
  const char *arch; /* --arch, one: a resolved path; plot capacity: a name */
  /* outputs */
  const char *output;       /* -o */
  const char *text;         /* --text */
  const char *fragility;    /* --fragility */
  const char *data;         /* --data */
  const char *history_file; /* pulse --history */
  /* reading, orientation, processing */
  aq_read_opts read;
  char units_text[1024]; /* every --units as given, space-separated */
  aq_orient_opts orient;
  aq_signal_opts proc;
  double merge_tol_g; /* --merge-tol, g */
  int no_cache;          /* --no-cache */
  const char *cache_dir; /* --cache-dir, or NULL: the default */
  unsigned long long cache_max; /* --cache-max, bytes, or 0: the default */
  /* dynamics */
  int model;       /* --model: an aq_model */
  double cor;      /* --cor, or NAN: each arch's own */
  double friction; /* --friction, or NAN: each arch's [contact] friction */
  double blocks_dt_s; /* --blocks-dt: the block model's step, s */
  int impact;      /* --impact: 0 cor, 1 momentum, -1 the arch's own */
  double ode_rtol; /* --ode-rtol */
  int polarity;    /* --polarity: AQ_POLARITY_* (opt.h) */
  /* the main job */
  double *scales; /* --scale */
  size_t nscale;
  double scale_to_pga_g;   /* --scale-to-pga, or NAN */
  double scale_to_lambda0; /* --scale-to-lambda0, or 0 */
  long threads;            /* -j */
  int history, store_records, resume, quiet;
  /* capacity */
  double scale_max;  /* --scale-max, or NAN */
  double resolution; /* --resolution */
  double scan_tol;   /* --tol (relative) */
  /* mechanism */
  int table;
  long points;
  /* pulse */
  double accel_g, duration_s, end_s, max_end_s, pulse_dt_s;
  /* domain (and plot domain) */
  double *ratios;
  size_t nratios;
  double domain_tol_s, max_duration_s;
  /* compare */
  double rtol, atol;
  const char *ignore[32]; /* --ignore names, pointing into ignore_buf */
  char ignore_buf[32][64];
  size_t nignore;
  /* spectrum */
  double *periods; /* --periods, s (NULL: PEER's 111) */
  size_t nperiods;
  double *dampings; /* --damping, ratios (NULL: 0.05) */
  size_t ndampings;
  int sampled_peaks; /* --sampled-peaks: the same as --peaks samples */
  /* select */
  const char *target;      /* --target SPEC (select, plot spectrum) */
  size_t count;            /* --count N */
  double range_s[2];       /* --periods T1,T2 of select, s (NAN: not given) */
  double *period_grid;     /* --period-grid, s (NULL: PEER's within the range) */
  size_t nperiod_grid;
  double scale_range[2];   /* --scale-range LO,HI */
  size_t max_per_event;    /* --max-per-event K (0: no limit) */
  int best_effort;         /* --best-effort */
  const char *fragility_in; /* select --fragility FILE (capacity's fits) */
  const char *suite;       /* --suite FILE (the main job, capacity) */
  /* plot */
  const char *run, *im, *record;
  int x_rad, y_pga; /* --x, --y: index in their choices */
  int paper;        /* --paper: 0 a4, 1 letter; -1 (default) the locale's */
  double rotation_rad;
  double *at_s; /* plot arch --at */
  int check_blocks; /* --check blocks: 0; not given: -1 */
  size_t nat;
} aq_opts;

/* One option (a row of the table). */
typedef struct {
  const char *name;   /* long name, without "--" */
  char short_name;    /* -o, -j, -q; 0: none */
  aq_arg_kind kind;
  const char *meta;   /* the argument in --help ("FILE"); NULL for flags */
  double lo, hi;      /* the range (numbers; LIST: each item) */
  int hi_open;        /* LIST: hi itself is outside (--damping: each in (0, 1)) */
  /* A value of 0 asks for nothing (--taper 0: no taper): it conflicts with
   * no option (a .conflicts rule holds only between values that conflict,
   * so --no-filter --taper 0 is no conflict). */
  int zero_is_off;
  const char *const *choices; /* AQ_ARG_CHOICE: NULL-terminated */
  size_t dest, dest_n;        /* offsetof(aq_opts, ...) */
  /* AQ_ARG_CUSTOM: checks arg and stores it; other kinds: called after the
   * value is stored (what else the option sets); NULL: nothing */
  void (*fn)(char *arg, aq_opts *o, int *nerr);
  /* AQ_ARG_CUSTOM options of reading and orientation: their own handler
   * checks arg and adds it to o->read (opt_record.h) or o->orient
   * (opt_orient.h); NULL: none */
  void (*read_fn)(const char *arg, aq_read_opts *ro, int *nerr);
  void (*orient_fn)(const char *arg, aq_orient_opts *oo, int *nerr);
  unsigned cmds;      /* the commands it applies to: bit 1u << aq_cmd */
  aq_opt_group group;
  const char *help;   /* one paragraph, wrapped by --help */
  const char *meta2, *help2; /* a second form (--units GLOB=U), or NULL */
  unsigned required;  /* the commands that need it (a subset of cmds): "expected
                         --name META, got none" when it is not given */
  /* Rules between this option and others, declared here once and made by
   * aq_opts_parse when this option is given, for every command that takes
   * both: each a list of option ids ending in -1 (OPTS(...) of
   * opt_table_impl.h), NULL for none.  A broken rule is one line naming both
   * options; nothing is run. */
  const int *requires;  /* each of these must be given too */
  const int *conflicts; /* none of these may be given with it */
  const int *not_below; /* its value >= each of these options' (given or default) */
  const int *not_above; /* its value <= each of these options' */
  const char *why;      /* why, in parentheses in the requires and conflicts lines */
  /* A check between this option and the values of others that the rules
   * above cannot say, made once every option is in, for every command the
   * row applies to (given or not): one line per problem, *nerr
   * incremented.  NULL: none. */
  void (*check)(aq_opts *o, int *nerr);
} aq_opt_row;

/* One command: its name and what --help says besides its options (its
 * entry point: dispatch.c's entry[], by the same aq_cmd).  Dispatch (dispatch.c), archquake --help's list of commands,
 * `archquake help`, the manual page (tools/man.sh reads --help) and
 * archquake-mpi (mpi.c) read this table alone. */
typedef struct {
  const char *name;     /* as typed after archquake ("" the main job, "plot arch") */
  int farmed;           /* archquake-mpi spreads its tasks over the ranks */
  const char *title;    /* in messages: "the main job", "info", "plot arch" */
  const char *help_cmd; /* its --help: "archquake HELP_CMD --help" ("plot" for figures) */
  const char *synopsis; /* in archquake --help's list of commands, after "archquake " */
  const char *summary;  /* ... and what it does, in a few words (NULL: not listed) */
  const char *head;     /* usage line(s) and description, each line ending in '\n' */
  const char *tail;     /* after the options: columns, exit status */
  const char *heading[AQ_GROUP_N]; /* a group's heading, if not the default */
} aq_opt_command;

extern const aq_opt_row aq_opt_rows[AQ_OPT_N];
extern const aq_opt_command aq_opt_commands[AQ_CMD_N];

/* The environment variables archquake reads and the files it keeps, each
 * with what it does (a table each, ending in {NULL, NULL}), in archquake
 * --help's Environment and Files (and so the man page's ENVIRONMENT and
 * FILES).  A getenv() added anywhere gets its row here. */
typedef struct {
  const char *name, *help;
} aq_opt_note;
extern const aq_opt_note aq_opt_environment[], aq_opt_files[];

/* The defaults of every option for command cmd. */
void aq_opts_init(aq_opts *o, aq_cmd cmd);
/* Free what parsing allocated (o may be freed again). */
void aq_opts_free(aq_opts *o);

/* Parse argv[1..argc) as command cmd's options (getopt_long: operands are
 * moved to the end, from argv[optind]).  Each bad value, unknown option,
 * option cmd does not take, required option not given and failed check
 * between options (the rows' .check) is reported on stderr in one line and
 * counted in *nerr; parsing goes on, so that all are reported.  Returns 1
 * if --help was given (cmd's help is then printed on stdout), else 0. */
int aq_opts_parse(aq_cmd cmd, int argc, char **argv, aq_opts *o, int *nerr);

/* cmd's --help on f: head, options by group, tail.  AQ_CMD_PLOT lists the
 * options of every figure, each with the figures it applies to. */
void aq_opts_help(aq_cmd cmd, FILE *f);

/* archquake --help on f: the main job's help, the list of commands (their
 * synopses and summaries) and the paragraph on arch names. */
void aq_opts_main_help(FILE *f);

/* One entry of a help text on f: lab, then text (and note, if not NULL)
 * from column col (on the next line if lab reaches it), its words wrapped
 * at 79 columns. */
void aq_opt_help_entry(FILE *f, const char *lab, const char *text, const char *note, int col);

/* `archquake help arch-file` on f: the arch file's syntax, sections, keys
 * (unit, range, default, the shapes that take them), shapes, joints and
 * faces files, all from the table the parser reads (src/arch/cfg_keys.h;
 * help_arch.c). */
void aq_help_arch_file(FILE *f);
#define AQ_HELP_ARCH_FILE "arch-file" /* its word after help */

/* 1 if option id applies to command cmd. */
int aq_opt_applies(aq_opt_id id, aq_cmd cmd);

/* 1 if word spells option id ("--name", or "-x" for its letter). */
int aq_opt_is(aq_opt_id id, const char *word);

/* The command named word (not a figure, not the main job), or NULL. */
const aq_opt_command *aq_opt_command_named(const char *word);

/* "info, mechanism, ..., plot": every command's name, as typed, into
 * buf[n] (for the line that refuses an unknown one). */
void aq_opt_command_names(char *buf, size_t n);

/* The figure of plot named word ("history": the command "plot history"),
 * or -1 with one line naming the figures on stderr. */
int aq_opts_figure(const char *word);

#endif
