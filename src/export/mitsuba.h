/* mitsuba.h: export a scene as a Mitsuba 3 XML scene, so that Mitsuba can render a second
 * independent reference (microfacet materials, caustics, emitting meshes, environment maps: what
 * POV-Ray cannot check) and be measured against (make crosscheck, make bench). The mapping of every
 * quantity, and what is refused, is listed in mcrt(1), `mcrt mitsuba`. */
#ifndef MCRT_MITSUBA_H
#define MCRT_MITSUBA_H

#include "core/diag.h"
#include "scene/scene.h"

/* Check s, then write it as Mitsuba 3 XML to path, its triangles as Wavefront OBJ files beside it
 * (PATH without a .xml suffix, then "-mesh0.obj", "-mesh1.obj", ..., named in the XML relative to
 * its folder). Each file is written to a temporary name and renamed when complete; a refused scene
 * writes nothing, and a failed export removes the meshes it wrote. */
mcrt_status mc_mitsuba_save(const struct scene *s, const char *path, mc_diag *d);

#endif
