/* export.h: what the scene exporters (pov.c, mitsuba.c) share: the questions both ask of a scene,
 * a fixed order of its primitives, and the refusal message. Each writes its file through
 * core/file.h's mc_output, so that a refused or failed export leaves no file. */
#ifndef MCRT_EXPORT_H
#define MCRT_EXPORT_H

#include "core/diag.h"
#include "scene/scene.h"

/* Whether the camera or any primitive moves. */
int mc_export_moves(const struct scene *s);

static inline int mc_export_is_emitter(const struct prim *p) { return !v3_is_zero(p->emit); }

/* The scene's primitives in a fixed order (a new array of s->prim_count pointers, to free; NULL
 * when out of memory): by kind (triangles, spheres, quads, disks), material, flags, motion,
 * normals, then the bytes of the geometry and the emission. Any fixed order would do; what
 * matters is that it is not the order scene preparation leaves the primitives in (static before
 * moving): an exported file must not change when only the preparation does (the POV-Ray
 * references are compared with theirs byte for byte). */
const struct prim **mc_export_sorted_prims(const struct scene *s);

/* MCRT_ERR_UNSUPPORTED with "NAME:LINE:COL: cannot export WHAT to TARGET: WHY", at the place the
 * scene text first uses construct `mark` (enum scene_mark), or "NAME: ..." when mark < 0 or the
 * text does not hold it. */
mcrt_status mc_export_refuse(mc_diag *d, const struct scene *s, int mark, const char *target,
                             const char *what, const char *why);

#endif
