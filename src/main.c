/* main.c: archquake's entry point.  It only hands the command line to the
 * dispatcher (src/app/dispatch.c); every stage lives in its own module:
 *   src/io -> src/signal -> src/arch -> src/job -> src/capacity
 *   -> src/report -> src/plot -> src/page, src/app on top.
 *
 * archquake implements the work-path approach of Stockdale, Sarhosis &
 * Milani, with the departures from the printed formulas that docs/method.md
 * gives (each with its reason).
 */
#include "app/app.h"

int main(int argc, char **argv)
{
  return aq_app_main(argc, argv);
}
