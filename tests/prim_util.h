/* prim_util.h: building primitives by hand in tests (not lights, no shading normals). */
#ifndef MCRT_PRIM_UTIL_H
#define MCRT_PRIM_UTIL_H

#include <string.h>

#include "geom/prim.h"

/* A primitive of the given kind with p[0..2] = a, b, c (see geom/prim.h for their meaning). */
static inline struct prim test_prim(int kind, vec3 a, vec3 b, vec3 c)
{
    struct prim p;
    memset(&p, 0, sizeof p);
    p.kind = (uint8_t)kind;
    p.light = -1;
    p.normals = -1;
    p.p[0] = a;
    p.p[1] = b;
    p.p[2] = c;
    return p;
}

#endif
