/* cfg_keys.c: the table of the arch file's sections and keys (see
 * cfg_keys.h for how to add one).  The parser (cfg.c) reads it; so do
 * `archquake help arch-file` and the manual page.  A key added here is
 * checked, refused with its range and documented at once: add keys here,
 * not in cfg.c alone. */
#include "cfg_keys.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model.h"

/* Which shapes take a key (bit 1 << aq_shape). */
#define S_ALL ((1u << AQ_SHAPE_COUNT) - 1)
#define S_CIRC (1u << AQ_SHAPE_CIRCULAR)
#define S_CURVE ((1u << AQ_SHAPE_POINTED) | (1u << AQ_SHAPE_ELLIPTICAL) | \
                 (1u << AQ_SHAPE_PARABOLIC) | (1u << AQ_SHAPE_CATENARY))
#define S_JOINTS (1u << AQ_SHAPE_JOINTS)

/* A length of the arch (> 0), and a coordinate. */
#define LENGTH .kind = AQ_CFG_REAL, .what = "a length", .unit = "m", \
               .lo = AQ_CFG_LENGTH_MIN_M, .hi = AQ_CFG_LENGTH_MAX_M
#define DENSITY .kind = AQ_CFG_REAL, .what = "a density", .unit = "kg/m^3", \
                .lo = AQ_CFG_DENSITY_MIN_KG_M3, .hi = AQ_CFG_DENSITY_MAX_KG_M3

static const char *const impacts[] = {"cor", "momentum", NULL}; /* aq_impact */
static const char *const controls[] = {"fixed", "free", NULL};  /* aq_hinge_control */

const aq_cfg_section aq_cfg_sections[] = {
    {"arch", "the arch: its shape, size and masonry (required)"},
    {"fill", "backfill above the extrados up to a horizontal level, carried by the "
             "voussoirs as rigid columns (optional; both keys when present)"},
    {"masses", "point masses (a statue, a wall) carried rigidly by a voussoir, one a line "
               "(optional)"},
    {"hinges", "the hinge sets and how they are chosen (optional: without a primary "
               "archquake searches every four-hinge set, and with control = free each "
               "direction of ground acceleration gets its own minimum-lambda0 set)"},
    {"contact", "the joints' contact (optional)"},
    {"supports", "the supports (optional; the block model, --model blocks)"},
    {"dynamics", "impacts and gravity (optional)"},
};
const size_t aq_cfg_nsections = sizeof aq_cfg_sections / sizeof aq_cfg_sections[0];

const aq_cfg_key aq_cfg_keys[AQ_CFG_NKEYS] = {
    [AQ_CFG_NAME] = {"arch", "name", AQ_CFG_TEXT, .shapes = S_ALL,
                     .deflt = "the file name without directory and .cfg",
                     .help = "the arch's label in every output row and in the HDF5 file; "
                             "1-63 characters, no tabs"},
    [AQ_CFG_SHAPE] = {"arch", "shape", AQ_CFG_CHOICE, .what = "a shape",
                      .choices = aq_shape_names, .shapes = S_ALL, .deflt = "circular",
                      .help = "the arch's centre line (Shapes, below); a key the shape "
                              "does not take is refused"},
    [AQ_CFG_RADIUS] = {"arch", "radius_m", LENGTH, .shapes = S_CIRC, .required = S_CIRC,
                       .help = "mean (centre-line) radius R; the intrados is at R - t/2, "
                               "the extrados at R + t/2"},
    [AQ_CFG_EMBRACE] = {"arch", "embrace_deg", AQ_CFG_REAL, .what = "an angle", .unit = "deg",
                        .lo = 0, .hi = 180, .lo_open = 1, .shapes = S_CIRC,
                        .required = S_CIRC,
                        .help = "angle between the springings, symmetric about the vertical "
                                "(180: a semicircle)"},
    [AQ_CFG_SPAN] = {"arch", "span_m", LENGTH, .shapes = S_CURVE, .required = S_CURVE,
                     .help = "distance between the springings of the centre line, which "
                             "run from (span/2, 0) to (-span/2, 0)"},
    [AQ_CFG_RISE] = {"arch", "rise_m", LENGTH, .shapes = S_CURVE, .required = S_CURVE,
                     .help = "height of the centre line's crown above its springings "
                             "(pointed: at least span_m/2)"},
    [AQ_CFG_THICKNESS] = {"arch", "thickness_m", LENGTH, .shapes = S_CIRC | S_CURVE,
                          .required = S_CIRC | S_CURVE,
                          .help = "thickness t of the ring, radial (circular: below 2 "
                                  "radius_m) or normal to the centre line, whose offsets by "
                                  "-t/2 and +t/2 are the intrados and the extrados"},
    [AQ_CFG_VOUSSOIRS] = {"arch", "voussoirs", AQ_CFG_INT, .what = "an integer", .lo = 4,
                          .hi = 1000, .shapes = S_CIRC | S_CURVE,
                          .required = S_CIRC | S_CURVE,
                          .help = "number of voussoirs, of equal length along the centre "
                                  "line; joints are numbered 0..voussoirs from the springing "
                                  "on the +x side (pointed: an even number)"},
    [AQ_CFG_DENSITY] = {"arch", "density_kg_m3", DENSITY, .shapes = S_ALL, .required = S_ALL,
                        .help = "density of the masonry"},
    [AQ_CFG_DEPTH] = {"arch", "depth_m", LENGTH, .shapes = S_ALL, .required = S_ALL,
                      .help = "out-of-plane depth; masses, inertias and energies are per "
                              "this depth"},
    [AQ_CFG_JOINTS_FILE] = {"arch", "joints_file", AQ_CFG_PATH, .shapes = S_JOINTS,
                            .required = S_JOINTS,
                            .help = "the joints, a CSV file (Joints file, below), relative "
                                    "to the .cfg's directory"},
    [AQ_CFG_FACES_FILE] = {"arch", "faces_file", AQ_CFG_PATH, .shapes = S_JOINTS,
                           .deflt = "straight faces between the joints",
                           .help = "points of the faces between the joints, a CSV file "
                                   "(Faces file, below), relative to the .cfg's directory"},
    [AQ_CFG_FILL_LEVEL] = {"fill", "level_m", AQ_CFG_REAL, .what = "a height", .unit = "m",
                           .lo = -AQ_CFG_COORD_MAX_M, .hi = AQ_CFG_COORD_MAX_M,
                           .shapes = S_ALL,
                           .help = "height y of the fill's horizontal top, above the "
                                   "springings (y = 0 is the springings' level for every "
                                   "shape but joints)"},
    [AQ_CFG_FILL_DENSITY] = {"fill", "density_kg_m3", DENSITY, .shapes = S_ALL,
                             .help = "density of the fill"},
    [AQ_CFG_MASS_LINE] = {"masses", "NAME", AQ_CFG_MASS, .what = "a mass", .unit = "kg",
                          .lo = 0, .hi = AQ_CFG_MASS_MAX_KG, .lo_open = 1, .shapes = S_ALL,
                          .help = "a mass of MASS_KG (for the arch's depth) at (X_M, Y_M), carried by voussoir "
                                  "VOUSSOIR; the point lies within the voussoir's vertical "
                                  "strip (the least to the greatest x of its outline and "
                                  "fill; a point on the joint between two voussoirs may name "
                                  "either) and above the arch's lowest point; NAME is 1-63 "
                                  "characters, each once"},
    [AQ_CFG_PRIMARY] = {"hinges", "primary", AQ_CFG_HINGES, .shapes = S_ALL,
                        .help = "four hinges JOINT FACE, FACE e (extrados) or i (intrados), "
                                "joints strictly increasing, e.g. 0e 6i 12e 19i, an "
                                "admissible mechanism; [hinges] names a primary or a "
                                "control (without a primary it is searched)"},
    [AQ_CFG_REVERSE] = {"hinges", "reverse", AQ_CFG_HINGES, .shapes = S_ALL,
                        .deflt = "the primary's joints with faces swapped",
                        .help = "the set the arch rocks on after it returns through the "
                                "undeformed shape; same syntax; needs a primary; refused "
                                "with control = free"},
    [AQ_CFG_CONTROL] = {"hinges", "control", AQ_CFG_CHOICE, .what = "a hinge control",
                        .choices = controls, .shapes = S_ALL,
                        .deflt = "fixed with a primary, free without",
                        .help = "fixed: the hinge-controlled arch, its sets the primary and "
                                "the reverse (every other joint carries what the thrust "
                                "demands); free: any joint may open, set 0 the minimum "
                                "mechanism of a ground acceleration along -x, set 1 that "
                                "along +x"},
    [AQ_CFG_FRICTION] = {"contact", "friction", AQ_CFG_REAL, .what = "a Coulomb coefficient",
                         .unit = "", .lo = 0, .hi = AQ_CFG_FRICTION_MAX, .lo_open = 1,
                         .shapes = S_ALL, .deflt = "none (sliding not checked)",
                         .help = "the Coulomb friction coefficient of every joint, the "
                                 "springings included (|T| <= friction N); --friction "
                                 "overrides it"},
    [AQ_CFG_EN] = {"contact", "e_n", AQ_CFG_REAL, .what = "a restitution", .unit = "",
                   .lo = 0, .hi = 1, .shapes = S_ALL, .deflt = "0",
                   .help = "the normal restitution of every contact of the block model "
                           "(--model blocks): Newton's law, a corner that lands leaves at "
                           "e_n times its approach velocity"},
    [AQ_CFG_SPREAD] = {"supports", "spread_m", AQ_CFG_REAL, .what = "a length", .unit = "m",
                       .lo = 0, .hi = AQ_CFG_LENGTH_MAX_M, .shapes = S_ALL, .deflt = "0",
                       .help = "the block model's supports (--model blocks) move apart by "
                               "this much, quasi-statically, before the record starts; "
                               "less than the voussoirs can reach across"},
    [AQ_CFG_ABUTMENT] = {"supports", "abutment_m", AQ_CFG_REAL, .what = "a length",
                         .unit = "m", .lo = 0, .hi = AQ_CFG_LENGTH_MAX_M, .shapes = S_ALL,
                         .deflt = "0",
                         .help = "the block model's supports (--model blocks): how far each "
                                 "support's face runs beyond both ends of the springing "
                                 "joint it bears (an impost or pier wider than the ring); 0: "
                                 "the springing joint as drawn"},
    [AQ_CFG_COR] = {"dynamics", "cor", AQ_CFG_REAL, .what = "a kinetic-energy ratio",
                    .unit = "", .lo = 0, .hi = 1, .shapes = S_ALL, .deflt = "0",
                    .help = "kinetic-energy ratio kept at an impact (not a velocity ratio), "
                            "used with impact = cor; --cor overrides it"},
    [AQ_CFG_IMPACT] = {"dynamics", "impact", AQ_CFG_CHOICE, .what = "an impact rule",
                       .choices = impacts, .shapes = S_ALL, .deflt = "cor",
                       .help = "cor (keep cor times the kinetic energy) or momentum "
                               "(conserve the new hinge set's generalised momentum)"},
    [AQ_CFG_G] = {"dynamics", "g_mps2", AQ_CFG_REAL, .what = "a gravity", .unit = "m/s^2",
                  .lo = 0, .hi = 100, .lo_open = 1, .shapes = S_ALL, .deflt = "9.80665",
                  .help = "gravity"},
};

const char *const *const aq_cfg_shape_names = aq_shape_names;
const char *const aq_cfg_shape_help[AQ_SHAPE_COUNT] = {
    [AQ_SHAPE_CIRCULAR] = "radius_m, embrace_deg, thickness_m, voussoirs: equal annular "
                          "sectors with radial joints, the circle's centre at the origin",
    [AQ_SHAPE_POINTED] = "span_m, rise_m, thickness_m, voussoirs: two arcs of radius "
                         "(rise^2 + span^2/4)/span meeting at the crown, rise >= span/2 "
                         "(span/2: a semicircle; span sqrt(3)/2: equilateral); a joint at "
                         "the crown",
    [AQ_SHAPE_ELLIPTICAL] = "span_m, rise_m, thickness_m, voussoirs: x = (span/2) cos u, "
                            "y = rise sin u",
    [AQ_SHAPE_PARABOLIC] = "span_m, rise_m, thickness_m, voussoirs: y = rise (1 - "
                           "(2x/span)^2)",
    [AQ_SHAPE_CATENARY] = "span_m, rise_m, thickness_m, voussoirs: y = rise - a (cosh(x/a) "
                          "- 1), y(+-span/2) = 0",
    [AQ_SHAPE_JOINTS] = "joints_file (faces_file): any arch, given joint by joint; "
                        "radius_m, span_m, rise_m, thickness_m and voussoirs are not taken",
};
const size_t aq_cfg_nshapes = AQ_SHAPE_COUNT;

const char aq_cfg_joints_header[] = "joint,xi_m,yi_m,xe_m,ye_m";
const char aq_cfg_faces_header[] = "voussoir,face,x_m,y_m";

const char aq_cfg_syntax_help[] =
    "An INI file: [section] headings, one KEY = VALUE a line, each key once; a line "
    "starting with ; or # is a comment, as is what follows \" ;\" on a line; lines of at "
    "most 190 characters, files of at most 1 MB; a UTF-8 byte-order mark is skipped.  "
    "Numbers are plain decimals (5, 5.0, 1.25e0); units are in the keys' names (_m "
    "metres, _deg degrees, _kg_m3 kg/m^3, _mps2 m/s^2).  A key outside a section, an "
    "unknown section or key, a key given twice and a value outside its range are refused "
    "in one line naming the file, the line and the key.";

const char aq_cfg_joints_help[] =
    "CSV with the header joint,xi_m,yi_m,xe_m,ye_m, then one row per joint 0, 1, 2, ... "
    "from the springing on the +x side over the crown to the other: the joint's intrados "
    "end (xi_m, yi_m) and its extrados end (xe_m, ye_m), m.  4 to 1000 voussoirs; each "
    "joint %g to %g m long; coordinates within +-%g m; no two joints meeting; "
    "each voussoir a simple polygon running counter-clockwise.  Lines starting with # "
    "and blank lines are skipped; CR LF line ends and a UTF-8 byte-order mark are read "
    "as well.";

const char aq_cfg_faces_help[] =
    "CSV with the header voussoir,face,x_m,y_m, then points of voussoir k's intrados "
    "(face i) or extrados (face e) strictly between joints k and k+1, in order from "
    "joint k (the rows of one face in that order; faces in any order); a face it does "
    "not mention is straight.  Coordinates within +-%g m; no voussoir may overlap "
    "another.";

/* x as written by hand: "1000", "0.001", "1e9" (%g, its exponent without
 * "+" and leading zeros). */
static void number(double x, char *buf, size_t n)
{
  char g[40], *e;
  if (fabs(x) < 1e6 && x == floor(x))
    snprintf(g, sizeof g, "%.0f", x);
  else
    snprintf(g, sizeof g, "%g", x);
  if ((e = strchr(g, 'e'))) {
    char *d = e + 1, *w = e + 1;
    if (*d == '+')
      d++;
    else if (*d == '-')
      *w++ = *d++;
    while (*d == '0' && d[1])
      d++;
    memmove(w, d, strlen(d) + 1);
  }
  snprintf(buf, n, "%s", g);
}

void aq_cfg_range_text(const aq_cfg_key *k, char *buf, size_t n)
{
  char lo[48], hi[48];
  number(k->lo, lo, sizeof lo);
  number(k->hi, hi, sizeof hi);
  if (k->kind == AQ_CFG_INT)
    snprintf(buf, n, "%s..%s", lo, hi);
  else if (k->kind == AQ_CFG_REAL || k->kind == AQ_CFG_MASS)
    snprintf(buf, n, "%c%s, %s%c%s%s", k->lo_open ? '(' : '[', lo, hi, k->hi_open ? ')' : ']',
             k->unit[0] ? " " : "", k->unit);
  else if (n)
    buf[0] = '\0';
}

int aq_cfg_in_range(const aq_cfg_key *k, double x)
{
  return (k->lo_open ? x > k->lo : x >= k->lo) && (k->hi_open ? x < k->hi : x <= k->hi);
}
