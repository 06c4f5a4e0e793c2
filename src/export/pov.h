/* pov.h: export a scene as POV-Ray 3.7 SDL under the physical mapping measured in
 * shared/research/povray-mapping.md, so that POV-Ray can render an independent reference. */
#ifndef MCRT_POV_H
#define MCRT_POV_H

#include "core/diag.h"
#include "scene/scene.h"

/* Emitter grids: N×N sub-lights per area light (mapping note: N = 16 keeps the grid bias of a
 * Lambertian quad under 0.1%). */
#define MC_POV_GRID 16
/* Frames averaged for motion blur: the clock-sampling error is about 1/K of the moving edge's
 * contrast at most, 0.4/K on average (mapping note, motion-blur row). */
#define MC_POV_FRAMES 64

/* Check s, then write it as SDL to path (to path.tmp-PID first, renamed over path when complete,
 * so that a refused or failed export leaves no file and never a half-written one). The second line
 * of the file is a comment "// povray FLAGS" with the pinned command-line flags of the reference
 * render (image size, box-filter antialiasing, and the clock frames for motion blur). */
mcrt_status mc_pov_save(const struct scene *s, const char *path, mc_diag *d);

#endif
