/* units.h: the one conversion constant.  SI inside (m, s, kg, J, rad);
 * g and degrees only at the edges (readers, options, report columns). */
#ifndef AQ_UNITS_H
#define AQ_UNITS_H

#define AQ_G0_MPS2 9.80665 /* standard gravity, m/s^2 (CGPM 1901) */
#define AQ_PI 3.14159265358979323846
#define AQ_DEG_RAD (AQ_PI / 180.0) /* radians per degree */

#endif
