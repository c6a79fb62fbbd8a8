/* h5_records.c: /records (one row per record: its file, metadata,
 * processing and intensity measures) and /waveforms (the processed records,
 * with --store-records) of the results writer (h5.h, h5_writer.h). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "../io/sha256.h"
#include "h5_writer.h"

/* A row of /records.  A new metadata field of aq_record is one member here,
 * one line in record_cols and one in aq_h5_write_record. */
typedef struct {
  /* the user's strings, whole (variable-length strings, owned by the row
   * until the flush: see row_strings) */
  char *source_file; /* path as given */
  char *name;        /* file name without directories */
  char sha256[65];   /* of the file's bytes */
  char status[AQ_SUMMARY_STATUS_MAX];
  char *error;
  /* as read */
  char format[16];
  char units_orig[24];
  double to_m_s2;
  char units_stated[24], units_source[12];
  int64_t npts;
  double dt_s, begin_s;
  char reference_time[40];
  char network[16], station[16], location[16], channel[16];
  int64_t vertical; /* 1 vertical, 0 horizontal, -1 not read */
  char vertical_by[8];
  /* processing used */
  char detrend[8];
  int64_t filter;
  double taper_frac, highpass_hz;
  int64_t highpass_order;
  double lowpass_hz;
  int64_t pad_front, pad_back, n_orig;
  /* intensity measures of the processed, unscaled record */
  double pga_g, pgv_m_s, pgd_m, arias_m_s, d5_95_s, cav_m_s, v_end_m_s, d_end_m;
  double pgv_pga_s;
  double sa[AQ_IM_SA_MAX + 1]; /* the spectral measures (aq_im_spectral_value),
                                  columns named by the root's options */
  double timing_read_s, timing_process_s;
  char waveform[40]; /* path of its /waveforms dataset, "" if not stored */
} record_row;

#define REC_COL(f, kind, units) AQ_H5_COL(record_row, f, kind, units)
static const aq_h5_col record_cols[] = {
    REC_COL(source_file, AQ_H5_VSTR, ""), REC_COL(name, AQ_H5_VSTR, ""),
    REC_COL(sha256, AQ_H5_STR, ""),      REC_COL(status, AQ_H5_STR, ""),
    REC_COL(error, AQ_H5_VSTR, ""),       REC_COL(format, AQ_H5_STR, ""),
    REC_COL(units_orig, AQ_H5_STR, ""),  REC_COL(to_m_s2, AQ_H5_DOUBLE, "m/s^2 per file unit"),
    REC_COL(units_stated, AQ_H5_STR, ""), REC_COL(units_source, AQ_H5_STR, ""),
    REC_COL(npts, AQ_H5_INT, "1"),       REC_COL(dt_s, AQ_H5_DOUBLE, "s"),
    REC_COL(begin_s, AQ_H5_DOUBLE, "s"), REC_COL(reference_time, AQ_H5_STR, ""),
    REC_COL(network, AQ_H5_STR, ""),     REC_COL(station, AQ_H5_STR, ""),
    REC_COL(location, AQ_H5_STR, ""),    REC_COL(channel, AQ_H5_STR, ""),
    REC_COL(vertical, AQ_H5_INT, "1"),   REC_COL(vertical_by, AQ_H5_STR, ""),
    REC_COL(detrend, AQ_H5_STR, ""),     REC_COL(filter, AQ_H5_INT, "1"),
    REC_COL(taper_frac, AQ_H5_DOUBLE, "1"), REC_COL(highpass_hz, AQ_H5_DOUBLE, "Hz"),
    REC_COL(highpass_order, AQ_H5_INT, "1"), REC_COL(lowpass_hz, AQ_H5_DOUBLE, "Hz"),
    REC_COL(pad_front, AQ_H5_INT, "1"),  REC_COL(pad_back, AQ_H5_INT, "1"),
    REC_COL(n_orig, AQ_H5_INT, "1"),     REC_COL(pga_g, AQ_H5_DOUBLE, "g"),
    REC_COL(pgv_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(pgd_m, AQ_H5_DOUBLE, "m"),
    REC_COL(arias_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(d5_95_s, AQ_H5_DOUBLE, "s"),
    REC_COL(cav_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(v_end_m_s, AQ_H5_DOUBLE, "m/s"),
    REC_COL(d_end_m, AQ_H5_DOUBLE, "m"), REC_COL(pgv_pga_s, AQ_H5_DOUBLE, "s"),
    REC_COL(timing_read_s, AQ_H5_DOUBLE, "s"),
    REC_COL(timing_process_s, AQ_H5_DOUBLE, "s"), REC_COL(waveform, AQ_H5_STR, ""),
};
enum { N_RECORD_COLS = sizeof record_cols / sizeof record_cols[0] };
_Static_assert(N_RECORD_COLS == AQ_H5W_RECORD_COLS, "AQ_H5W_RECORD_COLS: the count of record_cols");

void aq_h5w_records_init(aq_h5_writer *w)
{
  w->records.owned[w->records.nowned++] = offsetof(record_row, source_file);
  w->records.owned[w->records.nowned++] = offsetof(record_row, name);
  w->records.owned[w->records.nowned++] = offsetof(record_row, error);
}

const char *aq_h5w_detrend_name(aq_detrend d)
{
  switch (d) {
  case AQ_DETREND_MEAN:
    return "mean";
  case AQ_DETREND_LINEAR:
    return "linear";
  case AQ_DETREND_NONE:
    return "none";
  }
  return "unknown";
}

/* How a record was known to be vertical (/records vertical_by). */
static const char *vertical_by_name(int by)
{
  switch (by) {
  case AQ_VERTICAL_BY_STATED:
    return "stated";
  case AQ_VERTICAL_BY_DIP:
    return "dip";
  case AQ_VERTICAL_BY_NAME:
    return "name";
  }
  return "";
}

herr_t aq_h5w_records_open(aq_h5_writer *w, const aq_signal_opts *proc)
{
  memcpy(w->rec_cols, record_cols, sizeof record_cols);
  w->n_spectral = proc ? aq_im_spectral_count(proc) : 0;
  for (size_t k = 0; k < w->n_spectral; k++) {
    aq_im_spectral_name(proc, k, w->rec_names[k], sizeof w->rec_names[k]);
    w->rec_cols[N_RECORD_COLS + k] =
        (aq_h5_col){w->rec_names[k], AQ_H5_DOUBLE, offsetof(record_row, sa) + k * sizeof(double),
                 sizeof(double), "g"};
  }
  w->n_rec_cols = N_RECORD_COLS + w->n_spectral;
  return aq_h5w_table_open(w, &w->records, "/records", w->rec_cols, w->n_rec_cols,
                           sizeof(record_row), AQ_H5_RECORDS_CHUNK);
}

#define COPY(dst, src) snprintf((dst), sizeof(dst), "%s", (src) ? (src) : "")

aq_status aq_h5_write_record(aq_h5_writer *w, size_t index,
                             const aq_h5_record *r, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/records";
  if (!w->records.buf) /* no root written: the fixed columns */
    CK(aq_h5w_records_open(w, NULL), "table");
  record_row *row = aq_h5w_table_row(w, &w->records);
  CK(row ? 0 : -1, "rows");
  const char *base = r->source_file ? strrchr(r->source_file, '/') : NULL;
  row->source_file = aq_h5w_row_string(r->source_file);
  row->error = aq_h5w_row_string(r->error);
  row->name = aq_h5w_row_string(r->rec ? r->rec->name : base ? base + 1 : r->source_file);
  CK(row->source_file && row->error && row->name ? 0 : -1, "rows (out of memory)");
  COPY(row->sha256, r->sha256);
  if (!r->sha256 && r->rec && r->source_file) { /* a command that did not hash it
                                                   (capacity, spectrum): its file's */
    char file[4096];
    aq_error herr;
    if (aq_sha256_file(aq_record_file(r->source_file, file, sizeof file), row->sha256,
                       &herr) != AQ_OK)
      row->sha256[0] = '\0';
  }
  COPY(row->status, r->status ? r->status : "ok");
  row->to_m_s2 = row->dt_s = row->begin_s = NAN;
  row->taper_frac = row->highpass_hz = row->lowpass_hz = NAN;
  row->pga_g = row->pgv_m_s = row->pgd_m = row->arias_m_s = NAN;
  row->d5_95_s = row->cav_m_s = row->v_end_m_s = row->d_end_m = NAN;
  row->vertical = -1;
  row->pgv_pga_s = NAN;
  for (size_t k = 0; k < w->n_spectral; k++)
    row->sa[k] = NAN;
  if (r->rec) {
    const aq_record *rec = r->rec;
    COPY(row->format, rec->format);
    COPY(row->units_orig, rec->units_orig);
    row->to_m_s2 = rec->to_mps2;
    row->npts = (int64_t)rec->npts;
    row->dt_s = rec->dt_s;
    row->begin_s = rec->begin_s;
    COPY(row->reference_time, rec->reference);
    COPY(row->network, rec->network);
    COPY(row->station, rec->station);
    COPY(row->location, rec->location);
    COPY(row->channel, rec->channel);
    COPY(row->units_stated, rec->units_stated);
    COPY(row->units_source, rec->units_by);
    row->vertical = rec->vertical ? 1 : 0;
    COPY(row->vertical_by, vertical_by_name(rec->vertical_by));
  }
  if (r->proc) {
    const aq_processed *p = r->proc;
    const aq_signal_opts *u = &p->used;
    COPY(row->detrend, aq_h5w_detrend_name(u->detrend));
    row->filter = u->filter ? 1 : 0;
    row->taper_frac = u->filter ? u->taper_frac : 0.0;
    row->highpass_hz = u->filter ? u->highpass_hz : NAN;
    row->highpass_order = u->filter ? u->order : 0;
    row->lowpass_hz = u->filter && u->lowpass_hz > 0 ? u->lowpass_hz : NAN;
    row->pad_front = (int64_t)p->pad_front;
    row->pad_back = (int64_t)p->pad_back;
    row->n_orig = (int64_t)p->n_orig;
    if (w->store_records) {
      char name[32];
      snprintf(name, sizeof name, "/waveforms/%05zu", index);
      static const char *const time_attr[2] = {"dt_s", "t0_s"};
      const double time_val[2] = {p->dt_s, -(double)p->pad_front * p->dt_s};
      obj = "/waveforms";
      CK(aq_h5w_lazy_group(w, &w->g_waveforms, obj), "H5Gcreate");
      obj = "acceleration";
      CK(aq_h5w_dataset_1d(w, w->file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                           p->acc_mps2, p->n, "m/s^2", 2, time_attr, time_val, 1),
         name);
      snprintf(row->waveform, sizeof row->waveform, "%s", name);
    }
  }
  if (r->im) {
    const aq_im *m = r->im;
    row->pga_g = m->pga_g;
    row->pgv_m_s = m->pgv_mps;
    row->pgd_m = m->pgd_m;
    row->arias_m_s = m->arias_mps;
    row->d5_95_s = m->d5_95_s;
    row->cav_m_s = m->cav_mps;
    row->v_end_m_s = m->v_end_mps;
    row->d_end_m = m->d_end_m;
    row->pgv_pga_s = m->pgv_pga_s;
    for (size_t k = 0; k < w->n_spectral; k++)
      row->sa[k] = aq_im_spectral_value(m, k);
  }
  row->timing_read_s = r->timing_read_s;
  row->timing_process_s = r->timing_process_s;
  return AQ_OK;
fail:
  return st;
}
