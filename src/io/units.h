/* units.h: the units a record's values may be in, as words (what a file or
 * --units states: "g", "cm/s2", ...) and as factors to m/s^2.  Shared by the
 * readers (which report the units a file states) and record.c (which
 * decides the units that apply).  Pure functions; no allocation.
 */
#ifndef AQ_IO_UNITS_H
#define AQ_IO_UNITS_H

/* Units of a record's values.  AQ_UNITS_FILE: take the units from the file
 * (as an override: none given). */
typedef enum {
  AQ_UNITS_FILE = 0,
  AQ_UNITS_G,
  AQ_UNITS_GAL,    /* = cm/s^2 */
  AQ_UNITS_MPS2,
  AQ_UNITS_NMPS2,
  AQ_UNITS_COUNTS, /* divided by the sensitivity (SAC SCALE, counts per m/s^2) */
  AQ_UNITS_G10,    /* tenths of g (some agency formats) */
  AQ_UNITS_MMPS2   /* mm/s^2 */
} aq_units;

/* What a record's values are, as a file states it. */
typedef enum {
  AQ_QUANTITY_UNSTATED = 0,
  AQ_QUANTITY_ACCELERATION,
  AQ_QUANTITY_VELOCITY,
  AQ_QUANTITY_DISPLACEMENT
} aq_quantity;

/* The quantity a units word measures: acceleration for the words
 * aq_units_parse takes (but counts), velocity for cm/s, cm/sec, m/s, mm/s,
 * nm/s, in/s (also written /sec), displacement for cm, m, mm, nm, in;
 * AQ_QUANTITY_UNSTATED for anything else.  Case-insensitive. */
aq_quantity aq_units_quantity(const char *word);

/* "acceleration", "velocity", "displacement" or "unstated". */
const char *aq_quantity_name(aq_quantity q);

/* Parse a units word: g, gal, cm/s2 (also cm/s^2, cm/s/s, cm/sec2, cmps2),
 * m/s2 (m/s^2, m/s/s, mps2), mm/s2, nm/s2 (nm/s^2), g/10, counts;
 * case-insensitive.
 * Returns 1 and sets *out on success, 0 if s is not one of them. */
int aq_units_parse(const char *s, aq_units *out);

/* The canonical name of u ("g", "gal", "m/s2", "nm/s2", "counts", "file"). */
const char *aq_units_name(aq_units u);

/* Metres per second squared per unit of u (g: 9.80665, gal: 0.01, ...);
 * 0 for AQ_UNITS_FILE and AQ_UNITS_COUNTS (counts need a sensitivity). */
double aq_units_to_mps2(aq_units u);

#endif
