/* evidence.h: what a channel's fields say beyond its values, gathered and
 * named for the one decision in record.c (evidence.c).  Nothing here
 * decides units, plausibility or verticality; nothing prints. */
#ifndef AQ_IO_EVIDENCE_H
#define AQ_IO_EVIDENCE_H

#include <stddef.h>

#include "../error.h"
#include "reader.h"
#include "units.h"

/* Give each channel of raw (a parsed miniSEED file reported as name) the
 * one response of the StationXML files xml[0..nx) whose network, station,
 * location and channel match it and whose epoch holds its start
 * (aq_response_apply: sensitivity, units, azimuth, dip).  Each file is read
 * and parsed only when it mentions the channel's station.  AQ_OK, or
 * AQ_EUNITS when none matches (naming every file searched) or two match
 * (naming both), AQ_EIO for an unreadable file, AQ_ENOMEM; raw is left for
 * the caller to free either way. */
aq_status aq_evidence_responses(const char *const *xml, size_t nx, const char *name,
                                aq_raw_file *raw, aq_error *err);

/* Does anything about channel ch of the file at path contradict ground
 * acceleration?  Its stated quantity (ch->quantity: velocity or
 * displacement), units of velocity or displacement, the file name's words
 * (vel, veloc, disp, displ, VT2, DT2, ...), the same words in the channel's
 * name (a text column "velocity"), or a SEED instrument code of a sensor
 * that does not record acceleration (H, L, P, M); the last two not when
 * the file states acceleration itself.  Returns AQ_QUANTITY_VELOCITY or
 * AQ_QUANTITY_DISPLACEMENT with the evidence in ev (cap bytes, e.g.
 * "header IDEP: IVEL (7, velocity)") and *what the quantity's name for a
 * message ("velocity", "a mass position"); AQ_QUANTITY_UNSTATED (ev "")
 * when nothing contradicts it. */
aq_quantity aq_evidence_quantity(const aq_raw_channel *ch, const char *path, char *ev,
                                 size_t cap, const char **what);

/* Does a channel name say vertical?  Its words (split at anything not a
 * letter or digit, trailing digits dropped: KiK-net "UD2") UD, UP, U, Z, V,
 * VERT, VERTICAL, DOWN, DWN, DU, or a SEED code of three letters ending in
 * Z.  1 or 0. */
int aq_evidence_says_vertical(const char *name);

#endif
