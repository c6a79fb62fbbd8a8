/* cfg_impl.h: what the arch file's reading shares (cfg.c: its keys checked
 * line by line; cfg_load.c: the file read, then the arch built).  Private
 * to src/arch. */
#ifndef AQ_ARCH_CFG_IMPL_H
#define AQ_ARCH_CFG_IMPL_H

#include <stddef.h>

#include "../error.h"
#include "cfg_keys.h"
#include "model.h"

#define MAX_LINE_CHARS 190    /* libinih's line buffer is 200 bytes */
#define MAX_MASSES 1000       /* point masses in [masses] */
#define MAX_FILE_BYTES 1000000
#define PATH_BYTES 4096       /* a joints or faces file's path beside the .cfg */

typedef struct {
  aq_point_mass m;
  long line;
} mass_line;

typedef struct {
  const char *file;
  const char *text; /* cursor */
  long line;        /* lines read so far */
  long key_line[AQ_CFG_NKEYS];
  int hinges_section; /* line of [hinges], 0 if absent */
  int fill_section;   /* line of [fill], 0 if absent */
  aq_error *err;
  int failed;
  char name[64];
  int shape;
  char path[2][200];  /* joints_file, faces_file as given */
  double num[AQ_CFG_NKEYS];
  aq_hinge_set hs[2];
  int impact;
  int control; /* aq_hinge_control */
  mass_line *mass;
  size_t nmass;
} parse_ctx;

/* libinih's reader over parse_ctx's text: a line at a time, counted
 * (cfg.c). */
char *aq_cfg_reader(char *str, int num, void *stream);
/* libinih's handler: one key of a section, checked and kept (cfg.c). */
int aq_cfg_handler(void *user, const char *section, const char *name,
                   const char *value);

#endif
