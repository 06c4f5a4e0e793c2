/* vec.h: 3-vectors for points, directions and linear RGB colours (all static inline).
 * Conventions: right-handed, y up; directions are unit length unless a name says otherwise. */
#ifndef MCRT_VEC_H
#define MCRT_VEC_H

#include <math.h>

#define MC_PI 3.14159265358979323846f
#define MC_INV_PI 0.31830988618379067154f

typedef struct vec3 { float x, y, z; } vec3;
typedef struct vec2 { float x, y; } vec2;

static inline vec2 v2(float x, float y) { vec2 r; r.x = x; r.y = y; return r; }

static inline vec3 v3(float x, float y, float z) { vec3 r; r.x = x; r.y = y; r.z = z; return r; }
static inline vec3 v3s(float s) { return v3(s, s, s); }
static inline vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline vec3 v3_mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline vec3 v3_scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline vec3 v3_neg(vec3 a) { return v3(-a.x, -a.y, -a.z); }
/* a + b*s */
static inline vec3 v3_madd(vec3 a, vec3 b, float s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
static inline float v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_length2(vec3 a) { return v3_dot(a, a); }
static inline float v3_length(vec3 a) { return sqrtf(v3_dot(a, a)); }
static inline vec3 v3_normalize(vec3 a)
{
    float l = v3_length(a);
    return l > 0.0f ? v3_scale(a, 1.0f / l) : a;
}
/* Componentwise min and max as comparisons, which compile to single minss/maxss instructions
 * (fminf and fmaxf are library calls: C defines them for NaN). A NaN in b is ignored, as fminf
 * would, so a box grown by v3_min(box, p) is never poisoned by a NaN point. */
static inline float f_min(float a, float b) { return b < a ? b : a; }
static inline float f_max(float a, float b) { return b > a ? b : a; }
static inline vec3 v3_min(vec3 a, vec3 b) { return v3(f_min(a.x, b.x), f_min(a.y, b.y), f_min(a.z, b.z)); }
static inline vec3 v3_max(vec3 a, vec3 b) { return v3(f_max(a.x, b.x), f_max(a.y, b.y), f_max(a.z, b.z)); }
static inline vec3 v3_abs(vec3 a) { return v3(fabsf(a.x), fabsf(a.y), fabsf(a.z)); }
static inline float v3_get(vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
static inline float v3_max_comp(vec3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }
static inline int v3_is_zero(vec3 a) { return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f; }
static inline int v3_is_finite(vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
/* Mean of the three channels: the scalar "power" of an RGB quantity used for light selection
 * and Russian roulette. */
static inline float v3_avg(vec3 a) { return (a.x + a.y + a.z) * (1.0f / 3.0f); }

/* Orthonormal basis (t, b, n) around unit n: Duff et al. 2017, "Building an Orthonormal Basis,
 * Revisited", JCGT 6(1). Continuous except at n.z = -0 vs +0, and free of the 1/(1+z) blow-up. */
static inline void v3_basis(vec3 n, vec3 *t, vec3 *b)
{
    float s = copysignf(1.0f, n.z);
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    *t = v3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    *b = v3(c, s + n.y * n.y * a, -n.y);
}

/* Local shading frame: z is the normal. */
typedef struct frame { vec3 t, b, n; } frame;

static inline frame frame_from_normal(vec3 n)
{
    frame f;
    f.n = n;
    v3_basis(n, &f.t, &f.b);
    return f;
}
static inline vec3 frame_to_local(const frame *f, vec3 w)
{
    return v3(v3_dot(w, f->t), v3_dot(w, f->b), v3_dot(w, f->n));
}
static inline vec3 frame_to_world(const frame *f, vec3 w)
{
    return v3_add(v3_add(v3_scale(f->t, w.x), v3_scale(f->b, w.y)), v3_scale(f->n, w.z));
}

#endif
