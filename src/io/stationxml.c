/* stationxml.c: the instrument sensitivity, azimuth and dip of each channel
 * epoch of an FDSN StationXML file, through libxml2 (reader.h).
 *
 * Read: Network@code / Station@code / Channel@code, @locationCode,
 * @startDate, @endDate, with Azimuth, Dip and Response/InstrumentSensitivity
 * (Value, InputUnits/Name).  Elements are matched by local name, so the
 * namespace version does not matter.  The sensitivity is counts per input
 * unit; aq_stationxml_apply() turns it into counts per m/s^2 for the epoch
 * that covers a record's start, keeping its sign (a negative sensitivity
 * means the sensor's polarity is reversed).  libxml2 never prints here
 * (XML_PARSE_NOERROR | XML_PARSE_NOWARNING) and never touches the network.
 */
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../units.h"
#include "fixed.h"
#include "reader.h"

#define SXML_MAX_EPOCHS 100000
#define SXML_DIP_TOL_DEG 1.0 /* |dip| within this of 90 (or 0) is vertical (horizontal) */

static int is(const xmlNode *nd, const char *local)
{
  return nd->type == XML_ELEMENT_NODE && strcmp((const char *)nd->name, local) == 0;
}

static const xmlNode *child(const xmlNode *nd, const char *local)
{
  for (const xmlNode *c = nd ? nd->children : NULL; c; c = c->next)
    if (is(c, local))
      return c;
  return NULL;
}

static void attr(const xmlNode *nd, const char *key, char *out, size_t cap)
{
  out[0] = '\0';
  xmlChar *v = xmlGetProp((xmlNode *)nd, (const xmlChar *)key);
  if (v) {
    aq_copy_trim(out, cap, (const char *)v, strlen((const char *)v));
    xmlFree(v);
  }
}

static void text(const xmlNode *nd, char *out, size_t cap)
{
  out[0] = '\0';
  if (!nd)
    return;
  xmlChar *v = xmlNodeGetContent((xmlNode *)nd);
  if (v) {
    aq_copy_trim(out, cap, (const char *)v, strlen((const char *)v));
    xmlFree(v);
  }
}

static double number(const xmlNode *nd)
{
  char t[64];
  double v;
  text(nd, t, sizeof t);
  return aq_field_double(t, strlen(t), &v) ? v : NAN;
}

void aq_response_free(aq_response *resp)
{
  if (!resp)
    return;
  free(resp->epoch);
  resp->epoch = NULL;
  resp->n = 0;
}

static aq_status add_epoch(aq_response *r, const xmlNode *net, const xmlNode *sta,
                           const xmlNode *cha, const char *name, aq_error *err)
{
  if (r->n >= SXML_MAX_EPOCHS)
    return aq_error_set(err, AQ_EFORMAT, name, (long)cha->line, -1, "Channel",
                        "expected at most %d channel epochs", SXML_MAX_EPOCHS);
  aq_response_epoch *e = realloc(r->epoch, (r->n + 1) * sizeof *e);
  if (!e)
    return aq_error_set(err, AQ_ENOMEM, name, (long)cha->line, -1, "Channel", "out of memory");
  r->epoch = e;
  e += r->n++;
  memset(e, 0, sizeof *e);
  attr(net, "code", e->network, sizeof e->network);
  attr(sta, "code", e->station, sizeof e->station);
  attr(cha, "code", e->channel, sizeof e->channel);
  attr(cha, "locationCode", e->location, sizeof e->location);
  if (strcmp(e->location, "--") == 0)
    e->location[0] = '\0';
  attr(cha, "startDate", e->start, sizeof e->start);
  attr(cha, "endDate", e->end, sizeof e->end);
  e->azimuth_deg = number(child(cha, "Azimuth"));
  e->dip_deg = number(child(cha, "Dip"));
  const xmlNode *sens = child(child(cha, "Response"), "InstrumentSensitivity");
  e->sensitivity = number(child(sens, "Value"));
  text(child(child(sens, "InputUnits"), "Name"), e->input_units, sizeof e->input_units);
  return AQ_OK;
}

aq_status aq_stationxml_parse(const unsigned char *buf, size_t n, const char *name,
                              aq_response *resp, aq_error *err)
{
  memset(resp, 0, sizeof *resp);
  if (n > INT_MAX)
    return aq_error_set(err, AQ_EFORMAT, name, -1, -1, NULL, "file too large for StationXML");
  xmlDoc *doc = xmlReadMemory((const char *)buf, (int)n, name, NULL,
                              XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  if (!doc) {
    const xmlError *xe = xmlGetLastError();
    char msg[160];
    aq_copy_trim(msg, sizeof msg, xe && xe->message ? xe->message : "not well-formed",
                 xe && xe->message ? strlen(xe->message) : 15);
    return aq_error_set(err, AQ_EFORMAT, name, xe ? xe->line : -1, -1, "XML",
                        "expected well-formed XML, got: %s", msg);
  }
  const xmlNode *root = xmlDocGetRootElement(doc);
  aq_status s = AQ_OK;
  if (!root || !is(root, "FDSNStationXML")) {
    s = aq_error_set(err, AQ_EFORMAT, name, root ? (long)root->line : -1, -1, "root element",
                     "expected FDSNStationXML, got %s",
                     root ? (const char *)root->name : "none");
  }
  for (const xmlNode *net = root ? root->children : NULL; net && s == AQ_OK; net = net->next)
    if (is(net, "Network"))
      for (const xmlNode *sta = net->children; sta && s == AQ_OK; sta = sta->next)
        if (is(sta, "Station"))
          for (const xmlNode *cha = sta->children; cha && s == AQ_OK; cha = cha->next)
            if (is(cha, "Channel"))
              s = add_epoch(resp, net, sta, cha, name, err);
  xmlFreeDoc(doc);
  if (s == AQ_OK && resp->n == 0)
    s = aq_error_set(err, AQ_EFORMAT, name, -1, -1, "Channel",
                     "expected at least one Network/Station/Channel, got none");
  if (s != AQ_OK)
    aq_response_free(resp);
  return s;
}

/* m/s^2 per input unit of a StationXML acceleration unit name; 0 if the
 * name is not acceleration. */
static double input_units_to_mps2(const char *u)
{
  char t[24];
  size_t k = 0;
  for (const char *p = u; *p && k + 1 < sizeof t; p++)
    if (*p != ' ')
      t[k++] = (char)((*p >= 'a' && *p <= 'z') ? *p - 32 : *p);
  t[k] = '\0';
  static const struct {
    const char *name;
    double mps2;
  } known[] = {{"M/S**2", 1.0},   {"M/S^2", 1.0},    {"M/S2", 1.0},     {"M/S/S", 1.0},
               {"NM/S**2", 1e-9}, {"NM/S^2", 1e-9},  {"NM/S2", 1e-9},   {"NM/S/S", 1e-9},
               {"MM/S**2", 1e-3}, {"MM/S^2", 1e-3},  {"MM/S2", 1e-3},   {"CM/S**2", 1e-2},
               {"CM/S^2", 1e-2},  {"CM/S2", 1e-2},   {"GAL", 1e-2},     {"G", AQ_G0_MPS2}};
  for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
    if (strcmp(t, known[i].name) == 0)
      return known[i].mps2;
  return 0;
}

static int covers(const aq_response_epoch *e, double t_s)
{
  double a, b;
  if (!aq_iso_parse(e->start, &a) || t_s < a)
    return 0;
  return !e->end[0] || !aq_iso_parse(e->end, &b) || t_s < b;
}

aq_status aq_stationxml_apply(const aq_response *resp, const char *xml_name,
                              aq_raw_file *raw, const char *name, aq_error *err)
{
  for (size_t i = 0; i < raw->nchan; i++) {
    aq_raw_channel *ch = &raw->chan[i];
    char id[80], field[112];
    snprintf(id, sizeof id, "%s.%s.%s.%s", ch->network, ch->station, ch->location,
             ch->channel);
    snprintf(field, sizeof field, "channel %s", id);
    double t0;
    if (!aq_iso_parse(ch->reference, &t0))
      return aq_error_set(err, AQ_EUNITS, name, -1, -1, field,
                          "the record states no start time to choose a response epoch");
    t0 += ch->begin_s;
    const aq_response_epoch *hit = NULL;
    size_t nsame = 0;
    char spans[256] = "";
    for (size_t k = 0; k < resp->n; k++) {
      const aq_response_epoch *e = &resp->epoch[k];
      if (strcmp(e->network, ch->network) || strcmp(e->station, ch->station) ||
          strcmp(e->location, ch->location) || strcmp(e->channel, ch->channel))
        continue;
      if (nsame++ < 3) {
        size_t l = strlen(spans);
        snprintf(spans + l, sizeof spans - l, "%s%s to %s", l ? ", " : "", e->start,
                 e->end[0] ? e->end : "open");
      }
      if (!hit && covers(e, t0))
        hit = e;
    }
    if (nsame == 0)
      return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, field,
                          "expected a Channel for %s (record %s), got none in this StationXML",
                          id, name);
    if (!hit)
      return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, field,
                          "expected an epoch covering the record start %s, got %s", ch->reference,
                          spans);
    double per_unit = input_units_to_mps2(hit->input_units);
    if (per_unit == 0)
      return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, "InstrumentSensitivity InputUnits",
                          "%s: expected acceleration (M/S**2, NM/S**2, G), got \"%s\"", id,
                          hit->input_units);
    if (!isfinite(hit->sensitivity) || hit->sensitivity == 0)
      return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, "InstrumentSensitivity Value",
                          "%s: expected a non-zero number, got %g", id, hit->sensitivity);
    ch->counts_per_mps2 = hit->sensitivity / per_unit; /* counts/(unit) / (m/s^2 per unit) */
    if (isfinite(hit->azimuth_deg))
      ch->azimuth_deg = hit->azimuth_deg;
    if (isfinite(hit->dip_deg)) {
      ch->dip_deg = hit->dip_deg;
      ch->vertical = fabs(fabs(hit->dip_deg) - 90.0) < SXML_DIP_TOL_DEG ? 1
                     : fabs(hit->dip_deg) < SXML_DIP_TOL_DEG ? 0
                                                             : -1;
    }
  }
  return AQ_OK;
}
