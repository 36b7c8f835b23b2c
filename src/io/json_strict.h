/* json_strict.h — JSON text parsed as shlab reads every input file
 * (json_strict.c): duplicate keys and numbers outside double's range are
 * errors (jansson alone would read "1e-400" as 0). */
#ifndef SHLAB_JSON_STRICT_H
#define SHLAB_JSON_STRICT_H

#include <jansson.h>
#include <stddef.h>

/* *root, or SH_EFORMAT with one line "NAME: not valid JSON (line L: why)"
 * or "NAME: line L: the number '...' is outside double's range". */
int sh__json_parse(const char *buf, size_t n, const char *name, json_t **root);

#endif
