/* stationxml.c: the instrument sensitivity, azimuth and dip of each channel
 * epoch of an FDSN StationXML file, through libxml2 (reader.h).
 *
 * Read: Network@code / Station@code / Channel@code, @locationCode,
 * @startDate, @endDate, with Azimuth, Dip and Response/InstrumentSensitivity
 * (Value, InputUnits/Name).  Elements are matched by local name, so the
 * namespace version does not matter.  The sensitivity is counts per input
 * unit; aq_response_apply() turns it into counts per m/s^2, keeping its
 * sign (a negative sensitivity means the sensor's polarity is reversed);
 * evidence.c finds the epoch of each channel (aq_response_find) across every
 * StationXML given.  libxml2 never prints here
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

/* What a StationXML input unit name measures, and m/s^2 per unit for
 * acceleration (0 otherwise): *q AQ_QUANTITY_UNSTATED if unknown. */
static double input_units(const char *u, aq_quantity *q)
{
  char t[24];
  size_t k = 0;
  for (const char *p = u; *p && k + 1 < sizeof t; p++)
    if (*p != ' ')
      t[k++] = (char)((*p >= 'a' && *p <= 'z') ? *p - 32 : *p);
  t[k] = '\0';
  static const struct {
    const char *name;
    double mps2; /* 0: not acceleration */
    aq_quantity q;
  } known[] = {
      {"M/S**2", 1.0, AQ_QUANTITY_ACCELERATION},   {"M/S^2", 1.0, AQ_QUANTITY_ACCELERATION},
      {"M/S2", 1.0, AQ_QUANTITY_ACCELERATION},     {"M/S/S", 1.0, AQ_QUANTITY_ACCELERATION},
      {"NM/S**2", 1e-9, AQ_QUANTITY_ACCELERATION}, {"NM/S^2", 1e-9, AQ_QUANTITY_ACCELERATION},
      {"NM/S2", 1e-9, AQ_QUANTITY_ACCELERATION},   {"NM/S/S", 1e-9, AQ_QUANTITY_ACCELERATION},
      {"MM/S**2", 1e-3, AQ_QUANTITY_ACCELERATION}, {"MM/S^2", 1e-3, AQ_QUANTITY_ACCELERATION},
      {"MM/S2", 1e-3, AQ_QUANTITY_ACCELERATION},   {"CM/S**2", 1e-2, AQ_QUANTITY_ACCELERATION},
      {"CM/S^2", 1e-2, AQ_QUANTITY_ACCELERATION},  {"CM/S2", 1e-2, AQ_QUANTITY_ACCELERATION},
      {"GAL", 1e-2, AQ_QUANTITY_ACCELERATION},     {"G", AQ_G0_MPS2, AQ_QUANTITY_ACCELERATION},
      {"M/S", 0, AQ_QUANTITY_VELOCITY},            {"NM/S", 0, AQ_QUANTITY_VELOCITY},
      {"MM/S", 0, AQ_QUANTITY_VELOCITY},           {"CM/S", 0, AQ_QUANTITY_VELOCITY},
      {"M", 0, AQ_QUANTITY_DISPLACEMENT},          {"NM", 0, AQ_QUANTITY_DISPLACEMENT},
      {"MM", 0, AQ_QUANTITY_DISPLACEMENT},         {"CM", 0, AQ_QUANTITY_DISPLACEMENT}};
  for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
    if (strcmp(t, known[i].name) == 0) {
      *q = known[i].q;
      return known[i].mps2;
    }
  *q = AQ_QUANTITY_UNSTATED;
  return 0;
}

static int covers(const aq_response_epoch *e, double t_s)
{
  double a, b;
  if (!aq_iso_parse(e->start, &a) || t_s < a)
    return 0;
  return !e->end[0] || !aq_iso_parse(e->end, &b) || t_s < b;
}

size_t aq_response_find(const aq_response *resp, const char *net, const char *sta,
                        const char *loc, const char *cha, double t_s,
                        const aq_response_epoch **hit, size_t *nsame, char *spans, size_t cap)
{
  size_t nhit = 0, same = 0;
  *hit = NULL;
  for (size_t k = 0; k < resp->n; k++) {
    const aq_response_epoch *e = &resp->epoch[k];
    if (strcmp(e->network, net) || strcmp(e->station, sta) || strcmp(e->location, loc) ||
        strcmp(e->channel, cha))
      continue;
    if (same++ < 3 && spans && cap) {
      size_t l = strlen(spans);
      snprintf(spans + l, cap - l, "%s%s to %s", l ? ", " : "", e->start,
               e->end[0] ? e->end : "open");
    }
    if (covers(e, t_s) && nhit++ == 0)
      *hit = e;
  }
  if (nsame)
    *nsame += same;
  return nhit;
}

aq_status aq_response_apply(const aq_response_epoch *e, const char *xml_name, aq_raw_channel *ch,
                            aq_error *err)
{
  char id[80];
  snprintf(id, sizeof id, "%s.%s.%s.%s", e->network, e->station, e->location, e->channel);
  aq_quantity q;
  double per_unit = input_units(e->input_units, &q);
  const char *slash = strrchr(xml_name, '/');
  const char *base = slash ? slash + 1 : xml_name; /* for the short fields */
  if (q == AQ_QUANTITY_UNSTATED)
    return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, "InstrumentSensitivity InputUnits",
                        "%s: expected acceleration (M/S**2, NM/S**2, G), got \"%s\"", id,
                        e->input_units);
  ch->quantity = q;
  aq_text_fit(ch->quantity_said, sizeof ch->quantity_said, "%s: InputUnits %.20s", base,
              e->input_units);
  if (q == AQ_QUANTITY_ACCELERATION) {
    if (!isfinite(e->sensitivity) || e->sensitivity == 0)
      return aq_error_set(err, AQ_EUNITS, xml_name, -1, -1, "InstrumentSensitivity Value",
                          "%s: expected a non-zero number, got %g", id, e->sensitivity);
    ch->counts_per_mps2 = e->sensitivity / per_unit; /* counts/(unit) / (m/s^2 per unit) */
    aq_text_fit(ch->units_from, sizeof ch->units_from, "%s: InstrumentSensitivity", base);
  }
  if (isfinite(e->azimuth_deg))
    ch->azimuth_deg = e->azimuth_deg;
  if (isfinite(e->dip_deg)) {
    ch->dip_deg = e->dip_deg;
    ch->vertical = fabs(fabs(e->dip_deg) - 90.0) < SXML_DIP_TOL_DEG ? 1
                   : fabs(e->dip_deg) < SXML_DIP_TOL_DEG             ? 0
                                                                      : -1;
    aq_text_fit(ch->orient_said, sizeof ch->orient_said, "%s: Dip %g", base, e->dip_deg);
  }
  return AQ_OK;
}
