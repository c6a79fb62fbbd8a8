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
