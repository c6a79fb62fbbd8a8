/* cmd_info.c: `archquake info [OPTIONS] RECORD...`: one TSV row per record. */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../io/record.h"
#include "../units.h"
#include "app.h"
#include "opt.h"
#include "opt_record.h"

static const char usage[] =
    "usage: archquake info [OPTIONS] RECORD...\n"
    "Describe accelerograms: one TSV row per record on stdout.\n"
    AQ_OPT_RECORD_USAGE
    "  --help          this text\n"
    "Columns: file format npts dt_s duration_s units pga_g\n"
    "Exit status: 0 all records read, 1 some record failed, 2 bad options.\n";

int aq_cmd_info(int argc, char **argv)
{
  static const struct option longopts[] = {
      AQ_OPT_RECORD_LONGOPTS,
      {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  aq_read_opts ro = {0};
  int nerr = 0, c;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":", longopts, NULL)) != -1) {
    switch (c) {
    case 'h':
      fputs(usage, stdout);
      return AQ_EXIT_OK;
    default:
      if (!aq_opt_record_handle(c, optarg, &ro, &nerr))
        aq_opt_unknown("info ", argv, optind, optopt, &nerr);
    }
  }
  if (optind >= argc) {
    fprintf(stderr, "archquake: info: expected at least one RECORD\n");
    nerr++;
  }
  if (nerr)
    return AQ_EXIT_USAGE;

  int failed = 0;
  printf("file\tformat\tnpts\tdt_s\tduration_s\tunits\tpga_g\n");
  for (int i = optind; i < argc; i++) {
    aq_record rec;
    aq_error err;
    aq_error_clear(&err);
    if (aq_record_read(argv[i], &ro, &rec, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      failed = 1;
      continue;
    }
    double mean = 0, pga = 0;
    for (size_t k = 0; k < rec.npts; k++)
      mean += rec.acc_mps2[k];
    mean /= rec.npts ? (double)rec.npts : 1.0;
    for (size_t k = 0; k < rec.npts; k++)
      pga = fmax(pga, fabs(rec.acc_mps2[k] - mean));
    printf("%s\t%s\t%zu\t%.9g\t%.9g\t%s\t%.6g\n", rec.path, rec.format,
           rec.npts, rec.dt_s, rec.dt_s * (double)rec.npts, rec.units_orig,
           pga / AQ_G0_MPS2);
    aq_record_free(&rec);
  }
  fflush(stdout);
  return failed ? AQ_EXIT_FAIL : AQ_EXIT_OK;
}
