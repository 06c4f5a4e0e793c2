/* test_motion.c: rigid motion (geom/motion.h), its swept bounds, the motion BVH and the scene ray
 * queries (scene/trace.c) against static copies and brute force; and whole renders through the
 * public API: motion blur equals the average of static renders over the shutter, and a zero
 * motion changes no bit of the image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "mcrt.h"
#include "geom/bvh_node.h"
#include "prim_util.h"
#include "scene/scene.h"
#include "render_util.h"
#include "t.h"

static float uniform(pcg32 *g, float lo, float hi) { return lo + (hi - lo) * pcg32_float(g); }

static vec3 rand_in_box(pcg32 *g, float lo, float hi)
{
    float x = uniform(g, lo, hi), y = uniform(g, lo, hi);
    return v3(x, y, uniform(g, lo, hi));
}

static vec3 rand_dir(pcg32 *g)
{
    float z = 1.0f - 2.0f * pcg32_float(g), phi = 2.0f * MC_PI * pcg32_float(g);
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3(s * cosf(phi), s * sinf(phi), z);
}

/* A random motion: a quarter pure translations, a quarter pure rotations, the rest both. Spins up
 * to max_omega radians per unit time either way. */
static struct motion rand_motion(pcg32 *g, float max_omega)
{
    struct motion m;
    uint32_t kind = pcg32_next(g) % 4;
    m.axis = rand_dir(g);
    m.center = rand_in_box(g, -5.0f, 5.0f);
    m.move = kind == 1 ? v3s(0.0f) : rand_in_box(g, -4.0f, 4.0f);
    m.omega = kind == 0 ? 0.0f : uniform(g, -max_omega, max_omega);
    return m;
}

/* The map in double by a formula independent of Rodrigues' matrix: split u = x − c into its
 * parts along and across the axis and turn the latter, u∥ + cos θ·u⊥ + sin θ·(k × u⊥). θ is the
 * float product ω·t that mc_motion_at uses (its rounding is part of the definition). */
static void ref_point(const struct motion *m, float time, vec3 x, double out[3])
{
    double k[3] = {m->axis.x, m->axis.y, m->axis.z};
    double u[3] = {(double)x.x - m->center.x, (double)x.y - m->center.y, (double)x.z - m->center.z};
    double c[3] = {m->center.x, m->center.y, m->center.z}, v[3] = {m->move.x, m->move.y, m->move.z};
    double th = (double)(m->omega * time), ku = k[0] * u[0] + k[1] * u[1] + k[2] * u[2];
    double perp[3], kxp[3];
    int a;
    for (a = 0; a < 3; a++)
        perp[a] = u[a] - ku * k[a];
    kxp[0] = k[1] * perp[2] - k[2] * perp[1];
    kxp[1] = k[2] * perp[0] - k[0] * perp[2];
    kxp[2] = k[0] * perp[1] - k[1] * perp[0];
    for (a = 0; a < 3; a++)
        out[a] = ku * k[a] + cos(th) * perp[a] + sin(th) * kxp[a] + c[a] + (double)time * v[a];
}

static int near3(vec3 a, vec3 b, float tol)
{
    return fabsf(a.x - b.x) <= tol && fabsf(a.y - b.y) <= tol && fabsf(a.z - b.z) <= tol;
}

/* Maps worked out by hand. */
static void test_hand_maps(void)
{
    struct motion m;
    struct rigid x;
    vec3 p;
    /* A quarter turn about z through c = (1 2 3), then a move: c + x̂ goes to c + ŷ + v. */
    m.axis = v3(0.0f, 0.0f, 1.0f);
    m.center = v3(1.0f, 2.0f, 3.0f);
    m.move = v3(1.0f, -2.0f, 0.5f);
    m.omega = 0.5f * MC_PI;
    mc_motion_at(&m, 1.0f, &x);
    p = rigid_point(&x, v3(2.0f, 2.0f, 3.0f));
    T_CHECK(near3(p, v3(2.0f, 1.0f, 3.5f), 1e-6f), "quarter turn: %g %g %g", p.x, p.y, p.z);
    p = rigid_point(&x, v3(1.0f, 2.0f, 5.0f)); /* on the axis: only the move */
    T_CHECK(near3(p, v3(2.0f, 0.0f, 5.5f), 1e-6f), "on the axis: %g %g %g", p.x, p.y, p.z);
    /* Half that time: an eighth of a turn and half the move. */
    mc_motion_at(&m, 0.5f, &x);
    p = rigid_point(&x, v3(2.0f, 2.0f, 3.0f));
    T_CHECK(near3(p, v3(1.5f + sqrtf(0.5f), 1.0f + sqrtf(0.5f), 3.25f), 1e-6f), "eighth turn: %g %g %g",
            p.x, p.y, p.z);
    /* Negative time turns back: x̂ about z by −90° is −ŷ. */
    m.center = v3s(0.0f);
    m.move = v3s(0.0f);
    mc_motion_at(&m, -1.0f, &x);
    p = rigid_point(&x, v3(1.0f, 0.0f, 0.0f));
    T_CHECK(near3(p, v3(0.0f, -1.0f, 0.0f), 1e-6f), "negative time: %g %g %g", p.x, p.y, p.z);
    /* A third of a turn about (1 1 1) permutes the axes: x̂ → ŷ → ẑ → x̂. */
    m.axis = v3s(1.0f / sqrtf(3.0f));
    m.omega = 2.0f * MC_PI / 3.0f;
    mc_motion_at(&m, 1.0f, &x);
    T_CHECK(near3(x.r[0], v3(0, 0, 1), 1e-6f) && near3(x.r[1], v3(1, 0, 0), 1e-6f)
                && near3(x.r[2], v3(0, 1, 0), 1e-6f) && near3(x.t, v3s(0.0f), 1e-6f),
            "third turn rows %g %g %g / %g %g %g / %g %g %g", x.r[0].x, x.r[0].y, x.r[0].z,
            x.r[1].x, x.r[1].y, x.r[1].z, x.r[2].x, x.r[2].y, x.r[2].z);
    /* Time 0 is exactly the identity, spin or not; a pure translation is exactly t·v. */
    m.center = v3(3.0f, -1.0f, 7.0f);
    m.move = v3(4.0f, 0.0f, -8.0f);
    mc_motion_at(&m, 0.0f, &x);
    p = v3(0.3f, 0.7f, -0.1f);
    T_CHECK(rigid_point(&x, p).x == p.x && rigid_point(&x, p).y == p.y
                && rigid_point(&x, p).z == p.z,
            "time 0 is not the identity");
    m.omega = 0.0f;
    mc_motion_at(&m, 0.25f, &x);
    p = rigid_point(&x, v3(0.5f, 0.25f, 1.0f));
    T_CHECK(p.x == 1.5f && p.y == 0.25f && p.z == -1.0f, "translation: %g %g %g", p.x, p.y, p.z);
}

/* Random motions at random times: R orthonormal with determinant 1, distances and angles kept,
 * the inverse undoes the map, and the map equals the independent double formula. Tolerances: the
 * entries of R carry a few float roundings (≈ 4·2^-24 ≈ 2.4e-7), so 2e-6 (8×) for R·Rᵀ = I and
 * det R = 1; points have magnitude M ≲ |x| + 2|c| + |t·v| ≲ 40 here and pick up a few ulps of M
 * per operation, so 2^-18·M (64 ulps of M) for positions. */
static void test_rigidity(void)
{
    pcg32 g;
    int i, bad_r = 0, bad_len = 0, bad_inv = 0, bad_ref = 0;
    double worst_ref = 0.0;
    pcg32_seed(&g, 11, 3);
    for (i = 0; i < 20000; i++) {
        struct motion m = rand_motion(&g, 20.0f);
        float time = uniform(&g, -2.0f, 2.0f);
        struct rigid x;
        vec3 a = rand_in_box(&g, -10.0f, 10.0f), b = rand_in_box(&g, -10.0f, 10.0f);
        vec3 c = rand_in_box(&g, -10.0f, 10.0f), xa, xb, xc, back;
        double ref[3], det, mag;
        int j, k;
        mc_motion_at(&m, time, &x);
        for (j = 0; j < 3; j++)
            for (k = 0; k < 3; k++)
                bad_r += fabsf(v3_dot(x.r[j], x.r[k]) - (j == k)) > 2e-6f;
        det = v3_dot(x.r[0], v3_cross(x.r[1], x.r[2]));
        bad_r += fabs(det - 1.0) > 2e-6;
        xa = rigid_point(&x, a);
        xb = rigid_point(&x, b);
        xc = rigid_point(&x, c);
        mag = 10.0 + 2.0 * v3_max_comp(v3_abs(m.center)) + fabsf(time) * v3_max_comp(v3_abs(m.move));
        bad_len += fabs(v3_length(v3_sub(xa, xb)) - v3_length(v3_sub(a, b))) > 0x1p-18 * mag;
        bad_len += fabs(v3_dot(v3_sub(xa, xc), v3_sub(xb, xc)) - v3_dot(v3_sub(a, c), v3_sub(b, c)))
                   > 0x1p-18 * mag * 40.0;
        back = rigid_inv_point(&x, xa);
        bad_inv += !near3(back, a, (float)(0x1p-18 * mag));
        ref_point(&m, time, a, ref);
        for (k = 0; k < 3; k++) {
            double e = fabs(v3_get(xa, k) - ref[k]) / mag;
            worst_ref = e > worst_ref ? e : worst_ref;
        }
    }
    bad_ref = worst_ref > 0x1p-18;
    T_NOTE("rigidity: 20000 maps, worst |map − double formula| = %.2g of the magnitude", worst_ref);
    T_CHECK(bad_r == 0, "%d orthonormality/determinant failures", bad_r);
    T_CHECK(bad_len == 0, "%d distance/angle failures", bad_len);
    T_CHECK(bad_inv == 0, "%d inverse failures", bad_inv);
    T_CHECK(bad_ref == 0, "worst deviation from the double formula %g", worst_ref);
}

static int inside(vec3 p, struct aabb b)
{
    return p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z && p.x <= b.hi.x && p.y <= b.hi.y
        && p.z <= b.hi.z;
}

/* Swept bounds. Conservative: at random times in the shutter (and at its ends), the moved box's
 * corners and random points of it lie inside. Tight: against bounds of the corners sampled at 4096
 * times, each face is out by at most the documented pad, r·(2π/64)²/8 for the interpolation plus
 * the 2^-20 rounding pad (here < 2^-19·M), plus what 4096 samples themselves miss
 * (r·(Δθ/4096)²/8); past a full turn, plus the translation during one turn. A pure translation
 * is the union of the end boxes within the rounding pad alone. */
static void test_bounds(void)
{
    enum { CASES = 3000, TIMES = 100, DENSE = 4096 };
    pcg32 g;
    int i, outside = 0, loose = 0, trans_bad = 0, checked = 0;
    double worst_slack = 0.0;
    pcg32_seed(&g, 5, 9);
    for (i = 0; i < CASES; i++) {
        struct motion m = rand_motion(&g, i % 3 == 0 ? 40.0f : 4.0f);
        float t0 = uniform(&g, -1.0f, 1.0f), t1 = i % 50 == 0 ? t0 : t0 + uniform(&g, 0.0f, 2.0f);
        struct aabb box, sw, dense = aabb_empty();
        vec3 lo = rand_in_box(&g, -5.0f, 5.0f), ext = rand_in_box(&g, 0.01f, 3.0f), corner[8];
        float r = 0.0f, sweep_angle = fabsf(m.omega * (t1 - t0)), slack, mag;
        int j, k;
        if (i % 10 == 5) {
            /* A point on the spin axis far from the origin: r = 0, so no interpolation pad; only
             * the rounding pad covers the rounding of R·x + (c − R·c) back to x. */
            m.center = v3_scale(m.center, 20.0f);
            lo = v3_add(m.center, v3_scale(m.axis, uniform(&g, -3.0f, 3.0f)));
            ext = v3s(0.0f);
        }
        box.lo = lo;
        box.hi = v3_add(lo, ext);
        sw = mc_motion_bounds(&m, box, t0, t1);
        for (k = 0; k < 8; k++) {
            vec3 u;
            corner[k] = v3(k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y,
                           k & 4 ? box.hi.z : box.lo.z);
            u = v3_sub(corner[k], m.center);
            if (m.omega != 0.0f)
                r = fmaxf(r, v3_length(v3_sub(u, v3_scale(m.axis, v3_dot(u, m.axis)))));
        }
        for (j = 0; j < TIMES + 2; j++) {
            float t = j == 0 ? t0 : j == 1 ? t1 : uniform(&g, t0, t1);
            struct rigid x;
            mc_motion_at(&m, t, &x);
            for (k = 0; k < 8; k++)
                outside += !inside(rigid_point(&x, corner[k]), sw);
            for (k = 0; k < 4; k++)
                outside += !inside(rigid_point(&x, v3_add(lo, v3_mul(ext, rand_in_box(&g, 0, 1)))), sw);
            checked += 12;
        }
        for (j = 0; j <= DENSE; j++) {
            struct rigid x;
            mc_motion_at(&m, t0 + (t1 - t0) * ((float)j / DENSE), &x);
            for (k = 0; k < 8; k++)
                dense = aabb_grow(dense, rigid_point(&x, corner[k]));
        }
        mag = fmaxf(v3_max_comp(v3_abs(sw.lo)), v3_max_comp(v3_abs(sw.hi)))
            + 2.0f * v3_max_comp(v3_abs(m.center)) + r * (1.0f + fabsf(m.omega) * fmaxf(fabsf(t0), fabsf(t1)));
        slack = r * (2.0f * MC_PI / 64.0f) * (2.0f * MC_PI / 64.0f) / 8.0f
              + r * (sweep_angle / DENSE) * (sweep_angle / DENSE) / 8.0f + 0x1p-19f * mag;
        if (sweep_angle > 2.0f * MC_PI)
            slack += v3_max_comp(v3_abs(m.move)) * 2.0f * MC_PI / fabsf(m.omega);
        for (k = 0; k < 3; k++) {
            float s = fmaxf(v3_get(dense.lo, k) - v3_get(sw.lo, k), v3_get(sw.hi, k) - v3_get(dense.hi, k));
            loose += s > slack;
            if (r > 0.0f && sweep_angle <= 2.0f * MC_PI)
                worst_slack = fmax(worst_slack, (s - 0x1p-19f * mag) / r);
        }
        if (m.omega == 0.0f) {
            vec3 a = v3_scale(m.move, t0), z = v3_scale(m.move, t1);
            struct aabb exact = aabb_union((struct aabb){v3_add(box.lo, a), v3_add(box.hi, a)},
                                           (struct aabb){v3_add(box.lo, z), v3_add(box.hi, z)});
            float tol = 0x1p-19f * fmaxf(v3_max_comp(v3_abs(sw.lo)), v3_max_comp(v3_abs(sw.hi)));
            trans_bad += !near3(sw.lo, exact.lo, tol) || !near3(sw.hi, exact.hi, tol);
        }
    }
    T_NOTE("swept bounds: %d points checked in %d cases; worst face slack within a turn %.4f·r "
           "(bound 0.0012·r)", checked, CASES, worst_slack);
    T_CHECK(outside == 0, "%d moved points outside their swept bounds", outside);
    T_CHECK(loose == 0, "%d faces looser than the documented pad", loose);
    T_CHECK(trans_bad == 0, "%d translations not exact", trans_bad);
}

/* The rigid copy of primitive p as it is at `time`. */
static struct prim moved_copy(const struct prim *p, const struct motion *m, float time)
{
    struct prim q = *p;
    struct rigid x;
    mc_motion_at(m, time, &x);
    q.motion = 0;
    switch (p->kind) {
    case PRIM_TRIANGLE:
        q.p[0] = rigid_point(&x, p->p[0]);
        q.p[1] = rigid_point(&x, p->p[1]);
        q.p[2] = rigid_point(&x, p->p[2]);
        break;
    case PRIM_SPHERE:
        q.p[0] = rigid_point(&x, p->p[0]);
        break;
    case PRIM_DISK:
        q.p[0] = rigid_point(&x, p->p[0]);
        q.p[1] = rigid_vector(&x, p->p[1]);
        break;
    default:
        q.p[0] = rigid_point(&x, p->p[0]);
        q.p[1] = rigid_vector(&x, p->p[1]);
        q.p[2] = rigid_vector(&x, p->p[2]);
        break;
    }
    return q;
}

/* The time-0 point of p whose texture coordinates are uv, by inverting the parametrisation
 * (mc_prim_uv, man/mcrt.5) independently of it. */
static vec3 point_of_uv(const struct prim *p, vec2 uv)
{
    switch (p->kind) {
    case PRIM_SPHERE: {
        float th = MC_PI * (1.0f - uv.y), ph = 2.0f * MC_PI * (uv.x - 0.5f);
        vec3 d = v3(sinf(th) * sinf(ph), cosf(th), -sinf(th) * cosf(ph));
        return v3_madd(p->p[0], d, p->p[1].x);
    }
    case PRIM_DISK: {
        vec3 t, b;
        float k = 2.0f * p->p[2].x;
        v3_basis(p->p[1], &t, &b);
        return v3_add(p->p[0],
                      v3_add(v3_scale(t, k * (uv.x - 0.5f)), v3_scale(b, k * (uv.y - 0.5f))));
    }
    case PRIM_QUAD:
        return v3_add(p->p[0], v3_add(v3_scale(p->p[1], uv.x), v3_scale(p->p[2], uv.y)));
    default:
        return v3_add(v3_scale(p->p[0], 1.0f - uv.x - uv.y),
                      v3_add(v3_scale(p->p[1], uv.x), v3_scale(p->p[2], uv.y)));
    }
}

/* A prepared scene of prims with motions (prim.motion set by the caller). */
static void make_scene(struct scene *s, const struct prim *prims, size_t n,
                       const struct motion *motions, size_t nm, float t0, float t1)
{
    mc_diag d;
    size_t i;
    mc_scene_init(s);
    s->camera.shutter[0] = t0;
    s->camera.shutter[1] = t1;
    for (i = 0; i < nm; i++)
        mc_scene_add_motion(s, &motions[i]);
    for (i = 0; i < n; i++)
        mc_scene_add_prim(s, &prims[i]);
    if (mc_scene_prepare(s, &d) != MCRT_OK)
        T_CHECK(0, "prepare: %s", d.msg);
}

/* A ray from a random point around `target` toward a point near it (so that most rays hit). */
static struct ray aimed_ray(pcg32 *g, vec3 target, float spread, float time)
{
    struct ray r;
    vec3 aim = v3_add(target, v3_scale(rand_in_box(g, -1.0f, 1.0f), spread));
    r.o = v3_add(target, v3_scale(rand_dir(g), uniform(g, 2.0f, 8.0f)));
    r.d = v3_normalize(v3_sub(aim, r.o));
    r.tmax = INFINITY;
    r.time = time;
    return r;
}

/* One moving primitive of each kind against its static copy at the ray's time: the same hit or
 * miss, t within 1e-4, the surface point within 1e-4 and its normal within 1e-5 (a sphere's:
 * 1e-4/radius, see below). The texture moves with the primitive: the time-0 point of the hit's
 * texture coordinates, carried to the ray's time, is the hit point (within 1e-4: uv rounds by
 * ≈ 1e-7 of the primitive's size ≲ 2, times 2π on a sphere). The moving test
 * maps the ray (magnitudes ≲ 20) into the time-0 frame, the copy maps the geometry; each is a few
 * float roundings of ≲ 20 (≈ 1e-6), so 1e-4 is a hundredfold margin; unit normals differ by the
 * rounding of R, ≈ 1e-7. Hit or miss can differ only for rays within that rounding of an edge; the
 * count of such rays is reported and must be 0 for these seeds. */
static void test_against_static_copy(void)
{
    enum { TIMES = 8, RAYS = 4000 };
    static const int kinds[] = {PRIM_SPHERE, PRIM_TRIANGLE, PRIM_QUAD, PRIM_DISK};
    pcg32 g;
    int kind_i, hits = 0, miss_bad = 0, t_bad = 0, sf_bad = 0, occ_bad = 0, uv_bad = 0, rays = 0;
    pcg32_seed(&g, 21, 4);
    for (kind_i = 0; kind_i < 4; kind_i++) {
        struct motion m;
        struct prim p;
        struct scene s;
        int ti, i;
        m.axis = v3_normalize(v3(0.3f, 1.0f, -0.2f));
        m.center = v3(0.5f, -0.3f, 0.2f);
        m.move = v3(2.0f, 0.5f, -1.0f);
        m.omega = 2.5f;
        switch (kinds[kind_i]) {
        case PRIM_SPHERE:
            p = test_prim(PRIM_SPHERE, v3(0.2f, 0.1f, 0.0f), v3(0.7f, 0, 0), v3s(0));
            break;
        case PRIM_TRIANGLE:
            p = test_prim(PRIM_TRIANGLE, v3(-0.5f, -0.4f, 0.1f), v3(0.8f, -0.2f, 0.3f),
                          v3(0.1f, 0.9f, -0.2f));
            break;
        case PRIM_QUAD:
            p = test_prim(PRIM_QUAD, v3(-0.5f, -0.5f, 0.2f), v3(1.0f, 0.1f, 0.0f),
                          v3(-0.1f, 0.9f, 0.3f));
            break;
        default:
            p = test_prim(PRIM_DISK, v3(0.1f, 0.2f, -0.1f), v3_normalize(v3(0.2f, 0.3f, 1.0f)),
                          v3(0.6f, 0, 0));
            break;
        }
        p.motion = 1;
        make_scene(&s, &p, 1, &m, 1, 0.0f, 1.0f);
        T_CHECK(s.static_count == 0 && s.motion_bvh.node_count > 0 && s.bvh.node_count == 0,
                "kind %d: static_count %zu", kinds[kind_i], s.static_count);
        for (ti = 0; ti < TIMES; ti++) {
            float time = ((float)ti + 0.5f) / TIMES;
            struct prim q = moved_copy(&s.prims[0], &m, time);
            struct aabb qb = mc_prim_bounds(&q);
            for (i = 0; i < RAYS; i++) {
                struct ray r = aimed_ray(&g, aabb_center(qb), 0.6f, time);
                struct hit hm, hs;
                int fm, fs;
                hs.t = r.tmax;
                fm = mc_scene_intersect(&s, &r, &hm);
                fs = mc_prim_intersect(&q, &r, &hs);
                rays++;
                occ_bad += mc_scene_occluded(&s, &r) != fm;
                if (fm != fs) {
                    miss_bad++;
                    continue;
                }
                if (!fm)
                    continue;
                hits++;
                t_bad += fabsf(hm.t - hs.t) > 1e-4f || hm.prim != 0;
                {
                    struct surface a, b;
                    /* A sphere's normal is (p − c)/radius: it inherits the point's tolerance
                     * over the radius (grazing hits, ill-conditioned along the ray, need it). */
                    float ntol = q.kind == PRIM_SPHERE ? 1e-4f / q.p[1].x : 1e-5f;
                    hs.prim = 0;
                    mc_scene_surface(&s, &r, &hm, &a);
                    mc_prim_surface(&q, s.normals, &r, &hs, &b);
                    sf_bad += !near3(a.p, b.p, 1e-4f) || !near3(a.ng, b.ng, ntol)
                              || !near3(a.ns, b.ns, ntol) || a.front != b.front;
                    {
                        struct rigid x;
                        vec3 back = point_of_uv(&s.prims[0], mc_scene_uv(&s, &r, &hm));
                        mc_motion_at(&m, time, &x);
                        uv_bad += !near3(rigid_point(&x, back), a.p, 1e-4f);
                    }
                }
            }
        }
        mc_scene_free(&s);
    }
    T_NOTE("moving vs static copy: %d rays, %d hits, %d hit/miss disagreements", rays, hits,
           miss_bad);
    T_CHECK(hits > rays / 4, "too few hits (%d of %d) to test anything", hits, rays);
    T_CHECK(miss_bad == 0, "%d rays disagree on hit or miss", miss_bad);
    T_CHECK(t_bad == 0, "%d distances differ", t_bad);
    T_CHECK(sf_bad == 0, "%d surfaces differ", sf_bad);
    T_CHECK(uv_bad == 0, "%d texture coordinates do not move with their primitive", uv_bad);
    T_CHECK(occ_bad == 0, "%d occlusion answers differ from intersection", occ_bad);
}

static struct prim rand_prim(pcg32 *g, float spread)
{
    vec3 a = rand_in_box(g, -spread, spread);
    uint32_t kind = pcg32_next(g) % 8;
    if (kind == 0)
        return test_prim(PRIM_SPHERE, a, v3(uniform(g, 0.05f, 0.3f), 0, 0), v3s(0));
    if (kind == 1)
        return test_prim(PRIM_QUAD, a, v3_scale(rand_dir(g), 0.4f), v3_scale(rand_dir(g), 0.3f));
    if (kind == 2)
        return test_prim(PRIM_DISK, a, rand_dir(g), v3(uniform(g, 0.05f, 0.3f), 0, 0));
    return test_prim(PRIM_TRIANGLE, a, v3_add(a, v3_scale(rand_dir(g), 0.4f)),
                     v3_add(a, v3_scale(rand_dir(g), 0.4f)));
}

/* A static scene: everything in the static BVH, which is node for node the BVH mc_bvh_build makes
 * of the same primitives (motion costs it nothing), and the scene queries give its answers bit
 * for bit. */
static void test_static_scene(void)
{
    enum { N = 2000, RAYS = 20000 };
    struct prim *prims = malloc(N * sizeof *prims);
    struct bvh b;
    struct scene s;
    mc_diag d;
    pcg32 g;
    int i, bad = 0;
    pcg32_seed(&g, 8, 8);
    for (i = 0; i < N; i++)
        prims[i] = rand_prim(&g, 3.0f);
    make_scene(&s, prims, N, NULL, 0, 0.0f, 1.0f);
    T_CHECK(mc_bvh_build(&b, prims, N, &d) == MCRT_OK, "build: %s", d.msg);
    T_CHECK(s.static_count == N && s.motion_bvh.node_count == 0, "static_count %zu, motion nodes %zu",
            s.static_count, s.motion_bvh.node_count);
    T_CHECK(b.node_count == s.bvh.node_count
                && memcmp(b.nodes, s.bvh.nodes, b.node_count * sizeof *b.nodes) == 0
                && memcmp(prims, s.prims, N * sizeof *prims) == 0,
            "the static scene's BVH differs from mc_bvh_build's");
    for (i = 0; i < RAYS; i++) {
        struct ray r = aimed_ray(&g, v3s(0.0f), 3.0f, uniform(&g, 0.0f, 1.0f));
        struct hit a, c;
        int fa = mc_scene_intersect(&s, &r, &a), fc = mc_bvh_intersect(&s.bvh, s.prims, &r, &c);
        bad += fa != fc || (fa && (a.t != c.t || a.prim != c.prim || a.u != c.u || a.v != c.v));
        bad += mc_scene_occluded(&s, &r) != mc_bvh_occluded(&s.bvh, s.prims, &r);
    }
    T_CHECK(bad == 0, "%d rays differ from mc_bvh_intersect/occluded", bad);
    mc_bvh_free(&b);
    mc_scene_free(&s);
    free(prims);
}

/* Brute force over a prepared scene's primitives: static ones with the world ray, moving ones with
 * the ray mapped to their time-0 frame, the same map the BVH leaf applies. */
static int brute_intersect(const struct scene *s, const struct ray *r, struct hit *h)
{
    size_t i;
    int found = 0;
    h->t = r->tmax;
    for (i = 0; i < s->prim_count; i++) {
        const struct prim *p = &s->prims[i];
        struct ray local = *r;
        if (p->motion) {
            struct rigid x;
            mc_motion_at(&s->motions[p->motion - 1], r->time, &x);
            local = rigid_inv_ray(&x, r);
        }
        if (mc_prim_intersect(p, &local, h)) {
            h->prim = (uint32_t)i;
            found = 1;
        }
    }
    return found;
}

/* Static and moving primitives mixed, several motions (one per group of 20 primitives, so leaves
 * mix motions and the leaf's cached map must change correctly), rays at random times in a
 * shutter [0.2, 0.9]: the scene queries give brute force's answer bit for bit (the same t; the
 * same primitive except for exact ties). Also: lights index the final primitive order. */
static void test_mixed_brute_force(void)
{
    enum { N = 1200, MOTIONS = 30, RAYS = 20000 };
    struct prim *prims = malloc(N * sizeof *prims);
    struct motion motions[MOTIONS];
    struct scene s;
    pcg32 g;
    int i, bad = 0, occ_bad = 0, hits = 0, moving_hits = 0, ties = 0, light_bad = 0, lights = 0;
    size_t k;
    pcg32_seed(&g, 31, 2);
    for (i = 0; i < MOTIONS; i++)
        motions[i] = rand_motion(&g, 3.0f);
    for (i = 0; i < N; i++) {
        prims[i] = rand_prim(&g, 3.0f);
        if (i % 3 != 0)
            prims[i].motion = (uint16_t)(1 + (i / 20) % MOTIONS);
        if (i % 97 == 0)
            prims[i].emit = v3s(1.0f);
    }
    make_scene(&s, prims, N, motions, MOTIONS, 0.2f, 0.9f);
    T_CHECK(s.static_count == (N + 2) / 3, "static_count %zu", s.static_count);
    for (k = 0; k < s.prim_count; k++)
        bad += (k < s.static_count) != (s.prims[k].motion == 0);
    for (k = 0; k < s.light_count; k++) {
        if (s.lights[k].kind != LIGHT_AREA)
            continue;
        lights++;
        light_bad += s.prims[s.lights[k].prim].light != (int)k;
    }
    T_CHECK(bad == 0, "prims not partitioned static first");
    T_CHECK(lights == (N + 96) / 97 && light_bad == 0, "%d area lights, %d misindexed", lights,
            light_bad);
    for (i = 0; i < RAYS; i++) {
        struct ray r = aimed_ray(&g, v3s(0.0f), 5.0f, i % 10 == 0 ? (i % 20 ? 0.2f : 0.9f)
                                                                  : uniform(&g, 0.2f, 0.9f));
        struct hit a, b;
        int fa, fb;
        if (i % 4 == 0)
            r.tmax = uniform(&g, 0.5f, 6.0f);
        fa = mc_scene_intersect(&s, &r, &a);
        fb = brute_intersect(&s, &r, &b);
        occ_bad += mc_scene_occluded(&s, &r) != fb;
        if (fa != fb || (fa && a.t != b.t)) {
            bad++;
            continue;
        }
        if (!fa)
            continue;
        hits++;
        moving_hits += a.prim >= s.static_count;
        if (a.prim != b.prim)
            ties++;
    }
    T_NOTE("mixed scene: %d rays, %d hits (%d on moving prims), %d exact ties", RAYS, hits,
           moving_hits, ties);
    T_CHECK(moving_hits > RAYS / 10 && hits - moving_hits > RAYS / 20, "too few hits to test");
    T_CHECK(bad == 0, "%d rays differ from brute force", bad);
    T_CHECK(occ_bad == 0, "%d occlusion answers differ from brute force", occ_bad);
    T_CHECK(ties <= 2, "%d primitive mismatches", ties);
    mc_scene_free(&s);
    free(prims);
}

/* The 12 triangles of the cube [-0.5, 0.5]³ translated by c, wound outward. */
static size_t cube(struct prim *out, vec3 c)
{
    static const int face[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                   {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    vec3 v[8];
    size_t n = 0;
    int i;
    for (i = 0; i < 8; i++)
        v[i] = v3_add(c, v3(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f));
    for (i = 0; i < 6; i++) {
        out[n++] = test_prim(PRIM_TRIANGLE, v[face[i][0]], v[face[i][2]], v[face[i][1]]);
        out[n++] = test_prim(PRIM_TRIANGLE, v[face[i][0]], v[face[i][3]], v[face[i][2]]);
    }
    return n;
}

/* A spinning mesh (a cube spun 90° about a tilted axis through its centre while it moves, all 12
 * triangles sharing one motion) against the statically rotated copy at several times: hits, t and
 * normals as in test_against_static_copy. And the moving mesh stays closed: rays from its centre
 * at random times all hit it from inside (the leaf maps one ray for all its triangles, so the
 * watertight test's guarantee carries over). */
static void test_spinning_mesh(void)
{
    enum { TIMES = 6, RAYS = 5000 };
    struct prim prims[12], copy[12];
    struct motion m;
    struct scene s;
    pcg32 g;
    size_t n = cube(prims, v3(0.2f, 0.4f, -0.3f)), k;
    int ti, i, bad = 0, hits = 0, leaks = 0, wrong_side = 0;
    pcg32_seed(&g, 4, 40);
    m.axis = v3_normalize(v3(1.0f, 2.0f, 0.5f));
    m.center = v3(0.2f, 0.4f, -0.3f);
    m.move = v3(1.0f, 0.0f, 0.5f);
    m.omega = 0.5f * MC_PI;
    for (k = 0; k < n; k++)
        prims[k].motion = 1;
    make_scene(&s, prims, n, &m, 1, 0.0f, 1.0f);
    for (ti = 0; ti < TIMES; ti++) {
        float time = (float)ti / (TIMES - 1);
        for (k = 0; k < n; k++)
            copy[k] = moved_copy(&s.prims[k], &m, time);
        for (i = 0; i < RAYS; i++) {
            struct ray r = aimed_ray(&g, v3_add(m.center, v3_scale(m.move, time)), 1.0f, time);
            struct hit a, b;
            int fa = mc_scene_intersect(&s, &r, &a), fb = 0;
            b.t = r.tmax;
            for (k = 0; k < n; k++)
                if (mc_prim_intersect(&copy[k], &r, &b)) {
                    b.prim = (uint32_t)k;
                    fb = 1;
                }
            if (fa != fb) {
                bad++;
                continue;
            }
            if (fa) {
                struct surface sa, sb;
                hits++;
                mc_scene_surface(&s, &r, &a, &sa);
                mc_prim_surface(&copy[b.prim], s.normals, &r, &b, &sb);
                bad += fabsf(a.t - b.t) > 1e-4f || !near3(sa.ng, sb.ng, 1e-5f)
                       || !near3(sa.p, sb.p, 1e-4f);
            }
        }
    }
    for (i = 0; i < 20000; i++) {
        struct ray r;
        struct hit h;
        struct surface sf;
        r.time = uniform(&g, 0.0f, 1.0f);
        r.o = v3_add(m.center, v3_scale(m.move, r.time));
        r.d = rand_dir(&g);
        r.tmax = INFINITY;
        if (!mc_scene_intersect(&s, &r, &h)) {
            leaks++;
            continue;
        }
        mc_scene_surface(&s, &r, &h, &sf);
        wrong_side += sf.front;
    }
    T_NOTE("spinning cube: %d hits of %d rays agree with the rotated copy", hits, TIMES * RAYS);
    T_CHECK(bad == 0 && hits > TIMES * RAYS / 4, "%d disagreements, %d hits", bad, hits);
    T_CHECK(leaks == 0 && wrong_side == 0, "%d rays escape the moving cube, %d see its outside",
            leaks, wrong_side);
    mc_scene_free(&s);
}

/* prepare refuses a motion index past the scene's motions. */
static void test_bad_motion_index(void)
{
    struct scene s;
    struct prim p = test_prim(PRIM_SPHERE, v3s(0.0f), v3(1, 0, 0), v3s(0));
    mc_diag d;
    p.motion = 2;
    mc_scene_init(&s);
    mc_scene_add_prim(&s, &p);
    T_CHECK(mc_scene_prepare(&s, &d) == MCRT_ERR_INVALID, "a dangling motion index was accepted");
    mc_scene_free(&s);
}


/* ---- Renders through the public API ---- */

/* Render scene text at spp samples with the seed and thread count (0: all cores); returns the
 * pixels (3 floats each, malloc'd) or NULL after printing why. */
static float *render(const char *text, int spp, uint64_t seed, int threads, int *w, int *h)
{
    struct t_render_opts o = {0, 0, 0, 0, NULL, NULL};
    o.spp = spp;
    o.seed = seed;
    o.threads = threads;
    return t_render(text, &o, w, h, NULL);
}

/* The blur scene, 48×32 pixels: a grey wall under a point light, a red sphere crossing the image
 * from left to right (26 pixels over the shutter: 3.6 units of the 6.5 the image spans at its
 * depth) and casting a moving shadow, and a small emitting sphere rising (13 pixels: 1.8 of 4.4
 * units) that lights the wall, so that a moving emitter is sampled as a light too. With
 * moving != 0 the spheres are given at time 0 with their `move`; else they are static, placed
 * where they are at `time`. */
enum { BLUR_W = 48, BLUR_H = 32 };
static const double BLUR_SPEED_RED = 26.0, BLUR_SPEED_GLOW = 13.0; /* pixels per unit time */

static void blur_scene(char *buf, size_t size, int moving, double time)
{
    const double red_x = -2.0, red_v = 3.6, glow_y = -1.4, glow_v = 1.8;
    char red[64], glow[64];
    if (moving) {
        snprintf(red, sizeof red, "%.9g 0.2 0  move %.9g 0 0", red_x, red_v);
        snprintf(glow, sizeof glow, "0.5 %.9g 0.6  move 0 %.9g 0", glow_y, glow_v);
    } else {
        snprintf(red, sizeof red, "%.9g 0.2 0", red_x + time * red_v);
        snprintf(glow, sizeof glow, "0.5 %.9g 0.6", glow_y + time * glow_v);
    }
    snprintf(buf, size,
             "film { width %d height %d }\n"
             "camera { eye 0 0 6  look 0 0 0  fov 40  shutter 0 1 }\n"
             "integrator { method direct }\n"
             "material grey { diffuse 0.5 }\n"
             "material red { diffuse 0.8 0.2 0.1 }\n"
             "quad { corner -5 -4 -1  edge1 10 0 0  edge2 0 8 0  material grey }\n"
             "point_light { position 1 2 5  intensity 20 }\n"
             "sphere { center %s  radius 0.6  material red }\n"
             "sphere { center %s  radius 0.25  emit 0.5 }\n",
             BLUR_W, BLUR_H, red, glow);
}

/* Motion blur against the average of K static renders at the mid-times (i + ½)/K. R independent
 * replicas of each side (different seeds): the moving render with K samples per pixel, the static
 * average with 1 per time. Compared on the sum of the channels over 8×8 blocks. Pixels are
 * independent, so the variance of a block's mean difference is the sum of the per-pixel variances
 * (each estimated from the R replicas: 64·(R − 1) degrees of freedom per block) over 64². A block
 * passes within 4.3 standard errors (the two-sided Šidák bound for a 1e-3 chance of any false
 * failure over 24 blocks) plus the bias of the mid-point rule. Per pixel, that bias is at most
 * (h²/8)·∫|f''| (the Peano kernel of the mid-point rule; h = 1/K, f(t) the pixel's expected value
 * at time t). An edge of radiance contrast ΔL moving at v pixels per unit time through a pixel
 * gives f' = ΔL·v·ℓ(t), ℓ the edge's length inside the pixel (≤ √2, rising and falling at most
 * twice per edge, two edges per object), so ∫|f''| ≤ ΔL·v·8√2. Four things move — each sphere
 * and its shadow — and every contrast is at most Lmax, the largest radiance in the image (the
 * largest of the static renders' single samples): bias ≤ (h²/8)·8√2·Lmax·2·(v_red + v_glow). */
static void test_blur_equals_static_average(void)
{
    enum { K = 512, R = 4, B = 8, N = BLUR_W * BLUR_H };
    const double h = 1.0 / K;
    char text[1024];
    double *sum[2], *sum2[2], lmax = 0.0, bias, worst = 0.0, chi2 = 0.0;
    int j, i, side, k, bad = 0, blocks = 0, ok = 1;
    for (side = 0; side < 2; side++) {
        sum[side] = calloc(N, sizeof(double));
        sum2[side] = calloc(N, sizeof(double));
    }
    for (j = 0; j < R && ok; j++) {
        for (side = 0; side < 2 && ok; side++) {
            /* side 0: one moving render of K samples; side 1: K static ones of 1 sample */
            double acc[N];
            int n = side == 0 ? 1 : K;
            memset(acc, 0, sizeof acc);
            for (i = 0; i < n && ok; i++) {
                int w, ht;
                float *img;
                blur_scene(text, sizeof text, side == 0, (i + 0.5) / K);
                img = render(text, side == 0 ? K : 1, (uint64_t)(1 + side * 100000 + j * K + i),
                             side == 0 ? 0 : 1, &w, &ht);
                ok = img && w == BLUR_W && ht == BLUR_H;
                for (k = 0; ok && k < N; k++) {
                    double y = (double)img[3 * k] + img[3 * k + 1] + img[3 * k + 2];
                    acc[k] += y / n;
                    if (side == 1) /* one sample: a radiance at an instant */
                        lmax = fmax(lmax, y);
                }
                free(img);
            }
            for (k = 0; ok && k < N; k++) {
                sum[side][k] += acc[k];
                sum2[side][k] += acc[k] * acc[k];
            }
        }
    }
    T_CHECK(ok, "the blur renders failed");
    bias = h * h / 8.0 * 8.0 * sqrt(2.0) * lmax * 2.0 * (BLUR_SPEED_RED + BLUR_SPEED_GLOW);
    for (j = 0; ok && j + B <= BLUR_H; j += B)
        for (i = 0; i + B <= BLUR_W; i += B) {
            double diff = 0.0, var = 0.0, se;
            int x, y;
            for (y = j; y < j + B; y++)
                for (x = i; x < i + B; x++) {
                    k = y * BLUR_W + x;
                    for (side = 0; side < 2; side++) {
                        double m = sum[side][k] / R;
                        var += (sum2[side][k] - R * m * m) / (R - 1) / R;
                    }
                    diff += (sum[0][k] - sum[1][k]) / R;
                }
            diff /= B * B;
            se = sqrt(var) / (B * B);
            blocks++;
            chi2 += diff * diff / (se * se);
            worst = fmax(worst, fabs(diff) / (4.3 * se + bias));
            if (!(fabs(diff) <= 4.3 * se + bias)) {
                bad++;
                printf("block (%d, %d): moving − static = %.4g, standard error %.3g\n", i, j, diff, se);
            }
        }
    T_NOTE("blur vs %d static renders: %d blocks, sum of z² %.1f (expect ≈ %d), worst "
           "|diff|/tol %.2f (tol = 4.3 SE + mid-point bias %.1e, Lmax %.2f)", K, blocks, chi2, blocks,
           worst, bias, lmax);
    T_CHECK(blocks == 24 && bad == 0, "%d of %d blocks differ", bad, blocks);
    for (side = 0; side < 2; side++) {
        free(sum[side]);
        free(sum2[side]);
    }
}

/* `move 0 0 0` (and `spin` by 0 degrees, and a still camera `move`) is no motion: the image is
 * bit for bit the one without the keys, at the same seed. */
static void test_zero_motion_is_static(void)
{
    char a[1024], b[1024];
    float *ia, *ib;
    int wa, ha, wb, hb, v;
    for (v = 0; v < 2; v++) {
        const char *z = v ? "move 0 0 0" : "";
        snprintf(v ? b : a, sizeof a,
                 "film { width 40 height 30 spp 16 }\n"
                 "camera { eye 0 1 6  look 0 0.5 0  fov 40 %s }\n"
                 "material grey { diffuse 0.5 }\n"
                 "quad { corner -5 0 5  edge1 10 0 0  edge2 0 0 -10  material grey %s }\n"
                 "sphere { center -0.8 0.6 0  radius 0.6 %s }\n"
                 "mesh { file \"scenes/cube.obj\"  scale 0.4  translate 1 0.4 0 %s %s }\n"
                 "quad { corner -1 4 -1  edge1 2 0 0  edge2 0 0 2  emit 5 %s }\n",
                 z, z, z, z, v ? "spin 0 1 0 0" : "", z);
    }
    ia = render(a, 16, 3, 0, &wa, &ha);
    ib = render(b, 16, 3, 0, &wb, &hb);
    T_CHECK(ia && ib && wa == wb && ha == hb
                && memcmp(ia, ib, (size_t)wa * ha * 3 * sizeof *ia) == 0,
            "a zero motion changed the image");
    free(ia);
    free(ib);
}

int main(void)
{
    test_hand_maps();
    test_rigidity();
    test_bounds();
    test_against_static_copy();
    test_static_scene();
    test_mixed_brute_force();
    test_spinning_mesh();
    test_bad_motion_index();
    test_blur_equals_static_average();
    test_zero_motion_is_static();
    return t_done();
}
