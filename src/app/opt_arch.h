/* opt_arch.h: what --arch names.  A path (it has a '/' or ends in .cfg) is
 * the arch file itself; a bare name (oppenheim) is an installed arch,
 * NAME.cfg in the first of these arch directories that has it:
 *   $ARCHQUAKE_DATADIR/arches        (the environment overrides ...)
 *   PREFIX/share/archquake/arches    (... the data directory built in)
 *   BINDIR/../share/archquake/arches (an installation moved or staged)
 *   BINDIR/arches                    (the source tree: ./archquake)
 * and otherwise a file of that name in the working directory.  An unknown
 * name is reported in one line listing the installed arches.  The
 * resolved paths stay valid until the program ends. */
#ifndef AQ_APP_OPT_ARCH_H
#define AQ_APP_OPT_ARCH_H

#include <stdio.h>

/* The arch file that arg names: arg itself, or the installed file.  An
 * unknown name: one line on stderr, *nerr += 1, and arg is returned. */
char *aq_opt_arch(char *arg, int *nerr);

/* The paragraph of the usage on arch names, with the directories above. */
void aq_opt_arch_usage(FILE *f);

#endif
