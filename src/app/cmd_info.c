/* cmd_info.c: `archquake info [OPTIONS] RECORD...`: one TSV row per record. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../io/record.h"
#include "../signal/signal.h"
#include "../units.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"
#include "opt_table.h"
#include "opt_record.h"

/* One row for rec (processed by so in ws); 1 if it failed (reported). */
static int describe(const aq_record *rec, const aq_signal_opts *so, aq_signal_ws *ws)
{
  aq_error err;
  aq_error_clear(&err);
  aq_processed p;
  aq_im im;
  if (aq_signal_process(rec, so, ws, &p, &err) != AQ_OK ||
      aq_im_compute(&p, &im, &err) != AQ_OK) {
    if (!err.input[0])
      snprintf(err.input, sizeof err.input, "%s", rec->path);
    aq_error_print(&err, stderr);
    aq_processed_free(&p);
    return 1;
  }
  if (rec->units_conflict[0])
    fprintf(stderr, "archquake: %s: units: %s\n", rec->path, rec->units_conflict);
  aq_record_print_notes(rec, stderr);
  char warn[256];
  if (aq_im_residual_warning(&im, warn, sizeof warn))
    fprintf(stderr, "archquake: %s: warning: %s\n", rec->path, warn);
  printf("%s\t%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s", rec->path, rec->format,
         rec->npts, AQ_TEXT_NUM(rec->dt_s), AQ_TEXT_NUM(rec->dt_s * (double)rec->npts),
         rec->units_orig, AQ_TEXT_NUM(im.pga_g), AQ_TEXT_NUM(im.pgv_mps), AQ_TEXT_NUM(im.pgd_m),
         AQ_TEXT_NUM(im.arias_mps), AQ_TEXT_NUM(im.d5_95_s), AQ_TEXT_NUM(im.cav_mps), rec->channel,
         rec->vertical ? "yes" : "no", AQ_TEXT_NUM(im.pgv_pga_s));
  for (size_t k = 0; k < aq_im_spectral_count(so); k++)
    printf("\t%s", AQ_TEXT_NUM(aq_im_spectral_value(&im, k)));
  putchar('\n');
  aq_processed_free(&p);
  return 0;
}

int aq_cmd_info(int argc, char **argv)
{
  aq_opts o;
  aq_opts_init(&o, AQ_CMD_INFO);
  int nerr = 0;
  if (aq_opts_parse(AQ_CMD_INFO, argc, argv, &o, &nerr))
    return AQ_EXIT_OK; /* --help */
  aq_read_opts ro = o.read;
  aq_signal_opts so = o.proc;
  argc = optind + (int)aq_read_opts_take_stationxml(argv + optind, (size_t)(argc - optind), &ro);
  if (optind >= argc) {
    fprintf(stderr, "archquake: info: expected at least one RECORD\n");
    nerr++;
  }
  if (nerr)
    return AQ_EXIT_USAGE;

  aq_signal_ws *ws = aq_signal_ws_alloc();
  if (!ws) {
    fprintf(stderr, "archquake: info: out of memory\n");
    return AQ_EXIT_FAIL;
  }
  int failed = 0;
  printf("file\tformat\tnpts\tdt_s\tduration_s\tunits\tpga_g\tpgv_m_s\t"
         "pgd_m\tarias_m_s\td5_95_s\tcav_m_s\tchannel\tvertical\tpgv_pga_s");
  for (size_t k = 0; k < aq_im_spectral_count(&so); k++) {
    char name[64];
    aq_im_spectral_name(&so, k, name, sizeof name);
    printf("\t%s", name);
  }
  putchar('\n');
  for (int op = optind; op < argc; op++) { /* every channel a record (FILE#CH) */
    aq_record_set set;
    aq_error xerr;
    if (aq_record_read_all(argv[op], &ro, 0, &set, &xerr) != AQ_OK) {
      aq_error_print(&xerr, stderr);
      aq_signal_ws_free(ws);
      return AQ_EXIT_FAIL;
    }
    for (size_t i = 0; i < set.n; i++) {
      aq_record_item *it = &set.item[i];
      if (it->status != AQ_OK) {
        aq_error_print(&it->err, stderr);
        failed = 1;
        continue;
      }
      failed |= describe(&it->rec, &so, ws);
    }
    aq_record_set_free(&set);
  }
  aq_signal_ws_free(ws);
  fflush(stdout);
  return failed ? AQ_EXIT_FAIL : AQ_EXIT_OK;
}
