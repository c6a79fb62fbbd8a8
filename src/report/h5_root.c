/* h5_root.c: the root of a results, capacity or spectrum file (h5.h): its
 * attributes (version, command line, processing, model, scales) and the
 * tables and groups its kind holds. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "h5_writer.h"

/* Processing parameters requested (root attributes). */
static herr_t write_proc(aq_h5_writer *w, hid_t loc, const aq_signal_opts *p)
{
  if (aq_h5w_attr_str(w, loc, "detrend", aq_h5w_detrend_name(p->detrend)) < 0 ||
      aq_h5w_attr_int(w, loc, "filter", p->filter ? 1 : 0) < 0 ||
      aq_h5w_attr_double(w, loc, "taper_frac", p->filter ? p->taper_frac : 0.0) < 0 ||
      aq_h5w_attr_double(w, loc, "highpass_hz", p->filter ? p->highpass_hz : NAN) < 0 ||
      aq_h5w_attr_int(w, loc, "highpass_order", p->filter ? p->order : 0) < 0 ||
      aq_h5w_attr_double(w, loc, "lowpass_hz",
                         p->filter && p->lowpass_hz > 0 ? p->lowpass_hz : NAN) < 0 ||
      aq_h5w_attr_str(w, loc, "peaks", aq_spectrum_peaks_names[p->peaks]) < 0)
    return -1;
  return 0;
}

aq_status aq_h5_write_root(aq_h5_writer *w, const aq_h5_root *r, aq_error *err)
{
  return aq_h5_write_root_kind(w, r, "results", err);
}

aq_status aq_h5_write_root_kind(aq_h5_writer *w, const aq_h5_root *r, const char *kind,
                                aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/records";
  hid_t f = w->file;
  if (!w->records.buf)
    CK(aq_h5w_records_open(w, r->proc), "table");
  obj = "/";
  w->store_records = r->store_records;
  CK(aq_h5w_attr_str(w, f, "archquake_version", r->version), "root attributes");
  CK(aq_h5w_attr_str(w, f, "archquake_build", r->build ? r->build : r->version),
     "root attributes");
  CK(aq_h5w_attr_int(w, f, "format_version", AQ_H5_FORMAT_VERSION), "root attributes");
  CK(aq_h5w_attr_str(w, f, "command_line", r->command_line), "root attributes");
  CK(aq_h5w_attr_str(w, f, "created", r->created), "root attributes");
  if (r->proc)
    CK(write_proc(w, f, r->proc), "root attributes");
  kind = kind ? kind : "results";
  int results = strcmp(kind, "results") == 0, capacity = strcmp(kind, "capacity") == 0;
  CK(aq_h5w_attr_str(w, f, "kind", kind), "root attributes");
  if (results || capacity) { /* the files with arches */
    obj = "/arches";
    CK(aq_h5w_lazy_group(w, &w->g_arches, obj), "H5Gcreate");
  }
  w->no_runs = !results;
  if (results && !w->runs.buf) { /* and with runs */
    obj = "/summary";
    CK(aq_h5w_runs_open(w), "table");
  }
  obj = "/";
  if (!results && !capacity) { /* no runs: only what applies */
    CK(aq_h5w_attr_str(w, f, "units_override", r->units ? r->units : "file"), "root attributes");
    CK(aq_h5w_attr_int(w, f, "timing_threads", r->threads), "root attributes");
    return AQ_OK;
  }
  CK(aq_h5w_attr_double(w, f, "merge_tol_g", r->merge_tol_g), "root attributes");
  CK(aq_h5w_attr_str(w, f, "units_override", r->units ? r->units : "file"),
     "root attributes");
  CK(aq_h5w_attr_double(w, f, "dt_override_s",
                        r->dt_override_s > 0 ? r->dt_override_s : NAN),
     "root attributes");
  CK(aq_h5w_attr_str(w, f, "model", r->model), "root attributes");
  CK(aq_h5w_attr_double(w, f, "cor", r->cor), "root attributes");
  if (capacity) { /* the scales are the search's (capacity attributes), no histories */
    CK(aq_h5w_attr_str(w, f, "polarity", r->polarity ? r->polarity : "normal"), "root attributes");
    CK(aq_h5w_attr_int(w, f, "timing_threads", r->threads), "root attributes");
    return AQ_OK;
  }
  if (r->scales) {
    CK(aq_h5w_attr_str(w, f, "scale_mode", "list"), "root attributes");
    CK(aq_h5w_attr_doubles(f, "scales", r->scales, r->nscale), "root attributes");
  } else {
    CK(aq_h5w_attr_str(w, f, "scale_mode", r->scale_to_lambda0 > 0 ? "lambda0" : "pga"),
       "root attributes");
  }
  CK(aq_h5w_attr_double(w, f, "scale_to_lambda0",
                        r->scale_to_lambda0 > 0 ? r->scale_to_lambda0 : NAN),
     "root attributes");
  CK(aq_h5w_attr_double(w, f, "scale_to_pga_g", r->scale_to_pga_g), "root attributes");
  CK(aq_h5w_attr_int(w, f, "history", r->history ? 1 : 0), "root attributes");
  CK(aq_h5w_attr_int(w, f, "store_records", r->store_records ? 1 : 0), "root attributes");
  CK(aq_h5w_attr_str(w, f, "polarity", r->polarity ? r->polarity : "normal"), "root attributes");
  CK(aq_h5w_attr_int(w, f, "timing_threads", r->threads), "root attributes");
  return AQ_OK;
fail:
  return st;
}
