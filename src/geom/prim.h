/* prim.h: the geometric primitives (the shapes of MC_SHAPES: sphere, quad, disk, triangle) that
 * live together in one BVH. A primitive is a plain 64-byte value; the BVH's leaves refer to the
 * scene's primitive array by index. */
#ifndef MCRT_PRIM_H
#define MCRT_PRIM_H

#include <stdint.h>

#include "core/names.h"
#include "geom/ray.h"

/* The shapes, X(KIND, name), in the order the scene language lists them: each is the file
 * src/geom/NAME.c, which defines the functions of geom/shape_impl.h and the descriptor below.
 * Adding a shape is that file and a line here (and, to export it, one in export/pov.c). */
#define MC_SHAPES(X)                                                                           \
    X(PRIM_SPHERE, sphere) X(PRIM_QUAD, quad) X(PRIM_DISK, disk) X(PRIM_TRIANGLE, triangle)
enum prim_kind { MC_SHAPES(MC_NAMES_ENUM) };
#define PRIM_KIND_COUNT (0 MC_SHAPES(MC_NAMES_COUNT))

enum prim_flags {
    PRIM_TWO_SIDED = 1, /* emits from both sides */
    PRIM_FLIP = 2       /* front and back swapped: the normal points the other way */
};

struct prim {
    uint8_t kind;     /* enum prim_kind */
    uint8_t flags;    /* enum prim_flags */
    uint16_t motion;  /* 0: static; k: moves by scene->motions[k - 1] (p[] hold its place at time 0) */
    int32_t material; /* index into scene->materials */
    int32_t light;    /* index into scene->lights when emitting, else -1 (set by scene prepare) */
    int32_t normals;  /* mesh triangle: index k of its corners' attributes, or -1: the shading
                       * normals scene->normals[k..k+2] (zero: flat) and, when the scene has
                       * texture coordinates at all, scene->uvs[k..k+2] */
    /* The shape's parameters, as its file src/geom/NAME.c lays them out:
     * triangle: the vertices p[0..2]; front side along (p1-p0)×(p2-p0).
     * sphere:   p[0] the centre, p[1].x the radius; front side outward.
     * quad:     p[0] the corner, p[1] edge1, p[2] edge2; front side along edge1×edge2.
     * disk:     p[0] the centre, p[1] the unit normal (the front side), p[2].x the radius. */
    vec3 p[3];
    vec3 emit;        /* emitted radiance (Lambertian), zero when not an emitter */
};

/* A parameter of a shape's or a light's block in the scene language, `NAME { KEY value ... }`
 * (man/mcrt.5), which the parser reads into a vec3. */
enum param_kind {
    PARAM_POINT,     /* three numbers: a point or a vector */
    PARAM_DIRECTION, /* three numbers, normalised (in double); zero length is an error */
    PARAM_LENGTH,    /* one positive number, in .x */
    PARAM_RGB,       /* one number (grey) or three, none negative */
    PARAM_IMAGE,     /* a quoted image file name: the parser has the scene load it and gives 1 +
                      * the scene's image index in .x (0 when not given) */
    PARAM_SPIN       /* four numbers, an axis and an angle in degrees: given as the unit axis
                      * times the angle (zero when not given) */
};
struct block_param {
    const char *name;
    enum param_kind kind;
    vec3 def;                    /* the value when the key is not given */
};
#define MC_BLOCK_PARAMS 4
/* What a shape is made from, besides the keys every shape takes (material, emit, two_sided, flip,
 * move). */
struct shape {
    const struct block_param *params; /* at most MC_BLOCK_PARAMS */
    int nparams;
    /* Fill p->p[] from the parameters' values v[] (defaults applied). Returns NULL, or what is
     * wrong with them, setting bit i of *blame for each parameter i it concerns. */
    const char *(*build)(struct prim *p, const vec3 *v, unsigned *blame);
};
/* The descriptors, and the names (the scene language's blocks, the shapes in messages), indexed
 * by enum prim_kind; the names end in NULL (core/names.h). */
extern const struct shape *const mc_shapes[PRIM_KIND_COUNT];
extern const char *const mc_shape_names[PRIM_KIND_COUNT + 1];

/* What the BVH reports: distance, primitive index and the primitive's own 2D parameters
 * (triangle: barycentrics of p1 and p2; quad: s, t along edge1, edge2; sphere, disk: unused). */
struct hit {
    float t;
    uint32_t prim;
    float u, v;
};

/* The geometry at a hit, ready for shading. */
struct surface {
    vec3 p;     /* position, computed from the primitive's parameters (not o + t·d) */
    vec3 ng;    /* unit geometric normal on the primitive's front side (flip applied) */
    vec3 ns;    /* unit shading normal on the same side as ng (interpolated for meshes) */
    int front;  /* 1 when the ray arrived on the front side (dot(d, ng) < 0) */
    float err;  /* bound on how far p may lie off the surface as the intersection tests see it
                 * (mc_prim_point_error); a spawned ray must start beyond it */
};

/* Intersection in (0, h->t): on a hit, update h (t, u, v; not prim) and return 1.
 * Triangles use the watertight test of Woop, Benthin and Wald, JCGT 2(1) 2013. */
int mc_prim_intersect(const struct prim *p, const struct ray *r, struct hit *h);

/* A ray with the per-ray constants of the watertight triangle test (Woop et al. 2013, §3: the
 * axis permutation that makes z the dominant direction axis, and the shear that maps the ray onto
 * +z), so that a traversal computes them once per ray rather than once per triangle. */
struct ray_prep {
    struct ray r;
    int kx, ky, kz;
    float sx, sy, sz;
};
/* Fill q for r. Inline: it runs once per traced ray, inside the traversal's own set-up. */
static inline void mc_ray_prep(struct ray_prep *q, const struct ray *r)
{
    const float d[3] = {r->d.x, r->d.y, r->d.z};
    float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
    int kx, ky, kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    /* Swapping x and y for a negative dominant component keeps the winding (Woop et al. §3); the
     * test accepts both windings anyway, but this keeps the edge-function signs meaningful. */
    if (d[kz] < 0.0f) {
        int s = kx;
        kx = ky;
        ky = s;
    }
    q->r = *r;
    q->kx = kx;
    q->ky = ky;
    q->kz = kz;
    q->sx = -d[kx] / d[kz];
    q->sy = -d[ky] / d[kz];
    q->sz = 1.0f / d[kz];
}
/* Bound on the rounding error of the watertight test's distance t = ts / det (Pharr, Jakob and
 * Humphreys, "Physically Based Rendering", 4th ed., §6.8.7; pbrt-v4's Triangle::Intersect), from
 * the largest magnitudes of the translated and sheared vertices' x, y and scaled z and of the edge
 * functions. A hit counts only when t exceeds it: a ray that starts in a triangle's plane (one
 * spawned at a concave corner lies in the other face's plane) meets it at t = 0, which rounding
 * turns into a tiny t of either sign. The 4-wide test in bvh.c repeats these operations in the
 * same order, so that both decide alike. */
#define MC_GAMMA(n) ((n) * 0x1p-24f / (1 - (n) * 0x1p-24f)) /* γn of float rounding (PBR 6.8.1) */
static inline float mc_tri_t_error(float max_x, float max_y, float max_z, float max_e, float det)
{
    float dz = MC_GAMMA(3) * max_z, dx = MC_GAMMA(5) * (max_x + max_z);
    float dy = MC_GAMMA(5) * (max_y + max_z);
    float de = 2.0f * (MC_GAMMA(2) * max_x * max_y + dy * max_x + dx * max_y);
    return 3.0f * (MC_GAMMA(3) * max_e * max_z + de * max_z + dz * max_e) / fabsf(det);
}
/* The largest of |a|, |b|, |c|: mc_tri_t_error's magnitudes. */
static inline float mc_abs_max3(float a, float b, float c)
{
    return f_max(f_max(fabsf(a), fabsf(b)), fabsf(c));
}

/* mc_prim_intersect with the constants precomputed; the results are bitwise the same. */
int mc_prim_intersect_prep(const struct prim *p, const struct ray_prep *q, struct hit *h);
/* The vertices of the triangle whose edge functions the watertight test (triangle.c) evaluates
 * for a triangle (its own) or a quad (corner, corner + edge1, corner + edge2, in float: the quad
 * is the parallelogram they span). */
static inline void mc_prim_corners(const struct prim *p, vec3 v[3])
{
    int quad = p->kind == PRIM_QUAD;
    v[0] = p->p[0];
    v[1] = quad ? v3_add(p->p[0], p->p[1]) : p->p[1];
    v[2] = quad ? v3_add(p->p[0], p->p[2]) : p->p[2];
}
/* Whether the mc_prim_corners of a triangle or quad p are collinear: the cross product of their
 * differences, in double, is exactly zero. mc_prim_intersect never reports a hit on such a one. */
int mc_prim_degenerate(const struct prim *p);

struct aabb mc_prim_bounds(const struct prim *p);
float mc_prim_area(const struct prim *p);
/* Surface at a hit; normals is the scene's shading-normal array (used when p->normals >= 0). */
void mc_prim_surface(const struct prim *p, const vec3 *normals, const struct ray *r,
                     const struct hit *h, struct surface *s);
/* The texture coordinates (u, v) of hit h of ray r (in p's own frame, as for mc_prim_surface),
 * the parametrisation man/mcrt.5 documents (Texture coordinates), the same on both sides and under
 * flip. On demand rather than in struct surface: only textured materials pay for them.
 * sphere:   with d = (p − centre)/radius, u = atan2(d.x, −d.z)/2π + 1/2 (the environment map's
 *           longitude, light/envmap.c: u = 1/2 towards −z, 3/4 towards +x) and v = 1 − θ/π, θ
 *           the angle from +y (v = 1 at the north pole, 0 at the south);
 * quad:     (s, t) along edge1, edge2: corner (0, 0), corner + edge1 (1, 0);
 * disk:     planar, u = 1/2 + w·t/2r, v = 1/2 + w·b/2r, w = p − centre, (t, b) the tangent frame
 *           v3_basis gives the normal (t = +x, b = +y for normal +z; t = +x, b = −z for +y),
 *           the frame of its area samples: the disk is inscribed in the unit square;
 * triangle: the barycentrics of v1 and v2 (v0 (0, 0), v1 (1, 0), v2 (0, 1)), or for a mesh
 *           triangle with texture coordinates (uvs not NULL, p->normals >= 0) those
 *           interpolated by them. */
vec2 mc_prim_uv(const struct prim *p, const vec2 *uvs, const struct ray *r, const struct hit *h);
/* Bound on the distance between a computed point of p (a hit point, an area sample) and p's
 * surface as mc_prim_intersect sees it. Both are computed from p's parameters, whose rounding is
 * relative to their magnitude M (the largest coordinate of a vertex, corner plus edges, or centre
 * plus radius), not to the point's: a point near the origin on a primitive 1e5 wide is off by
 * ulps of 1e5. Returns 32·2^-24·M (16 ulps of M), a few times the γ3..γ5 error of the sums. */
float mc_prim_point_error(const struct prim *p);
/* A point uniform in area on p (pdf 1/area), with its front-side unit geometric normal. */
vec3 mc_prim_sample_area(const struct prim *p, vec2 u, vec3 *n);

/* Whether the parallelogram spanned by e1 and e2 has (numerically) no area: |e1 × e2| is at most
 * 1e-6 |e1| |e2| (a sine below 1e-6, or a zero edge; evaluated in double so that it cannot
 * overflow), or e1 × e2 evaluated in float has zero or NaN length. Shared by the triangle and quad
 * checks of the shapes, the camera check of the parser and the OBJ reader. */
int mc_edges_degenerate(vec3 e1, vec3 e2);

#endif
