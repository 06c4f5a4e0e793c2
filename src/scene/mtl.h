/* mtl.h: Wavefront MTL material libraries (the files an OBJ's mtllib names), read into mcrt's
 * materials. The mapping, for users in man/mcrt.5 ("OBJ materials"):
 *   illum 4, 6, 7 or 9, or d < 1 (Tr > 0)   glass of index Ni (1.5), tint Tf (1), smooth
 *   else Pm > 0.5 (the PBR extension)        metal of reflectance Kd
 *   else Ks > 0 and illum not 0 or 1, or Pr  Kd black: metal of reflectance Ks; else plastic of
 *                                            albedo Kd, coat index Ni when above 1 (else 1.5)
 *   else                                     diffuse of albedo Kd
 * metal and plastic of GGX α = Pr² when Pr is given, else from Ns (mtl.c), times map_Pr's
 * value squared (a roughness texture).
 * and Ke is the emitted radiance; map_Kd is an image texture multiplying Kd (of diffuse and
 * plastic materials), map_Pr one giving the roughness (of metal and plastic). Kd, Ks and Ke are 0 when absent (as tinyobjloader reads them), so a
 * material of Ke alone is a black emitter, but Kd is 1 beside a map_Kd, whose image is then the
 * colour. */
#ifndef MCRT_MTL_H
#define MCRT_MTL_H

#include <stddef.h>

#include "bsdf/material.h"
#include "core/diag.h"

struct scene;

/* The statements of MTL, one line each: X(name, how). how is READ (it sets the material), QUIET
 * (ignored: it means nothing to a path tracer) or WARN (ignored, and the first in each file is
 * reported as a warning with the reason mtl.c gives). Any other statement is an error. */
#define MC_MTL_STATEMENTS(X)                                                                    \
    X(newmtl, READ) X(Kd, READ) X(Ks, READ) X(Ke, READ) X(Ns, READ) X(Ni, READ) X(d, READ)      \
    X(Tr, READ) X(Tf, READ) X(illum, READ) X(map_Kd, READ) X(Pr, READ) X(Pm, READ)              \
    X(map_Pr, READ)                                                                             \
    X(Ka, QUIET) X(map_Ka, QUIET)                                                               \
    X(map_Ks, WARN) X(map_Ns, WARN) X(map_d, WARN) X(map_Ke, WARN)              \
    X(map_bump, WARN) X(bump, WARN) X(disp, WARN) X(decal, WARN) X(norm, WARN) X(refl, WARN)    \
    X(sharpness, WARN) X(map_aat, WARN) X(Ps, WARN) X(Pc, WARN) X(Pcr, WARN)                  \
    X(aniso, WARN) X(anisor, WARN) X(map_Pm, WARN) X(map_Ps, WARN)

#define MC_MTL_ENUM(name, how) MTL_##name,
enum mtl_statement { MC_MTL_STATEMENTS(MC_MTL_ENUM) MTL_STATEMENT_COUNT };
#undef MC_MTL_ENUM
/* Their keywords, NULL at [MTL_STATEMENT_COUNT] (for the manual's check, tests/tools/words). */
extern const char *const mc_mtl_statement_names[MTL_STATEMENT_COUNT + 1];

enum { MTL_MAP_KD, MTL_MAP_PR };

/* One material of a library. */
struct mtl_entry {
    char name[64];             /* as newmtl gives it */
    size_t file;               /* the library file that defines it: mtl_library.paths[file] */
    int line, col;             /* of its name after newmtl */
    struct material m;         /* named "FILE:NAME", which no scene word can name */
    vec3 emit;                 /* Ke */
    struct mtl_map {
        char *path;            /* the image file (beside the MTL file) or NULL (owned) */
        char *origin;          /* "FILE:LINE:COL" of its name, for the image's messages (owned) */
    } maps[2];                 /* map_Kd's (MTL_MAP_KD) and map_Pr's (MTL_MAP_PR) */
    int scene_index;           /* the scene's material, -1 until a face uses it (obj.c) */
};

/* The materials of every library an OBJ file has named so far. */
struct mtl_library {
    struct mtl_entry *e;
    size_t n, cap;
    char **paths;              /* the files read, as opened */
    size_t npaths;
};

/* Read the MTL file at path into lib. Messages: "path:line:col: what" for malformed contents,
 * including a material defined twice in the files read (MCRT_ERR_PARSE), "origin: cannot
 * open/read 'path': reason" (MCRT_ERR_IO), MCRT_ERR_NOMEM. Warnings about ignored statements go
 * to warn (mc_scene_warn). On failure lib keeps what it held and what was read, for
 * mc_mtl_free. A map's image is only named (maps): mc_mtl_use makes it a texture. */
mcrt_status mc_mtl_load(struct mtl_library *lib, const char *path, const char *origin,
                        struct scene *warn, mc_diag *d);
/* The scene's material for entry i of lib, added to s (with its maps' textures) the first time:
 * its index, or -1 when out of memory. */
int mc_mtl_use(struct mtl_library *lib, size_t i, struct scene *s);
/* The entry named [name, name + len), or -1. */
int mc_mtl_find(const struct mtl_library *lib, const char *name, size_t len);
void mc_mtl_free(struct mtl_library *lib);

#endif
