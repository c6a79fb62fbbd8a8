/* joints.c: the joints file of a `shape = joints` arch and its optional
 * faces file (docs/arch-file.md), read and checked: every message names
 * the file, its line and the column.
 *
 *   joints file: header joint,xi_m,yi_m,xe_m,ye_m, then one row per joint
 *                0, 1, 2, ... (its intrados end, its extrados end), from the
 *                springing on the +x side to the other;
 *   faces file:  header voussoir,face,x_m,y_m, then points of voussoir k's
 *                intrados (i) or extrados (e) strictly between joints k and
 *                k+1, in order from joint k (the rows of one face in that
 *                order; faces may come in any order).
 * Blank lines and lines starting with '#' are skipped; CR LF line ends are
 * read as LF.  Checks: coordinates within +-1000 m (cfg_keys.h), joints
 * numbered in order, 4 to 1000 voussoirs, each joint 0.001 to 1000 m
 * long, each voussoir a simple polygon of
 * positive area (counter-clockwise: the arch runs from +x to -x over the
 * crown, so a file given the other way round is refused), no joint
 * crossing another, no two voussoirs overlapping.
 */
#include "joints.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg_keys.h"
#include "infile.h"

#define MAX_FILE_BYTES 20000000 /* 20 MB */
#define MAX_JOINTS 1001
#define MAX_FACE_POINTS 1000000
#define MAX_FIELD 64

void aq_joints_free(aq_joints *j)
{
  if (!j)
    return;
  free(j->ji);
  free(j->je);
  free(j->jline);
  for (int f = 0; f < 2; f++) {
    free(j->face_pt[f]);
    free(j->face_start[f]);
    free(j->face_line[f]);
  }
  free(j->bytes[0]);
  free(j->bytes[1]);
  memset(j, 0, sizeof *j);
}

/* The file whole (20 MB at most, text without NUL bytes), or NULL and *st. */
static char *slurp(const char *path, size_t *len, aq_error *err, aq_status *st)
{
  size_t n = 0;
  char *buf = aq_infile_read(path, MAX_FILE_BYTES, "file", &n, st, err);
  if (buf && (n > MAX_FILE_BYTES || memchr(buf, '\0', n))) {
    free(buf);
    *st = aq_error_set(err, AQ_EFORMAT, path, -1, -1, NULL, "expected a text file of at "
                       "most 20 MB, got %s", n > MAX_FILE_BYTES ? "more" : "a NUL byte");
    return NULL;
  }
  *len = n;
  return buf;
}

/* Split the line at p (up to '\n' or the end) into at most max fields
 * separated by commas, blanks around them trimmed, into f[] (NUL-terminated
 * copies, truncated at MAX_FIELD - 1); returns the number of fields, and
 * sets *next past the line. */
static int split(const char *p, char f[][MAX_FIELD], int max, const char **next)
{
  const char *e = strchr(p, '\n');
  if (!e)
    e = p + strlen(p);
  *next = *e ? e + 1 : e;
  const char *end = e;
  if (end > p && end[-1] == '\r')
    end--;
  int nf = 0;
  const char *s = p;
  for (;;) {
    const char *c = memchr(s, ',', (size_t)(end - s));
    const char *fe = c ? c : end;
    const char *a = s, *b = fe;
    while (a < b && (*a == ' ' || *a == '\t'))
      a++;
    while (b > a && (b[-1] == ' ' || b[-1] == '\t'))
      b--;
    if (nf < max) {
      size_t l = (size_t)(b - a) < MAX_FIELD - 1 ? (size_t)(b - a) : MAX_FIELD - 1;
      memcpy(f[nf], a, l);
      f[nf][l] = '\0';
    }
    nf++;
    if (!c)
      break;
    s = c + 1;
  }
  return nf;
}

static int skip_line(const char *p)
{
  while (*p == ' ' || *p == '\t' || *p == '\r')
    p++;
  return *p == '\n' || *p == '\0' || *p == '#';
}

static int integer(const char *s, long *x)
{
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (end == s || *end || errno)
    return 0;
  *x = v;
  return 1;
}

/* 1 and *x if s is a number within +-AQ_CFG_COORD_MAX_M (cfg_keys.h). */
static int coordinate(const char *s, double *x)
{
  return aq_infile_number(s, x) && fabs(*x) <= AQ_CFG_COORD_MAX_M;
}

/* The next row that is not skipped, its fields split into f (split) and
 * *p past it, *line counting every line read; -1 at the end of the text. */
static int next_row(const char **p, long *line, char f[][MAX_FIELD], int max)
{
  while (**p) {
    (*line)++;
    if (!skip_line(*p))
      return split(*p, f, max, p);
    const char *nl = strchr(*p, '\n');
    *p = nl ? nl + 1 : *p + strlen(*p);
  }
  return -1;
}

/* The header line: the first line that is not skipped must be want (a
 * UTF-8 byte-order mark before it, as spreadsheets write one, skipped). */
static const char *header(const char *text, const char *path, const char *want, long *line,
                          aq_error *err, aq_status *st)
{
  const char *next = strncmp(text, "\xEF\xBB\xBF", 3) ? text : text + 3;
  char f[8][MAX_FIELD], got[8 * MAX_FIELD + 8];
  int nf = next_row(&next, line, f, 8);
  if (nf < 0) {
    *st = aq_error_set(err, AQ_EFORMAT, path, *line + 1, -1, NULL,
                       "expected the header %s, got an empty file", want);
    return NULL;
  }
  got[0] = '\0';
  for (int i = 0; i < nf && i < 8; i++)
    snprintf(got + strlen(got), sizeof got - strlen(got), "%s%s", i ? "," : "", f[i]);
  if (strcmp(got, want) != 0) {
    *st = aq_error_set(err, AQ_EFORMAT, path, *line, -1, NULL,
                       "expected the header %s, got \"%.200s\"", want, got);
    return NULL;
  }
  return next;
}

static aq_status read_joints(const char *path, const char *text, aq_joints *J, aq_error *err)
{
  static const char *const col[5] = {"joint", "xi_m", "yi_m", "xe_m", "ye_m"};
  aq_status st = AQ_OK;
  long line = 0;
  const char *p = header(text, path, aq_cfg_joints_header, &line, err, &st);
  if (!p)
    return st;
  size_t cap = 64, n = 0;
  J->ji = malloc(cap * sizeof *J->ji);
  J->je = malloc(cap * sizeof *J->je);
  J->jline = malloc(cap * sizeof *J->jline);
  if (!J->ji || !J->je || !J->jline)
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  char f[6][MAX_FIELD];
  int nf;
  while ((nf = next_row(&p, &line, f, 6)) >= 0) {
    if (nf != 5) {
      char got[32];
      snprintf(got, sizeof got, "%d", nf);
      return aq_error_set(err, AQ_EFORMAT, path, line, -1, NULL,
                          "expected 5 comma-separated fields (joint,xi_m,yi_m,xe_m,ye_m), "
                          "got %s", got);
    }
    long j;
    if (!integer(f[0], &j) || j != (long)n)
      return aq_error_set(err, AQ_EFORMAT, path, line, -1, col[0],
                          "expected joint %zu (joints numbered from 0 in order), got \"%s\"",
                          n, f[0]);
    if (n + 1 > MAX_JOINTS)
      return aq_error_set(err, AQ_EVALUE, path, line, -1, col[0],
                          "expected at most %d joints (1000 voussoirs), got more", MAX_JOINTS);
    double v[4];
    for (int k = 0; k < 4; k++)
      if (!coordinate(f[k + 1], &v[k]))
        return aq_error_set(err, AQ_EVALUE, path, line, -1, col[k + 1],
                            "expected a coordinate within +-%g m, got \"%s\"",
                            AQ_CFG_COORD_MAX_M, f[k + 1]);
    if (n == cap) {
      cap *= 2;
      aq_vec2 *a = realloc(J->ji, cap * sizeof *a);
      if (a)
        J->ji = a;
      aq_vec2 *b = realloc(J->je, cap * sizeof *b);
      if (b)
        J->je = b;
      long *l = realloc(J->jline, cap * sizeof *l);
      if (l)
        J->jline = l;
      if (!a || !b || !l)
        return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    }
    J->ji[n] = (aq_vec2){v[0], v[1]};
    J->je[n] = (aq_vec2){v[2], v[3]};
    J->jline[n] = line;
    double len = hypot(v[2] - v[0], v[3] - v[1]);
    if (!(len >= AQ_CFG_LENGTH_MIN_M && len <= AQ_CFG_LENGTH_MAX_M))
      return aq_error_set(err, AQ_EGEOMETRY, path, line, -1, "xe_m",
                          "expected a joint %g to %g m long (its extrados end away from its "
                          "intrados end), got %g m from (%g, %g) to (%g, %g) m",
                          AQ_CFG_LENGTH_MIN_M, AQ_CFG_LENGTH_MAX_M, len, v[0], v[1], v[2],
                          v[3]);
    n++;
  }
  if (n < 5)
    return aq_error_set(err, AQ_EVALUE, path, line, -1, col[0],
                        "expected at least 5 joints (4 voussoirs), got %zu", n);
  J->n = n - 1;
  return AQ_OK;
}

static aq_status read_faces(const char *path, const char *text, aq_joints *J, aq_error *err)
{
  static const char *const col[4] = {"voussoir", "face", "x_m", "y_m"};
  aq_status st = AQ_OK;
  long line = 0;
  const char *p = header(text, path, aq_cfg_faces_header, &line, err, &st);
  if (!p)
    return st;
  size_t n = J->n, cap = 0, np = 0;
  struct row {
    size_t k;
    int f;
    aq_vec2 p;
    long line;
  } *rows = NULL;
  char f[5][MAX_FIELD];
  int nf;
  while ((nf = next_row(&p, &line, f, 5)) >= 0) {
    if (nf != 4) {
      free(rows);
      return aq_error_set(err, AQ_EFORMAT, path, line, -1, NULL,
                          "expected 4 comma-separated fields (voussoir,face,x_m,y_m), got %d",
                          nf);
    }
    long k;
    double x, y;
    const char *bad = NULL;
    char expect[80];
    if (!integer(f[0], &k) || k < 0 || (size_t)k >= n)
      bad = col[0], snprintf(expect, sizeof expect, "a voussoir in 0..%zu", n - 1);
    else if (strcmp(f[1], "i") && strcmp(f[1], "e"))
      bad = col[1], snprintf(expect, sizeof expect, "i (intrados) or e (extrados)");
    else if (!coordinate(f[2], &x))
      bad = col[2], snprintf(expect, sizeof expect, "a coordinate within +-%g m",
                             AQ_CFG_COORD_MAX_M);
    else if (!coordinate(f[3], &y))
      bad = col[3], snprintf(expect, sizeof expect, "a coordinate within +-%g m",
                             AQ_CFG_COORD_MAX_M);
    else if (np >= MAX_FACE_POINTS)
      bad = col[0], snprintf(expect, sizeof expect, "at most %d points", MAX_FACE_POINTS);
    if (bad) {
      const char *got = bad == col[0] ? f[0] : bad == col[1] ? f[1] : bad == col[2] ? f[2] : f[3];
      aq_error_set(err, AQ_EFORMAT, path, line, -1, bad, "expected %s, got \"%s\"", expect,
                   got);
      free(rows);
      return AQ_EFORMAT;
    }
    if (np == cap) {
      cap = cap ? 2 * cap : 64;
      struct row *r = realloc(rows, cap * sizeof *r);
      if (!r) {
        free(rows);
        return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
      }
      rows = r;
    }
    rows[np++] = (struct row){(size_t)k, f[1][0] == 'e', {x, y}, line};
  }
  /* per face, per voussoir, in file order (a counting sort) */
  for (int f = 0; f < 2; f++) {
    J->face_start[f] = calloc(n + 1, sizeof *J->face_start[f]);
    J->face_pt[f] = malloc((np ? np : 1) * sizeof *J->face_pt[f]);
    J->face_line[f] = malloc((np ? np : 1) * sizeof *J->face_line[f]);
    if (!J->face_start[f] || !J->face_pt[f] || !J->face_line[f]) {
      free(rows);
      return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    }
    for (size_t i = 0; i < np; i++)
      if (rows[i].f == f)
        J->face_start[f][rows[i].k + 1]++;
    for (size_t k = 0; k < n; k++)
      J->face_start[f][k + 1] += J->face_start[f][k];
    size_t *at = malloc((n ? n : 1) * sizeof *at);
    if (!at) {
      free(rows);
      return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    }
    memcpy(at, J->face_start[f], n * sizeof *at);
    for (size_t i = 0; i < np; i++)
      if (rows[i].f == f) {
        J->face_pt[f][at[rows[i].k]] = rows[i].p;
        J->face_line[f][at[rows[i].k]++] = rows[i].line;
      }
    free(at);
  }
  free(rows);
  return AQ_OK;
}

/* ---- polygon checks ----------------------------------------------------- */

typedef struct {
  aq_vec2 p;
  const char *file;
  long line;
  const char *field;
} vtx;

static double cross3(aq_vec2 o, aq_vec2 a, aq_vec2 b)
{
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

static int on_segment(aq_vec2 a, aq_vec2 b, aq_vec2 p)
{
  return fmin(a.x, b.x) <= p.x && p.x <= fmax(a.x, b.x) && fmin(a.y, b.y) <= p.y &&
         p.y <= fmax(a.y, b.y);
}

/* 1 if segments ab and cd share a point (touching counts). */
static int segments_meet(aq_vec2 a, aq_vec2 b, aq_vec2 c, aq_vec2 d)
{
  double d1 = cross3(c, d, a), d2 = cross3(c, d, b), d3 = cross3(a, b, c), d4 = cross3(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 1;
  return (d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) ||
         (d3 == 0 && on_segment(a, b, c)) || (d4 == 0 && on_segment(a, b, d));
}

/* Voussoir k's polygon: joint k's ends, the extrados points, joint k+1's
 * ends, the intrados points back; each vertex with its file and line. */
static size_t polygon(const aq_joints *J, size_t k, const char *jpath, const char *fpath,
                      vtx *v)
{
  size_t m = 0;
  v[m++] = (vtx){J->ji[k], jpath, J->jline[k], "xi_m"};
  v[m++] = (vtx){J->je[k], jpath, J->jline[k], "xe_m"};
  if (J->face_start[1])
    for (size_t i = J->face_start[1][k]; i < J->face_start[1][k + 1]; i++)
      v[m++] = (vtx){J->face_pt[1][i], fpath, J->face_line[1][i], "x_m"};
  v[m++] = (vtx){J->je[k + 1], jpath, J->jline[k + 1], "xe_m"};
  v[m++] = (vtx){J->ji[k + 1], jpath, J->jline[k + 1], "xi_m"};
  if (J->face_start[0])
    for (size_t i = J->face_start[0][k + 1]; i-- > J->face_start[0][k];)
      v[m++] = (vtx){J->face_pt[0][i], fpath, J->face_line[0][i], "x_m"};
  return m;
}

/* The joints alone (each voussoir's quadrilateral, its faces left out):
 * they must run from the springing on the +x side to the other, each
 * intrados end in xi_m, yi_m.  Joints running from -x, or whose ends are
 * swapped, turn most quadrilaterals clockwise; both at once turn them back
 * counter-clockwise but start at -x: each said for what it is. */
static aq_status check_direction(const aq_joints *J, const char *jpath, aq_error *err)
{
  size_t n = J->n, clockwise = 0;
  for (size_t k = 0; k < n; k++) {
    aq_vec2 q[4] = {J->ji[k], J->je[k], J->je[k + 1], J->ji[k + 1]};
    double area = 0;
    for (int i = 0; i < 4; i++)
      area += q[i].x * q[(i + 1) % 4].y - q[(i + 1) % 4].x * q[i].y;
    clockwise += area < 0;
  }
  double x0 = 0.5 * (J->ji[0].x + J->je[0].x), xn = 0.5 * (J->ji[n].x + J->je[n].x);
  int from_minus = x0 < xn, cw = 2 * clockwise > n;
  if (!from_minus && !cw)
    return AQ_OK;
  if (from_minus && cw) /* the same arch, listed from the other springing */
    return aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[1], -1, "joint",
                        "expected joints from the springing on the +x side over the crown to "
                        "the other, got joint 0 at x = %.4g m and joint %zu at x = %.4g m "
                        "(%zu of %zu voussoirs clockwise): the file runs the other way",
                        x0, n, xn, clockwise, n);
  if (cw) /* from +x, but every joint upside down */
    return aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[0], -1, "xi_m",
                        "expected each joint's intrados end in xi_m,yi_m and its extrados end "
                        "in xe_m,ye_m, got them swapped: the joints run from +x (joint 0 at x "
                        "= %.4g m) to -x (joint %zu at x = %.4g m) yet %zu of %zu voussoirs "
                        "turn clockwise, as they do when the intrados and extrados columns "
                        "are exchanged",
                        x0, n, xn, clockwise, n);
  return aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[0], -1, "xi_m",
                      "expected joints from the springing on the +x side, each intrados end "
                      "in xi_m,yi_m, got joint 0 at x = %.4g m and joint %zu at x = %.4g m "
                      "with the voussoirs counter-clockwise: the file runs the other way and "
                      "its intrados and extrados columns are swapped",
                      x0, n, xn);
}

/* Of the edges v[i]..v[i+1] (of m) and w[j]..w[j+1] (of mw), the vertex a
 * message names: the latest face point if one of their ends is one (the
 * joints were checked on their own), else joint. */
static const vtx *blame(const vtx *v, size_t i, size_t m, const vtx *w, size_t j, size_t mw,
                        const char *jpath, const vtx *joint)
{
  const vtx *ends[4] = {&v[i], &v[(i + 1) % m], &w[j], &w[(j + 1) % mw]}, *at = joint;
  int face = 0;
  for (int q = 0; q < 4; q++)
    if (ends[q]->file != jpath && (!face || ends[q]->line > at->line))
      at = ends[q], face = 1;
  return at;
}

/* 1 if segments ab and cd cross at a point inside both (touching, at an
 * end or along a line, does not count). */
static int segments_cross(aq_vec2 a, aq_vec2 b, aq_vec2 c, aq_vec2 d)
{
  double d1 = cross3(c, d, a), d2 = cross3(c, d, b), d3 = cross3(a, b, c), d4 = cross3(a, b, d);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

static aq_status check_polygons(const aq_joints *J, const char *jpath, const char *fpath,
                                aq_error *err)
{
  size_t n = J->n, most = 4;
  for (size_t k = 0; k < n; k++) {
    size_t m = 4;
    for (int f = 0; f < 2; f++)
      if (J->face_start[f])
        m += J->face_start[f][k + 1] - J->face_start[f][k];
    most = m > most ? m : most;
  }
  vtx *v = malloc(most * sizeof *v), *w = malloc(most * sizeof *w);
  double *box = malloc(4 * n * sizeof *box);
  aq_status st = AQ_OK;
  if (!v || !w || !box) {
    st = aq_error_set(err, AQ_ENOMEM, jpath, -1, -1, NULL, "out of memory");
    goto done;
  }
  /* joints do not cross one another */
  for (size_t a = 0; a <= n && st == AQ_OK; a++)
    for (size_t b = a + 1; b <= n; b++)
      if (segments_meet(J->ji[a], J->je[a], J->ji[b], J->je[b])) {
        st = aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[b], -1, "joint",
                          "expected joints that do not meet, got joint %zu meeting joint %zu",
                          b, a);
        break;
      }
  if (st == AQ_OK)
    st = check_direction(J, jpath, err);
  for (size_t k = 0; k < n && st == AQ_OK; k++) {
    size_t m = polygon(J, k, jpath, fpath, v);
    double area = 0;
    box[4 * k] = box[4 * k + 2] = HUGE_VAL;
    box[4 * k + 1] = box[4 * k + 3] = -HUGE_VAL;
    for (size_t i = 0; i < m; i++) {
      aq_vec2 a = v[i].p, b = v[(i + 1) % m].p;
      area += 0.5 * (a.x * b.y - b.x * a.y);
      box[4 * k] = fmin(box[4 * k], a.x), box[4 * k + 1] = fmax(box[4 * k + 1], a.x);
      box[4 * k + 2] = fmin(box[4 * k + 2], a.y), box[4 * k + 3] = fmax(box[4 * k + 3], a.y);
    }
    double scale = 0;
    for (size_t i = 0; i < m; i++)
      scale = fmax(scale, fmax(fabs(v[i].p.x), fabs(v[i].p.y)));
    if (fabs(area) <= 1e-12 * scale * scale) {
      st = aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[k + 1], -1, "joint",
                        "expected voussoir %zu (joints %zu and %zu) of area > 0, got %.3g m^2",
                        k, k, k + 1, area);
      break;
    }
    /* simple: no two edges meet but neighbours, at their shared vertex */
    for (size_t i = 0; i < m && st == AQ_OK; i++)
      for (size_t j = i + 2; j < m; j++) {
        if (i == 0 && j == m - 1)
          continue;
        if (segments_meet(v[i].p, v[(i + 1) % m].p, v[j].p, v[(j + 1) % m].p)) {
          /* the latest face point of the two edges, else the later edge */
          const vtx *at = blame(v, i, m, v, j, m, jpath, &v[j]);
          st = aq_error_set(err, AQ_EGEOMETRY, at->file, at->line, -1, at->field,
                            "expected voussoir %zu a simple polygon (joints %zu and %zu, its "
                            "faces between), got one whose sides cross",
                            k, k, k + 1);
          break;
        }
      }
    if (st != AQ_OK)
      break;
    if (!(area > 0)) {
      st = aq_error_set(err, AQ_EGEOMETRY, jpath, J->jline[k + 1], -1, "joint",
                        "expected joints counter-clockwise from the springing on the +x side "
                        "over the crown (voussoirs of positive area), got voussoir %zu "
                        "clockwise (area %.6g m^2): the file runs the other way",
                        k, area);
      break;
    }
  }
  /* no two voussoirs overlap: edges of voussoirs more than one apart whose
   * boxes meet do not meet; neighbours, which share a joint, do not cross
   * (a face point of one inside the other).  The line blamed is the face
   * point's that makes an edge, else the later voussoir's joint. */
  for (size_t a = 0; a < n && st == AQ_OK; a++)
    for (size_t b = a + 1; b < n && st == AQ_OK; b++) {
      if (box[4 * a] > box[4 * b + 1] || box[4 * b] > box[4 * a + 1] ||
          box[4 * a + 2] > box[4 * b + 3] || box[4 * b + 2] > box[4 * a + 3])
        continue;
      size_t ma = polygon(J, a, jpath, fpath, v), mb = polygon(J, b, jpath, fpath, w);
      vtx joint = {J->je[b], jpath, J->jline[b], "joint"};
      for (size_t i = 0; i < ma && st == AQ_OK; i++)
        for (size_t j = 0; j < mb; j++)
          if (b == a + 1 ? segments_cross(v[i].p, v[(i + 1) % ma].p, w[j].p, w[(j + 1) % mb].p)
                         : segments_meet(v[i].p, v[(i + 1) % ma].p, w[j].p, w[(j + 1) % mb].p)) {
            const vtx *at = blame(v, i, ma, w, j, mb, jpath, &joint);
            st = aq_error_set(err, AQ_EGEOMETRY, at->file, at->line, -1, at->field,
                              "expected voussoirs that do not overlap, got voussoir %zu "
                              "meeting voussoir %zu",
                              b, a);
            break;
          }
    }
done:
  free(v);
  free(w);
  free(box);
  return st;
}

aq_status aq_joints_read(const char *joints_path, const char *faces_path, aq_joints *out,
                         aq_error *err)
{
  memset(out, 0, sizeof *out);
  aq_status st = AQ_OK;
  out->bytes[0] = slurp(joints_path, &out->nbytes[0], err, &st);
  if (!out->bytes[0])
    goto fail;
  if ((st = read_joints(joints_path, out->bytes[0], out, err)) != AQ_OK)
    goto fail;
  if (faces_path) {
    out->bytes[1] = slurp(faces_path, &out->nbytes[1], err, &st);
    if (!out->bytes[1])
      goto fail;
    if ((st = read_faces(faces_path, out->bytes[1], out, err)) != AQ_OK)
      goto fail;
  }
  if ((st = check_polygons(out, joints_path, faces_path ? faces_path : joints_path, err)) !=
      AQ_OK)
    goto fail;
  return AQ_OK;
fail:
  aq_joints_free(out);
  return st;
}
