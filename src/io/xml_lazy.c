/* xml_lazy.c: libxml2 opened when a StationXML file is first parsed, not
 * when archquake starts (src/util/lazylib.h): linked directly, libxml2 and
 * what it needs (ICU's common and data libraries, libstdc++, liblzma) were
 * mapped and relocated by every command, `archquake --version` included.
 *
 * The libxml2 functions stationxml.c calls are defined here as trampolines
 * through pointers set from the library (prototypes from libxml2's
 * headers, so a mismatch does not compile), and so is the allocator hook
 * xmlFree, a variable in this libxml2 build, as a function calling the
 * library's own.  xmlReadMemory opens the library; when it cannot, it
 * returns NULL and xmlGetLastError gives the loader's reason as the
 * parser's message, which stationxml.c reports as any parse failure, naming
 * the file.  A libxml2 function not listed here fails to link ("undefined
 * reference"): add it to AQ_XML_FUNCS. */
#include <libxml/globals.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <stdlib.h>
#include <string.h>

#include "../util/lazylib.h"
#include "lazylib_sonames.h" /* build/: AQ_XML2_SONAME, from the build's libxml2.so */

/* V(name, parameters, arguments): returns void; R(type, name, ...): type. */
#define AQ_XML_FUNCS(V, R)                                                                \
  R(xmlDocPtr, xmlReadMemory,                                                             \
    (const char *buffer, int size, const char *URL, const char *encoding, int options),   \
    (buffer, size, URL, encoding, options))                                               \
  R(xmlErrorPtr, xmlGetLastError, (void), ())                                             \
  R(xmlNodePtr, xmlDocGetRootElement, (const xmlDoc *doc), (doc))                         \
  R(xmlChar *, xmlGetProp, (const xmlNode *node, const xmlChar *name), (node, name))      \
  R(xmlChar *, xmlNodeGetContent, (const xmlNode *cur), (cur))                            \
  V(xmlFreeDoc, (xmlDocPtr cur), (cur))

AQ_XML_FUNCS(AQ_LAZYLIB_POINTER_V, AQ_LAZYLIB_POINTER_R)
static xmlFreeFunc *p_xmlFree; /* the library's variable */
static const aq_lazylib_sym xml_syms[] = {
    AQ_XML_FUNCS(AQ_LAZYLIB_SYM_V, AQ_LAZYLIB_SYM_R){"xmlFree", &p_xmlFree}};

static aq_lazylib xml = {AQ_XML2_SONAME, "libxml2", xml_syms,
                         sizeof xml_syms / sizeof xml_syms[0], 0, ""};

/* The reason the library could not be opened, as libxml2's last error. */
static _Thread_local xmlError load_error;
static _Thread_local char load_message[sizeof ((aq_error *)0)->message + 32];

xmlDocPtr xmlReadMemory(const char *buffer, int size, const char *URL,
                        const char *encoding, int options)
{
  aq_error e;
  if (aq_lazylib_load(&xml, &e) != AQ_OK) {
    memset(&load_error, 0, sizeof load_error);
    snprintf(load_message, sizeof load_message, "%s (needed for StationXML)", e.message);
    load_error.message = load_message;
    load_error.line = -1;
    return NULL;
  }
  load_error.message = NULL;
  return p_xmlReadMemory(buffer, size, URL, encoding, options);
}

xmlErrorPtr xmlGetLastError(void)
{
  if (load_error.message)
    return &load_error;
  return p_xmlGetLastError ? p_xmlGetLastError() : NULL;
}

/* The others are called only on a document xmlReadMemory made, so after
 * the library was opened: a call before is a bug, and stops the program. */
static void need(int resolved)
{
  if (!resolved)
    abort();
}

/* xmlReadMemory and xmlGetLastError are written out above */
#define AQ_XML_SKIP_R(type, name, params, args)
AQ_XML_FUNCS(AQ_LAZYLIB_TRAMPOLINE_V, AQ_XML_SKIP_R) /* xmlFreeDoc */
AQ_LAZYLIB_TRAMPOLINE_R(xmlNodePtr, xmlDocGetRootElement, (const xmlDoc *doc), (doc))
AQ_LAZYLIB_TRAMPOLINE_R(xmlChar *, xmlGetProp, (const xmlNode *node, const xmlChar *name),
                        (node, name))
AQ_LAZYLIB_TRAMPOLINE_R(xmlChar *, xmlNodeGetContent, (const xmlNode *cur), (cur))

static void free_through_library(void *mem)
{
  need(p_xmlFree != NULL);
  (*p_xmlFree)(mem);
}
xmlFreeFunc xmlFree = free_through_library;
