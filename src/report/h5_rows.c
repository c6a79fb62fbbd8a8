/* h5_rows.c: the results writer's buffered tables (h5_writer.h): rows
 * filled as their struct, packed as the file stores them, appended to an
 * extensible compound dataset a chunk at a time. */
#include <stdlib.h>
#include <string.h>

#include "h5_writer.h"

/* The bytes of column c in a row: its member's (a pointer for a
 * variable-length string). */
static size_t col_bytes(const aq_h5_col *c)
{
  return c->kind == AQ_H5_VSTR ? sizeof(const char *) : c->size;
}

herr_t aq_h5w_table_open(aq_h5_writer *w, aq_h5w_table *T, const char *name,
                         const aq_h5_col *cols, size_t ncols, size_t rowsize,
                         size_t chunk)
{
  T->rowsize = rowsize;
  T->cap = chunk;
  T->cols = cols;
  T->ncols = ncols;
  T->row = calloc(1, rowsize);
  T->at = calloc(ncols, sizeof *T->at);
  if (!T->row || !T->at)
    return -1;
  hid_t mt = aq_h5_table_type(cols, ncols, rowsize, &T->ft);
  if (mt < 0 || H5Tclose(mt) < 0)
    return -1;
  T->psize = H5Tget_size(T->ft);
  for (size_t i = 0; i < ncols; i++) {
    int k = H5Tget_member_index(T->ft, cols[i].name);
    if (k < 0)
      return -1;
    T->at[i] = H5Tget_member_offset(T->ft, (unsigned)k);
    for (size_t j = 0; j < T->nowned; j++)
      if (T->owned[j] == cols[i].offset)
        T->owned_at[j] = T->at[i];
  }
  /* every byte of a packed row is a column's, so row_pack writes it all */
  size_t bytes = 0;
  for (size_t i = 0; i < ncols; i++)
    bytes += col_bytes(&cols[i]);
  T->buf = bytes == T->psize ? malloc(chunk * T->psize) : NULL;
  if (!T->psize || !T->buf)
    return -1;
  hsize_t dim = 0, maxdim = H5S_UNLIMITED, ch = chunk;
  hid_t sp = H5Screate_simple(1, &dim, &maxdim);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  herr_t rc = sp < 0 || dcpl < 0 ? -1 : H5Pset_chunk(dcpl, 1, &ch);
  if (rc >= 0) {
    T->d = H5Dcreate2(w->file, name, T->ft, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    rc = T->d < 0 ? -1 : 0;
  }
  if (rc >= 0)
    rc = aq_h5_table_units(T->d, cols, ncols);
  if (dcpl >= 0 && H5Pclose(dcpl) < 0)
    rc = -1;
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

/* Free the buffered rows' own strings (after a flush, or when giving up),
 * and with all, the open row's. */
static void row_strings_free(aq_h5w_table *T, int all)
{
  for (size_t r = 0; T->buf && r < T->nbuf; r++)
    for (size_t k = 0; k < T->nowned; k++) {
      char *p; /* (a packed row's pointers are not aligned) */
      memcpy(&p, T->buf + r * T->psize + T->owned_at[k], sizeof p);
      free(p);
    }
  for (size_t k = 0; all && T->open && k < T->nowned; k++)
    free(*(char **)(void *)(T->row + T->owned[k]));
  if (all)
    T->open = 0;
}

/* Pack the open row into the buffer (which has room). */
static void row_pack(aq_h5w_table *T)
{
  unsigned char *p = T->buf + T->nbuf++ * T->psize;
  for (size_t i = 0; i < T->ncols; i++)
    memcpy(p + T->at[i], T->row + T->cols[i].offset, col_bytes(&T->cols[i]));
  T->open = 0;
}

char *aq_h5w_row_string(const char *s)
{
  return strdup(s ? s : "");
}

/* Append the buffered rows to the table.  Returns < 0 on failure. */
static herr_t table_flush(aq_h5_writer *w, aq_h5w_table *T)
{
  if (T->nbuf == 0)
    return 0;
  hsize_t start = T->nrows, count = T->nbuf, size = T->nrows + T->nbuf;
  if (H5Dset_extent(T->d, &size) < 0)
    return -1;
  hid_t fs = H5Dget_space(T->d);
  if (fs < 0)
    return -1;
  hid_t ms = H5Screate_simple(1, &count, NULL);
  hid_t xfer = aq_h5_xfer(T->d, T->ft, T->nbuf);
  herr_t rc = -1;
  if (ms >= 0 && xfer >= 0 &&
      H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL) >= 0)
    rc = H5Dwrite(T->d, T->ft, ms, fs, xfer, T->buf);
  if (xfer >= 0 && H5Pclose(xfer) < 0)
    rc = -1;
  if (ms >= 0 && H5Sclose(ms) < 0)
    rc = -1;
  if (H5Sclose(fs) < 0)
    rc = -1;
  if (rc >= 0) {
    aq_h5w_sync_hint(w, T->nbuf * T->psize);
    row_strings_free(T, 0); /* (a packed row's every byte is a column's) */
    T->nrows += T->nbuf;
    T->nbuf = 0;
  }
  return rc;
}

/* Pack the open row, if any, after a flush if the buffer is full.
 * Returns < 0 if that flush failed. */
static herr_t row_commit(aq_h5_writer *w, aq_h5w_table *T)
{
  if (!T->open)
    return 0;
  if (T->nbuf == T->cap && table_flush(w, T) < 0)
    return -1;
  row_pack(T);
  return 0;
}

void *aq_h5w_table_row(aq_h5_writer *w, aq_h5w_table *T)
{
  if (row_commit(w, T) < 0)
    return NULL;
  memset(T->row, 0, T->rowsize);
  T->open = 1;
  return T->row;
}

void aq_h5w_table_close_quietly(aq_h5w_table *T)
{
  row_strings_free(T, 1);
  T->nbuf = 0;
  if (T->ft >= 0)
    H5Tclose(T->ft);
  T->ft = -1;
}

void aq_h5w_table_free(aq_h5w_table *T)
{
  free(T->buf);
  free(T->row);
  free(T->at);
}

herr_t aq_h5w_table_close(aq_h5_writer *w, aq_h5w_table *T)
{
  herr_t rc = row_commit(w, T) < 0 ? -1 : table_flush(w, T);
  if (rc >= 0 && H5Dclose(T->d) < 0)
    rc = -1;
  if (rc >= 0)
    T->d = -1;
  if (rc >= 0 && H5Tclose(T->ft) < 0)
    rc = -1;
  if (rc >= 0)
    T->ft = -1;
  return rc;
}
