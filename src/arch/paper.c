/* paper.c: the paper's printed method (see paper.h). */
#include "paper.h"

#include <stdlib.h>

struct aq_paper {
  int dummy;
};

aq_paper *aq_paper_alloc(const aq_path *primary, const aq_path *reverse,
                         aq_error *err)
{
  (void)primary;
  (void)reverse;
  aq_error_set(err, AQ_EUNSUPPORTED, NULL, -1, -1, "model",
               "the paper model is not available yet");
  return NULL;
}

void aq_paper_free(aq_paper *w) { free(w); }

double aq_paper_wmin(const aq_paper *w, int set, double s)
{
  (void)w;
  (void)set;
  (void)s;
  return 0;
}

aq_status aq_paper_leg(aq_paper *w, int set, double a_mps2, aq_motion *m,
                       double dt_s, double *used_s, aq_leg_end *end,
                       aq_leg_stats *stats, aq_error *err)
{
  (void)w; (void)set; (void)a_mps2; (void)m; (void)dt_s; (void)stats;
  *used_s = 0;
  *end = AQ_LEG_REST;
  return aq_error_set(err, AQ_EUNSUPPORTED, NULL, -1, -1, "model",
                      "the paper model is not available yet");
}
