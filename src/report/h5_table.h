/* h5_table.h: one table writer for the HDF5 files (h5.c, h5_capacity.c,
 * h5_spectrum.c).  A table is a list of columns over a row struct: each
 * column's name, kind, place in the row and units.  The same list makes a
 * compound dataset (one row per struct: /summary, /records, /spectra,
 * capacity/scan_points) or a group of 1-D datasets (one per column:
 * /capacity, capacity/fragility), so a new table is a column list.
 * Nothing here prints; every HDF5 call is checked (< 0 on failure). */
#ifndef AQ_REPORT_H5_TABLE_H
#define AQ_REPORT_H5_TABLE_H

#include <hdf5.h>
#include <stddef.h>

#include "../error.h"

typedef enum {
  AQ_H5_STR = 0, /* char[size], fixed length, NUL-terminated */
  AQ_H5_VSTR,    /* const char * (NULL as ""), a variable-length string: never cut */
  AQ_H5_DOUBLE,  /* double */
  AQ_H5_INT      /* int64_t */
} aq_h5_kind;

typedef struct {
  const char *name;  /* member (or dataset) name */
  aq_h5_kind kind;
  size_t offset;     /* offsetof the row struct's member */
  size_t size;       /* sizeof the member */
  const char *units; /* compound: attribute units_<name> of the table;
                        columns: attribute units of the column; NULL: none */
} aq_h5_col;

/* A column of row struct T: AQ_H5_COL(T, member, kind, units). */
#define AQ_H5_COL(T, f, kind, units) {#f, kind, offsetof(T, f), sizeof(((T *)0)->f), units}

/* The compound type of the columns (memory layout, rows of rowsize bytes),
 * or < 0; *file gets its packed copy for the file (close both). */
hid_t aq_h5_table_type(const aq_h5_col *cols, size_t ncols, size_t rowsize, hid_t *file);

/* A transfer property list for writing n values of memory type mt to
 * dataset d, whose type-conversion buffers hold the n values (in the larger
 * of the two types) rather than HDF5's default 1 MiB (two of which are
 * calloc'ed, every page touched, at each write that converts), up to that
 * default; or < 0.  Close it with H5Pclose. */
hid_t aq_h5_xfer(hid_t d, hid_t mt, size_t n);

/* The units_<name> attributes of table d (the columns with units). */
herr_t aq_h5_table_units(hid_t d, const aq_h5_col *cols, size_t ncols);

/* Dataset name of loc: the nrows rows (rowsize bytes each) as one
 * compound table, with its units_<name> attributes.  *out (NULL: closed)
 * gets the open dataset for more attributes. */
herr_t aq_h5_table_write(hid_t loc, const char *name, const aq_h5_col *cols, size_t ncols,
                         size_t rowsize, const void *rows, size_t nrows, hid_t *out);

/* One 1-D dataset per column into loc, named as the column, nrows values
 * each gathered from the rows, with a units attribute where it has units. */
herr_t aq_h5_columns_write(hid_t loc, const aq_h5_col *cols, size_t ncols, size_t rowsize,
                           const void *rows, size_t nrows);

/* Dataset name of loc: n rows x cols of type t from buf (cols 1: 1-D),
 * with its units attribute (units NULL: none). */
herr_t aq_h5_array_write(hid_t loc, const char *name, hid_t t, const void *buf, size_t n,
                         size_t cols, const char *units);

/* Attribute name of loc with the given type and dataspace, holding buf
 * (created, written, closed; type and space stay the caller's). */
herr_t aq_h5_attr_write(hid_t loc, const char *name, hid_t type, hid_t space, const void *buf);

/* Attribute name of loc: n variable-length strings (a 2-D dataset's
 * columns and their units, one string per column). */
herr_t aq_h5_attr_strings(hid_t loc, const char *name, const char *const *v, size_t n);

/* Scalar string attribute (fixed length strlen + 1, NUL-terminated; NULL
 * as ""). */
herr_t aq_h5_attr_string(hid_t loc, const char *name, const char *value);

/* The file of `archquake COMMAND -o` at path, opened read-only (HDF5's
 * automatic error printing off) into *file, and its object name, of kind
 * H5I_GROUP or H5I_DATASET, into *obj; close them with H5Oclose and
 * H5Fclose.  AQ_EIO when HDF5 cannot open the file, AQ_EFORMAT (field
 * /name, "expected MISSING") when the file has no such object of that
 * kind; nothing is left open then. */
aq_status aq_h5_open_output(const char *path, const char *command, const char *name,
                            H5I_type_t kind, const char *missing, hid_t *file, hid_t *obj,
                            aq_error *err);

#endif
