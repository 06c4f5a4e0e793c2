/* obj.h: Wavefront OBJ triangle meshes loaded into the scene as triangle primitives.
 * Reads v, vn, vt and f (forms v, v/vt, v//vn, v/vt/vn; negative indices count back from the latest
 * element; polygons become triangle fans), mtllib and usemtl (mtl.h) when the mesh takes its
 * materials from them, and ignores every other statement. */
#ifndef MCRT_OBJ_H
#define MCRT_OBJ_H

#include <stddef.h>

#include "scene/scene.h"

/* The largest OBJ file read, in bytes (1 GiB). */
#define MC_OBJ_MAX_BYTES ((size_t)1 << 30)

/* One mesh to load. */
struct obj_mesh {
    const char *path;   /* file to open; also the name in messages about its contents */
    const char *origin; /* "scene.mcrt:4:8": where the scene asks for it, for messages about the
                         * file as a whole (cannot open, too large, no faces) */
    float xform[12];    /* object to world, row-major 3x4 affine map: x' = m[0]x + m[1]y + m[2]z + m[3] */
    struct prim proto;  /* material, flags and emit copied to every triangle */
    int mtl;            /* nonzero: mtllib and usemtl give the faces after a usemtl its material
                         * (else they are ignored, and every face takes proto's) */
    int mtl_emit;       /* nonzero (with mtl): and its Ke as their emit */
};

/* What a load produced. */
struct obj_stats {
    size_t triangles;   /* added to the scene */
    size_t degenerate;  /* dropped: zero area after the transform (see mc_edges_degenerate) */
};

/* Append the mesh's triangles to s. Vertices are mapped by xform; shading normals (used on a face
 * when all its vertices have a vn of nonzero length) by its inverse transpose, renormalised. When
 * xform mirrors (negative determinant) each triangle's winding is reversed so that its front side
 * stays on the side the file's winding and normals meant. Texture coordinates (vt u [v [w]], v
 * 0 when absent) are used on a face when all its corners have one; they are not transformed.
 * Messages are "path:line:col: what" for malformed contents (MCRT_ERR_PARSE), "origin: cannot
 * open/read 'path': reason" (MCRT_ERR_IO), "origin: 'path' has no faces" (MCRT_ERR_PARSE) and
 * MCRT_ERR_NOMEM. On failure the triangles
 * already added stay in s (mc_scene_free releases them). stats may be NULL. */
mcrt_status mc_obj_load(struct scene *s, const struct obj_mesh *m, struct obj_stats *stats,
                        mc_diag *d);

#endif
