/* units.c: units words and factors (units.h). */
#include "units.h"

#include <stddef.h>
#include <strings.h>

#include "../units.h"

static const struct {
  const char *word;
  aq_units units;
} units_words[] = {
    {"g", AQ_UNITS_G},           {"gal", AQ_UNITS_GAL},
    {"cm/s2", AQ_UNITS_GAL},     {"cm/s^2", AQ_UNITS_GAL},
    {"cm/s/s", AQ_UNITS_GAL},    {"cm/sec2", AQ_UNITS_GAL},
    {"cm/sec^2", AQ_UNITS_GAL},  {"cm/sec/sec", AQ_UNITS_GAL},
    {"cmps2", AQ_UNITS_GAL},     {"m/s2", AQ_UNITS_MPS2},
    {"m/s^2", AQ_UNITS_MPS2},    {"m/s/s", AQ_UNITS_MPS2},
    {"m/s**2", AQ_UNITS_MPS2},   {"mps2", AQ_UNITS_MPS2},
    {"nm/s2", AQ_UNITS_NMPS2},   {"nm/s^2", AQ_UNITS_NMPS2},
    {"nm/s/s", AQ_UNITS_NMPS2},  {"counts", AQ_UNITS_COUNTS},
    {"g/10", AQ_UNITS_G10},      {"mm/s2", AQ_UNITS_MMPS2},
    {"mm/s^2", AQ_UNITS_MMPS2},  {"mm/s/s", AQ_UNITS_MMPS2},
    {"mm/sec2", AQ_UNITS_MMPS2}, {"mm/sec/sec", AQ_UNITS_MMPS2},
};

int aq_units_parse(const char *s, aq_units *out)
{
  if (!s)
    return 0;
  for (size_t i = 0; i < sizeof units_words / sizeof units_words[0]; i++)
    if (strcasecmp(s, units_words[i].word) == 0) {
      *out = units_words[i].units;
      return 1;
    }
  return 0;
}

const char *aq_units_name(aq_units u)
{
  switch (u) {
  case AQ_UNITS_FILE:
    return "file";
  case AQ_UNITS_G:
    return "g";
  case AQ_UNITS_GAL:
    return "gal";
  case AQ_UNITS_MPS2:
    return "m/s2";
  case AQ_UNITS_NMPS2:
    return "nm/s2";
  case AQ_UNITS_COUNTS:
    return "counts";
  case AQ_UNITS_G10:
    return "g/10";
  case AQ_UNITS_MMPS2:
    return "mm/s2";
  }
  return "?";
}

double aq_units_to_mps2(aq_units u)
{
  switch (u) {
  case AQ_UNITS_G:
    return AQ_G0_MPS2;
  case AQ_UNITS_GAL:
    return 0.01;
  case AQ_UNITS_MPS2:
    return 1.0;
  case AQ_UNITS_NMPS2:
    return 1e-9;
  case AQ_UNITS_G10:
    return AQ_G0_MPS2 / 10.0;
  case AQ_UNITS_MMPS2:
    return 1e-3;
  case AQ_UNITS_FILE:
  case AQ_UNITS_COUNTS:
    break;
  }
  return 0.0;
}

aq_quantity aq_units_quantity(const char *word)
{
  static const char *const vel[] = {"cm/s", "cm/sec", "m/s", "m/sec", "mm/s", "mm/sec",
                                    "nm/s", "nm/sec", "in/s", "in/sec", "kine"};
  static const char *const disp[] = {"cm", "m", "mm", "nm", "in", "inch", "inches"};
  aq_units u;
  if (!word || !*word)
    return AQ_QUANTITY_UNSTATED;
  if (aq_units_parse(word, &u))
    return u == AQ_UNITS_COUNTS ? AQ_QUANTITY_UNSTATED : AQ_QUANTITY_ACCELERATION;
  for (size_t i = 0; i < sizeof vel / sizeof vel[0]; i++)
    if (strcasecmp(word, vel[i]) == 0)
      return AQ_QUANTITY_VELOCITY;
  for (size_t i = 0; i < sizeof disp / sizeof disp[0]; i++)
    if (strcasecmp(word, disp[i]) == 0)
      return AQ_QUANTITY_DISPLACEMENT;
  return AQ_QUANTITY_UNSTATED;
}

const char *aq_quantity_name(aq_quantity q)
{
  switch (q) {
  case AQ_QUANTITY_ACCELERATION:
    return "acceleration";
  case AQ_QUANTITY_VELOCITY:
    return "velocity";
  case AQ_QUANTITY_DISPLACEMENT:
    return "displacement";
  case AQ_QUANTITY_UNSTATED:
    break;
  }
  return "unstated";
}
