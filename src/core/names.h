/* names.h: the closed sets of names (samplers, filters, image layers, shapes, light kinds), each
 * a NULL-terminated array indexed by the set's enum and built from the set's one X-macro table,
 * looked up and listed the same way by the parser, the API's checks and their messages. */
#ifndef MCRT_NAMES_H
#define MCRT_NAMES_H

#include <stddef.h>

/* The three uses of a table MC_SETS(X) of lines X(KIND, NAME):
 *     enum set_kind { MC_SETS(MC_NAMES_ENUM) };            the enumerators
 *     #define SET_COUNT (0 MC_SETS(MC_NAMES_COUNT))         their number
 *     names[SET_COUNT + 1] = {MC_SETS(MC_NAMES_ENTRY) [SET_COUNT] = NULL}   the names by kind
 * (NAME a string literal; MC_NAMES_IDENT when it is an identifier, made a string). */
#define MC_NAMES_ENUM(kind, name) kind,
#define MC_NAMES_COUNT(kind, name) +1
#define MC_NAMES_ENTRY(kind, name) [kind] = name,
/* The same for tables whose NAME is an identifier (the shapes, the kinds of light). */
#define MC_NAMES_IDENT(kind, name) [kind] = #name,

/* Index of name[0..len) in the NULL-terminated names, or -1. */
int mc_names_find(const char *const *names, const char *name, size_t len);
/* names joined as "a, b or c" into buf (cut short when it does not fit); `last` is the word
 * before the final name (" or ", ", "). Returns buf. */
const char *mc_names_join(const char *const *names, const char *last, char *buf, size_t size);

#endif
