/* test_arch_joints_files.c: faults of a joints arch's files named where
 * they are.
 *   - a faces-file point that makes its voussoir overlap another is blamed
 *     on the faces file's line, not on a joint (a far-off point on line 2
 *     gave "joints.csv:4: ... voussoir 2 meeting voussoir 0"); a point
 *     that carries a voussoir's face into its neighbour, which no check
 *     saw, is refused on its line;
 *   - a joints file whose intrados and extrados columns are exchanged, one
 *     listed from the -x springing, and one both, are each refused saying
 *     which (a file both reversed and swapped was taken, its faces named
 *     the wrong way round). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

static void write_file(const char *path, const char *text)
{
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

/* arches/vertical.csv's rows (joint 0..12), as columns of numbers. */
static int vertical_joints(double j[13][4])
{
  char *csv = aq_test_read_file("arches/vertical.csv", NULL);
  int n = 0;
  for (const char *p = csv; p && *p && n < 13;) {
    int k;
    if (sscanf(p, "%d,%lf,%lf,%lf,%lf", &k, &j[n][0], &j[n][1], &j[n][2], &j[n][3]) == 5 &&
        k == n)
      n++;
    p = strchr(p, '\n');
    p = p ? p + 1 : NULL;
  }
  free(csv);
  return n;
}

/* vertical.csv's joints j as a joints file at path: listed from -x
 * (reversed) and with the intrados and extrados ends exchanged (swapped)
 * as asked. */
static void write_joints(const char *path, double j[13][4], int reversed, int swapped)
{
  char csv[4096];
  size_t len = (size_t)snprintf(csv, sizeof csv, "joint,xi_m,yi_m,xe_m,ye_m\n");
  for (int k = 0; k < 13; k++) {
    const double *r = j[reversed ? 12 - k : k];
    int i = swapped ? 2 : 0, e = swapped ? 0 : 2;
    len += (size_t)snprintf(csv + len, sizeof csv - len, "%d,%.15g,%.15g,%.15g,%.15g\n", k,
                            r[i], r[i + 1], r[e], r[e + 1]);
  }
  write_file(path, csv);
}

/* mechanism on dir/a.cfg (joints j.csv, faces f.csv if faces): exit 1 and
 * one line starting with want (%s: dir). */
static void refused(const char *what, const char *dir, const char *want)
{
  char args[900], out[4096], err[4096], w[1200];
  snprintf(args, sizeof args, "mechanism --arch %s/a.cfg", dir);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  snprintf(w, sizeof w, want, dir);
  aq_check(rc == 1 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
               !strncmp(err, w, strlen(w)),
           "%s: exit %d, one line \"%s...\": %s", what, rc, w, err);
}

AQ_TEST(arch_joints_files_faults_where_they_are)
{
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/a.cfg", dir);
  write_file(path, "[arch]\nshape = joints\njoints_file = j.csv\nfaces_file = f.csv\n"
                   "density_kg_m3 = 2100\ndepth_m = 1\n");
  double j[13][4];
  if (!aq_check(vertical_joints(j) == 13, "arches/vertical.csv: 13 joints"))
    return;
  char jpath[700];
  snprintf(jpath, sizeof jpath, "%s/j.csv", dir);
  write_joints(jpath, j, 0, 0); /* as given: from +x, intrados first */
  snprintf(path, sizeof path, "%s/f.csv", dir);
  /* voussoir 2's intrados pulled out over voussoir 0 (x 3.9, y 0.2) */
  write_file(path, "voussoir,face,x_m,y_m\n2,i,3.9,0.2\n");
  refused("a far-off face point", dir, "archquake: %s/f.csv:2: x_m: expected voussoirs that "
                                        "do not overlap, got voussoir 2 meeting voussoir 0");
  /* voussoir 1's extrados carried over the top of joint 2 into voussoir
   * 2: a simple polygon of its own, overlapping its neighbour */
  write_file(path, "voussoir,face,x_m,y_m\n1,e,2.7,2.5\n1,e,2.7,1.8\n");
  refused("a face point inside the neighbour", dir,
          "archquake: %s/f.csv:3: x_m: expected voussoirs that do not overlap, got voussoir 2 "
          "meeting voussoir 1");
  write_file(path, "voussoir,face,x_m,y_m\n");
  /* the intrados and extrados columns exchanged */
  write_joints(jpath, j, 0, 1);
  refused("columns exchanged", dir, "archquake: %s/j.csv:2: xi_m: expected each joint's "
                                     "intrados end in xi_m,yi_m and its extrados end in "
                                     "xe_m,ye_m, got them swapped");
  /* listed from the -x springing */
  write_joints(jpath, j, 1, 0);
  refused("from -x", dir, "archquake: %s/j.csv:3: joint: expected joints from the springing "
                          "on the +x side over the crown to the other, got joint 0 at x = "
                          "-4.33 m and joint 12 at x = 4.33 m (12 of 12 voussoirs clockwise): "
                          "the file runs the other way");
  /* both: from -x, columns exchanged (counter-clockwise again) */
  write_joints(jpath, j, 1, 1);
  refused("from -x, exchanged", dir, "archquake: %s/j.csv:2: xi_m: expected joints from the "
                                     "springing on the +x side, each intrados end in "
                                     "xi_m,yi_m, got joint 0 at x = -4.33 m and joint 12 at x = "
                                     "4.33 m with the voussoirs counter-clockwise: the file "
                                     "runs the other way and its intrados and extrados columns "
                                     "are swapped");
}
