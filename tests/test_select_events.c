/* test_select_events.c: the event each record names, as select's
 * --max-per-event compares it (aq_record.event_key: the reader reports the
 * event alone, io/record.c decides the key).  Expected: the events that
 * tests/data/records/PROVENANCE.md and agency/PROVENANCE.md give each file
 * (components of one recording share an event; records of one event at
 * two stations too; a CSMIP file's "Record of" line is the record's trigger
 * time, not an event; an AT2 text line's station and component are not
 * part of its event). */
#include <string.h>

#include "check.h"
#include "io/record.h"

#define R "tests/data/records/"

static void key_of(const char *path, char *key, size_t n)
{
  aq_record rec;
  aq_error e;
  aq_read_opts ro = {0};
  key[0] = '\0';
  if (!aq_check(aq_record_read(path, &ro, &rec, &e) == AQ_OK, "%s: %s", path, e.message))
    return;
  snprintf(key, n, "%s", rec.event_key);
  aq_record_free(&rec);
}

AQ_TEST(io_event_keys_for_select)
{
  static const struct {
    const char *a, *b; /* one event */
  } same[] = {
      {R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2"},
      {R "RSN763_LOMAP_GIL067.AT2", R "RSN763_LOMAP_GIL337.AT2"},
      {R "CHY028-N.AT2", R "TCU052-N.AT2"}, /* Chi-Chi at two stations */
      {R "AOM0170806140843.NS", R "AOM0170806140843.EW"},
      {R "agency/ce36456p_CE36456.V2#90", R "agency/ce36456p_CE36456.V2#0"},
      {R "2-ECU.dat#N", R "2-ECU.dat#E"},
      {R "copiapo1002271.v1#EW", R "copiapo1002271.v1#NZ"},
  };
  char a[96], b[96];
  for (size_t i = 0; i < sizeof same / sizeof same[0]; i++) {
    key_of(same[i].a, a, sizeof a);
    key_of(same[i].b, b, sizeof b);
    aq_check(a[0] && !strcmp(a, b), "%s and %s: one event (\"%s\", \"%s\")", same[i].a,
             same[i].b, a, b);
  }
  static const struct {
    const char *path, *key;
  } want[] = {
      /* NGA-West2 "Event, date, station, component": the first two fields */
      {R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "imperial valley 02 5 19 1940"},
      {R "RSN1616_DUZCE_362-E.AT2", "duzce turkey 11 12 1999"},
      /* the older PEER line "EVENT DATE TIME, STATION, COMPONENT" */
      {R "ARL360.at2", "northridge 01 17 94 1231"},
      {R "agency/ce36456p_CE36456.V2#90", "coalinga earthquake"},
      {R "2-ECU.dat#N", "origin time gmt 08 2018 02 06 23 50 42"},
      {R "copiapo1002271.v1#EW", "maule 2010"},
      /* CSMIP's "Record of Mon Feb 13, 2012 ..." names the record: none */
      {R "agency/CE89146.V1#360", ""},
      /* a CSV without a header of its own: none */
      {R "kocaeli.csv", ""},
  };
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
    key_of(want[i].path, a, sizeof a);
    aq_check(!strcmp(a, want[i].key), "%s: \"%s\", want \"%s\"", want[i].path, a,
             want[i].key);
  }
  /* two events */
  key_of(R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2", a, sizeof a);
  key_of(R "RSN763_LOMAP_GIL067.AT2", b, sizeof b);
  aq_check(strcmp(a, b) != 0, "Imperial Valley and Loma Prieta differ");
}
