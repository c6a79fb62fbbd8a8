/* joints.h: the joints file (and optional faces file) of a `shape =
 * joints` arch, read and checked (joints.c; format in docs/arch-file.md).
 * Lengths in m.  aq_joints_read fills *out, which aq_joints_free releases;
 * errors name the file, its line and the column. */
#ifndef AQ_ARCH_JOINTS_H
#define AQ_ARCH_JOINTS_H

#include <stddef.h>

#include "../error.h"
#include "model.h"

typedef struct {
  size_t n;              /* voussoirs (joints less one) */
  aq_vec2 *ji, *je;      /* n + 1 joints: intrados and extrados ends */
  long *jline;           /* each joint's line in the joints file */
  /* faces ([0] intrados, [1] extrados; NULL without a faces file):
   * voussoir k's points are face_pt[f][face_start[f][k] .. face_start[f][k+1]) */
  aq_vec2 *face_pt[2];
  size_t *face_start[2];
  long *face_line[2];    /* each point's line in the faces file */
  char *bytes[2];        /* the files as read (joints, faces or NULL), NUL-terminated */
  size_t nbytes[2];
} aq_joints;

/* Read joints_path and, if not NULL, faces_path; check them (numbers,
 * order, 4 to 1000 voussoirs, joints of length > 0 that do not meet,
 * voussoirs simple polygons of positive area, counter-clockwise, not
 * overlapping).  AQ_EIO, AQ_EFORMAT, AQ_EVALUE, AQ_EGEOMETRY or AQ_ENOMEM. */
aq_status aq_joints_read(const char *joints_path, const char *faces_path, aq_joints *out,
                         aq_error *err);
void aq_joints_free(aq_joints *j);

#endif
