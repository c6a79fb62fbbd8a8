/* read.h: the results and capacity files as the page shows them
 * (src/page/read.c).  Text where the page shows text: every attribute of
 * the root and of each arch group, and every column of the /records table,
 * as the file holds them (numbers as the shortest decimal that reads back
 * to the same double, aq_text_double); the runs
 * as aq_h5_read_suite reads them; capacity tables as aq_h5_capacity_read.
 * Everything malloc'd, freed by aq_page_results_free. */
#ifndef AQ_PAGE_READ_H
#define AQ_PAGE_READ_H

#include <stddef.h>

#include "../error.h"
#include "../report/h5.h"
#include "../report/h5_capacity.h"
#include "page.h"

/* Named values as text. */
typedef struct {
  size_t n;
  char (*name)[64];
  char **value; /* n strings */
  double *num;  /* n: the value if it is one number, else NAN */
} aq_page_attrs;

/* A table's columns as text. */
typedef struct {
  size_t ncol, nrow;
  char (*col)[64];
  char **cell; /* nrow x ncol strings, row-major */
  double *num; /* nrow x ncol numbers (NAN for text) */
} aq_page_table;

typedef struct {
  aq_page_attrs root;
  aq_page_table records;
  size_t narch;
  aq_page_attrs *arch; /* narch: /arches/NNN in order */
  aq_page_attrs *geom; /* narch: /geometry/NNN (shape, voussoirs, masses; none
                          in a file written before it was kept) */
  aq_h5_suite suite;   /* the runs */
  int have_histories;  /* /histories exists */
} aq_page_results;

/* Read the file at path, of any kind (aq_page_file_kind): its root, its
 * records, its arches (none in a spectrum file) and its runs (none but in a
 * results file). */
aq_status aq_page_results_read(const char *path, aq_page_results *r, aq_error *err);
void aq_page_results_free(aq_page_results *r);

/* Value of name in a (NULL if absent), and as a number (NAN). */
const char *aq_page_attr(const aq_page_attrs *a, const char *name);
double aq_page_attr_num(const aq_page_attrs *a, const char *name);
/* Column index of name in t, or -1. */
long aq_page_col(const aq_page_table *t, const char *name);
/* Cell (row, column name) of t: the text ("" if no such column), the number. */
const char *aq_page_cell(const aq_page_table *t, size_t row, const char *name);
double aq_page_cell_num(const aq_page_table *t, size_t row, const char *name);

#endif
