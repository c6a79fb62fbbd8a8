/* cfg_keys.h: every section and key of the arch file (.cfg), declared
 * once, in one table (aq_cfg_keys in cfg_keys.c): its section, name, kind,
 * unit, range, the shapes that take and need it, its default and its
 * help.  The parser (cfg.c) checks every key through it, so that a value
 * outside the range is refused in one line naming the range the table
 * states; `archquake help arch-file` and the manual page (tools/man.sh
 * reads it) print the same table, so the page and the parser cannot drift
 * apart.  The bounds of the lengths that the joints and faces files and
 * [masses] give (joints.c, cfg.c) are here too.  Nothing here prints.
 *
 * To add a key:
 *   1. its id in aq_cfg_key_id below (the order of the ids is the order
 *      of `archquake help arch-file` within its section);
 *   2. its row in aq_cfg_keys[] (cfg_keys.c): section, name, kind, the
 *      words of its messages ("a length"), unit, range, choices, the shapes
 *      that take and need it, default and help; a new section also gets its
 *      row in aq_cfg_sections[];
 *   3. what it sets, in cfg.c's handler (a number or a choice is checked
 *      and kept by the table's rules before the handler sees it: read it
 *      from c->num[id]).
 */
#ifndef AQ_ARCH_CFG_KEYS_H
#define AQ_ARCH_CFG_KEYS_H

#include <stddef.h>

/* The plausible range of every length of an arch file, m: a radius, span,
 * rise, thickness or depth (and each joint of a joints file) in
 * [AQ_CFG_LENGTH_MIN_M, AQ_CFG_LENGTH_MAX_M]; a coordinate (a joints or
 * faces file's points, [fill] level_m, a point mass's x and y) within
 * +-AQ_CFG_COORD_MAX_M.  Masonry arches span from about 0.1 m (laboratory
 * models) to about 100 m; the bounds leave a factor of 10 on either side. */
#define AQ_CFG_LENGTH_MIN_M 1e-3
#define AQ_CFG_LENGTH_MAX_M 1e3
#define AQ_CFG_COORD_MAX_M 1e3
/* Densities, kg/m^3: light fills (about 300) to the densest stone (about
 * 3000) and metals (lead, 11 340), with room on either side. */
#define AQ_CFG_DENSITY_MIN_KG_M3 10.0
#define AQ_CFG_DENSITY_MAX_KG_M3 2e4
/* A point mass, kg: up to a million tonnes per arch. */
#define AQ_CFG_MASS_MAX_KG 1e9
/* The Coulomb friction coefficient of a joint: dry masonry has about 0.4
 * to 0.8; above 1000 no joint of an arch could slide. */
#define AQ_CFG_FRICTION_MAX 1e3

/* The kinds of value. */
typedef enum {
  AQ_CFG_TEXT,   /* a label: 1..63 characters, no tab */
  AQ_CFG_CHOICE, /* one word of .choices (kept as its index) */
  AQ_CFG_PATH,   /* a file, relative to the .cfg's directory: 1..199 characters */
  AQ_CFG_REAL,   /* a decimal number in the range */
  AQ_CFG_INT,    /* an integer in the range */
  AQ_CFG_HINGES, /* four hinges JOINT FACE */
  AQ_CFG_MASS    /* [masses]: NAME = VOUSSOIR X_M Y_M MASS_KG, any NAME */
} aq_cfg_kind;

/* The keys, in the order of `archquake help arch-file` within a section. */
typedef enum {
  AQ_CFG_NAME = 0,
  AQ_CFG_SHAPE,
  AQ_CFG_RADIUS,
  AQ_CFG_EMBRACE,
  AQ_CFG_SPAN,
  AQ_CFG_RISE,
  AQ_CFG_THICKNESS,
  AQ_CFG_VOUSSOIRS,
  AQ_CFG_DENSITY,
  AQ_CFG_DEPTH,
  AQ_CFG_JOINTS_FILE,
  AQ_CFG_FACES_FILE,
  AQ_CFG_FILL_LEVEL,
  AQ_CFG_FILL_DENSITY,
  AQ_CFG_MASS_LINE,
  AQ_CFG_PRIMARY,
  AQ_CFG_REVERSE,
  AQ_CFG_CONTROL,
  AQ_CFG_FRICTION,
  AQ_CFG_EN,
  AQ_CFG_SPREAD,
  AQ_CFG_ABUTMENT,
  AQ_CFG_COR,
  AQ_CFG_IMPACT,
  AQ_CFG_G,
  AQ_CFG_NKEYS
} aq_cfg_key_id;

typedef struct {
  const char *section, *name; /* [section] name ("NAME" for [masses]) */
  aq_cfg_kind kind;
  const char *what;           /* in messages: "a length" (REAL, INT) */
  const char *unit;           /* "m", "deg", "kg/m^3", "m/s^2"; "" for none */
  double lo, hi;              /* REAL, INT: the range */
  int lo_open, hi_open;       /* 1: lo (hi) itself is outside */
  const char *const *choices; /* CHOICE: the words, NULL-terminated */
  unsigned shapes;            /* the shapes that take it: bit 1u << shape */
  unsigned required;          /* the shapes that need it */
  const char *deflt;          /* the default as text; NULL: none (required, or optional
                                 without one) */
  const char *help;           /* one paragraph */
} aq_cfg_key;

typedef struct {
  const char *name; /* "arch": [arch] */
  const char *help; /* one paragraph */
} aq_cfg_section;

extern const aq_cfg_key aq_cfg_keys[AQ_CFG_NKEYS];
extern const aq_cfg_section aq_cfg_sections[];
extern const size_t aq_cfg_nsections;

/* The shapes: their names (as `shape =` takes them, NULL-terminated) and
 * what each is, indexed alike. */
extern const char *const *const aq_cfg_shape_names;
extern const char *const aq_cfg_shape_help[];
extern const size_t aq_cfg_nshapes;

/* The joints file's and the faces file's header lines; their formats, as
 * printf formats of the bounds (joints: AQ_CFG_LENGTH_MIN_M,
 * AQ_CFG_LENGTH_MAX_M, AQ_CFG_COORD_MAX_M; faces: AQ_CFG_COORD_MAX_M, all
 * %g); the .cfg's syntax (plain text). */
extern const char aq_cfg_joints_header[], aq_cfg_faces_header[];
extern const char aq_cfg_joints_help[], aq_cfg_faces_help[], aq_cfg_syntax_help[];

/* The range of key k as text, "[0.001, 1000] m" or "4..1000", into buf[n]
 * (REAL and INT; "" for the other kinds). */
void aq_cfg_range_text(const aq_cfg_key *k, char *buf, size_t n);

/* 1 if x lies in key k's range (REAL, INT). */
int aq_cfg_in_range(const aq_cfg_key *k, double x);

#endif
