/* test_disk.c: the disk primitive: intersection and surface with known answers, the rim of tiny,
 * huge and far disks and of grazing rays against an extended-precision reference, hit points on
 * the plane, tight and conservative bounds, area, uniform area sampling (chi-square), and the
 * BVH against brute force. */
#include <stdlib.h>
#include <string.h>

#include "chi2.h"
#include "geom/bvh.h"
#include "prim_util.h"
#include "t.h"

#define CHI2_TESTS 1

static const double PI = 3.14159265358979323846;

static struct prim disk(vec3 c, vec3 n, float r)
{
    return test_prim(PRIM_DISK, c, v3_normalize(n), v3(r, 0.0f, 0.0f));
}

static void test_known(void)
{
    struct prim p = disk(v3(1, 2, 3), v3(0, 0, 1), 2.0f);
    struct hit h;
    struct surface s;
    struct ray r = test_ray(v3(1.5f, 2.25f, 10), v3(0, 0, -1));
    /* Exact in binary: t = 7, the point (1.5, 2.25, 3). */
    T_CHECK(test_hit1(&p, r, &h) && h.t == 7.0f, "front hit, t %g", h.t);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.p.x == 1.5f && s.p.y == 2.25f && s.p.z == 3.0f, "p (%g %g %g)", s.p.x, s.p.y, s.p.z);
    T_CHECK(s.ng.z == 1.0f && s.ns.z == 1.0f && s.front == 1, "ng.z %g front %d", s.ng.z, s.front);
    r = test_ray(v3(1.5f, 2.25f, -1), v3(0, 0, 1));
    T_CHECK(test_hit1(&p, r, &h) && h.t == 4.0f, "back hit, t %g", h.t);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.front == 0 && s.ng.z == 1.0f, "back: front %d", s.front);
    p.flags = PRIM_FLIP;
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.front == 1 && s.ng.z == -1.0f && s.ns.z == -1.0f, "flip: front %d ng.z %g", s.front,
            s.ng.z);
    p.flags = 0;

    /* The rim at radius 2: 1.999 in, 2.001 out (along x and along a diagonal). */
    T_CHECK(test_hit1(&p, test_ray(v3(2.999f, 2, 5), v3(0, 0, -1)), &h), "just inside the rim");
    T_CHECK(!test_hit1(&p, test_ray(v3(3.001f, 2, 5), v3(0, 0, -1)), &h), "just outside the rim");
    T_CHECK(test_hit1(&p, test_ray(v3(1 + 1.414f, 2 + 1.414f, 5), v3(0, 0, -1)), &h), "inside, diagonal");
    T_CHECK(!test_hit1(&p, test_ray(v3(1 + 1.415f, 2 + 1.415f, 5), v3(0, 0, -1)), &h), "outside, diagonal");
    T_CHECK(!test_hit1(&p, test_ray(v3(1, 2, 5), v3(0, 0, 1)), &h), "pointing away");
    T_CHECK(!test_hit1(&p, test_ray(v3(0, 2, 3), v3(1, 0, 0)), &h), "ray in the plane");
    T_CHECK(!test_hit1(&p, test_ray(v3(0, 2, 4), v3(1, 0, 0)), &h), "parallel ray");
    T_CHECK(!test_hit1(&p, test_ray(v3(1, 2, 3), v3(0, 0, 1)), &h), "t = 0 is rejected");
    r = test_ray(v3(1, 2, 10), v3(0, 0, -1));
    r.tmax = 7.0f;
    T_CHECK(!test_hit1(&p, r, &h), "hit at tmax is rejected");
    T_NEAR(mc_prim_area(&p), 4.0 * PI, 4e-6, "area π r²");
}

/* The reference: the same float ray and disk in long double. Returns the hit distance (or -1 for
 * no plane hit ahead) and the hit's distance from the centre in *rho. */
static long double reference(const struct prim *p, const struct ray *r, long double *rho)
{
    long double n[3] = {p->p[1].x, p->p[1].y, p->p[1].z}, d[3] = {r->d.x, r->d.y, r->d.z};
    long double f[3] = {(long double)r->o.x - p->p[0].x, (long double)r->o.y - p->p[0].y,
                        (long double)r->o.z - p->p[0].z};
    long double den = n[0] * d[0] + n[1] * d[1] + n[2] * d[2], t, w2 = 0.0L;
    int i;
    if (den == 0.0L)
        return -1.0L;
    t = -(n[0] * f[0] + n[1] * f[1] + n[2] * f[2]) / den;
    for (i = 0; i < 3; i++)
        w2 += (f[i] + t * d[i]) * (f[i] + t * d[i]);
    *rho = sqrtl(w2);
    return t > 0.0L ? t : -1.0L;
}

/* Rays aimed at points near the rim, ρ ∈ r·[0.99, 1.01], of disks that stress float: a 1e-3 disk
 * 2000 away, a 1e6 disk seen from 4e6, a unit disk met at 1e-4 rad from its plane (the plane test
 * divides by n·d = 1e-4). The float ray is what it is; the reference classifies that float ray
 * exactly (to long double). Every ray whose reference ρ is more than 1e-6·r from the rim must be
 * classified as the reference does, with t within 1e-6 relative. In float, the offset of a hit
 * 2000 away from a 1e-3 disk would carry errors of ~2000·2^-24 ≈ 1e-4 = 10% of r. */
static void test_rim(void)
{
    struct {
        const char *name;
        vec3 c, o;
        float r, graze; /* graze > 0: origin placed at this angle from the disk's plane */
    } cases[] = {
        {"tiny far disk", {1000, 2000, -500}, {0, 0, 0}, 1e-3f, 0.0f},
        {"huge disk", {5e5f, -2e5f, 1e5f}, {3e6f, 1e6f, -2e6f}, 1e6f, 0.0f},
        {"grazing rays", {0.3f, -0.2f, 0.1f}, {0, 0, 0}, 1.0f, 1e-4f},
    };
    pcg32 g;
    int k, i;
    pcg32_seed(&g, 0xd15c, 1);
    for (k = 0; k < 3; k++) {
        int wrong = 0, tested = 0, hits = 0;
        double worst_t = 0.0;
        for (i = 0; i < 20000; i++) {
            vec3 n = test_rand_dir(&g), t, b, o = cases[k].o, target;
            struct prim p = disk(cases[k].c, n, cases[k].r);
            double phi = 2.0 * PI * pcg32_double(&g);
            double rho = cases[k].r * (0.99 + 0.02 * pcg32_double(&g));
            struct hit h;
            struct ray r;
            long double lrho = 0.0L, lt;
            int got;
            v3_basis(p.p[1], &t, &b);
            target = v3((float)(p.p[0].x + rho * (cos(phi) * t.x + sin(phi) * b.x)),
                        (float)(p.p[0].y + rho * (cos(phi) * t.y + sin(phi) * b.y)),
                        (float)(p.p[0].z + rho * (cos(phi) * t.z + sin(phi) * b.z)));
            if (cases[k].graze > 0.0f) {
                /* From 4 away along a direction in the plane, lifted by the grazing angle (from
                 * farther, the rounding of the origin would move the crossing point by more than
                 * the band about the rim). */
                vec3 away = v3_add(v3_scale(t, cosf((float)phi)), v3_scale(b, sinf((float)phi)));
                o = v3_add(target, v3_scale(v3_add(away, v3_scale(p.p[1], cases[k].graze)), 4.0f));
            }
            r = test_ray(o, v3_normalize(v3_sub(target, o)));
            lt = reference(&p, &r, &lrho);
            got = test_hit1(&p, r, &h);
            if (lt < 0.0L || fabsl(lrho - cases[k].r) <= 1e-6L * cases[k].r)
                continue;
            tested++;
            if (got != (lrho < cases[k].r)) {
                wrong++;
                continue;
            }
            if (got) {
                hits++;
                worst_t = fmax(worst_t, (double)(fabsl(h.t - lt) / lt));
            }
        }
        T_NOTE("%s: %d rays classified, %d hits, %d wrong, largest relative t error %.2g",
               cases[k].name, tested, hits, wrong, worst_t);
        T_CHECK(tested > 15000 && hits > 5000 && wrong == 0 && worst_t <= 1e-6,
                "%s: %d of %d wrong", cases[k].name, wrong, tested);
    }
}

/* Hit points lie on the plane: for rays from 10^4 away, the point's distance from the plane is
 * within 2 ulps of the largest coordinate involved (c and the offset within the disk), where
 * o + t·d alone would be off by ulps of 10^4. */
static void test_surface_on_plane(void)
{
    pcg32 g;
    int i, bad = 0, n = 0;
    double worst = 0.0;
    pcg32_seed(&g, 0x5f, 2);
    for (i = 0; i < 10000; i++) {
        struct prim p = disk(v3(3, 4, 5), test_rand_dir(&g), 1.0f);
        vec3 o = v3_scale(test_rand_dir(&g), 1e4f), t, b, target;
        struct hit h;
        struct surface s;
        struct ray r;
        double off, ulp = 2.0 * 6.0 * 0x1p-24; /* 2 ulps of 6 (|c| components up to 5, plus r) */
        v3_basis(p.p[1], &t, &b);
        /* A point within the square of half-side 0.6 about the centre: inside the disk. */
        target = v3_add(p.p[0], v3_add(v3_scale(t, 0.6f * (2 * pcg32_float(&g) - 1)),
                                       v3_scale(b, 0.6f * (2 * pcg32_float(&g) - 1))));
        r = test_ray(o, v3_normalize(v3_sub(target, o)));
        if (!test_hit1(&p, r, &h))
            continue;
        n++;
        mc_prim_surface(&p, NULL, &r, &h, &s);
        off = fabs((double)p.p[1].x * ((double)s.p.x - p.p[0].x)
                   + (double)p.p[1].y * ((double)s.p.y - p.p[0].y)
                   + (double)p.p[1].z * ((double)s.p.z - p.p[0].z));
        worst = fmax(worst, off);
        bad += !(off <= ulp) || v3_length(v3_sub(s.ng, p.p[1])) > 1e-6f
               || v3_length(v3_sub(s.ns, s.ng)) != 0.0f || s.front != (v3_dot(r.d, s.ng) < 0.0f);
    }
    T_NOTE("hit points from 1e4 away: %d hits, largest distance from the plane %.2g", n, worst);
    T_CHECK(n > 9000 && bad == 0, "%d of %d hit points off the plane or with wrong normals", bad,
            n);
}

/* The box is centre ± r·sinθi per axis: it contains every rim point (computed in double) and is
 * reached by them to within 1e-6·r plus an ulp on each side. A normal 1e-4 rad from an axis gives
 * an extent r·1e-4 along it, which 1 − n² in float would lose. */
static void test_bounds(void)
{
    pcg32 g;
    int i, k, a, bad = 0;
    double worst = 0.0;
    vec3 normals[34];
    normals[0] = v3(0, 0, 1);
    normals[1] = v3(1e-4f, 0, 1);
    normals[2] = v3(0, -1, 1e-4f);
    normals[3] = v3(1, 1, 1);
    pcg32_seed(&g, 0xb0, 3);
    for (i = 4; i < 34; i++)
        normals[i] = test_rand_dir(&g);
    for (i = 0; i < 34; i++) {
        struct prim p = disk(v3(1, -2, 3), normals[i], 0.75f);
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        struct aabb bb = mc_prim_bounds(&p);
        double blo[3] = {bb.lo.x, bb.lo.y, bb.lo.z}, bhi[3] = {bb.hi.x, bb.hi.y, bb.hi.z};
        double c[3] = {1, -2, 3}, n[3] = {p.p[1].x, p.p[1].y, p.p[1].z}, u[3], v[3], l;
        /* An orthonormal pair in the plane, in double. */
        int m = fabs(n[0]) < 0.5 ? 0 : 1;
        double e[3] = {m == 0, m == 1, 0};
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (a = 0; a < 3; a++)
            n[a] /= nn;
        u[0] = n[1] * e[2] - n[2] * e[1];
        u[1] = n[2] * e[0] - n[0] * e[2];
        u[2] = n[0] * e[1] - n[1] * e[0];
        l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (a = 0; a < 3; a++)
            u[a] /= l;
        v[0] = n[1] * u[2] - n[2] * u[1];
        v[1] = n[2] * u[0] - n[0] * u[2];
        v[2] = n[0] * u[1] - n[1] * u[0];
        for (k = 0; k < 20000; k++) {
            double phi = 2.0 * PI * k / 20000.0;
            for (a = 0; a < 3; a++) {
                double x = c[a] + 0.75 * (cos(phi) * u[a] + sin(phi) * v[a]);
                lo[a] = fmin(lo[a], x);
                hi[a] = fmax(hi[a], x);
            }
        }
        for (a = 0; a < 3; a++) {
            double slack = 1e-6 * 0.75 + 4.0 * 0x1p-24 * 4.0; /* sampling of φ, ulps of |x| <= 4 */
            worst = fmax(worst, fmax(lo[a] - blo[a], bhi[a] - hi[a]));
            bad += !(blo[a] <= lo[a] && bhi[a] >= hi[a] && lo[a] - blo[a] <= slack
                     && bhi[a] - hi[a] <= slack);
        }
    }
    T_NOTE("disk bounds: largest slack %.2g", worst);
    T_CHECK(bad == 0, "%d disk box sides loose or not conservative", bad);
}

/* Area sampling: points on the plane within the radius, the front normal (flipped with
 * PRIM_FLIP), and uniform: (ρ²/r², φ) of a uniform point is uniform on [0, 1] × [0, 2π). */
struct disk_ctx {
    struct prim p;
    vec3 t, b;
};

static int sample_disk_polar(void *ctx, pcg32 *g, double *x, double *y)
{
    const struct disk_ctx *c = (const struct disk_ctx *)ctx;
    vec3 n, q, w;
    double a, b, phi;
    q = mc_prim_sample_area(&c->p, v2(pcg32_float(g), pcg32_float(g)), &n);
    w = v3_sub(q, c->p.p[0]);
    if (fabsf(v3_dot(w, c->p.p[1])) > 1e-6f || v3_length(v3_sub(n, c->p.p[1])) > 1e-6f)
        return -1;
    a = v3_dot(w, c->t);
    b = v3_dot(w, c->b);
    phi = atan2(b, a);
    *x = (a * a + b * b) / ((double)c->p.p[2].x * c->p.p[2].x);
    *y = phi < 0.0 ? phi + 2.0 * PI : phi;
    return 1;
}

static double uniform_polar(void *ctx, double x, double y)
{
    (void)ctx;
    (void)x;
    (void)y;
    return 1.0 / (2.0 * PI);
}

static void test_sample_area(void)
{
    struct disk_ctx c;
    struct chi2_spec s;
    struct chi2_result r;
    vec3 n;
    c.p = disk(v3(0.5f, -1, 2), v3(1, 2, -2), 1.5f);
    v3_basis(c.p.p[1], &c.t, &c.b);
    s = chi2_rect_spec("disk area sampling", sample_disk_polar, uniform_polar, &c, 0.0, 1.0, 0.0,
                       2.0 * PI, 40, 80);
    s.seed = 9;
    s.tests = CHI2_TESTS;
    r = chi2_run(&s);
    T_NOTE("disk area sampling: chi2 %.1f, dof %d, p %.3g", r.chi2, r.dof, r.p);
    T_CHECK(r.pass, "disk area sampling: %s", r.why);
    c.p.flags = PRIM_FLIP;
    mc_prim_sample_area(&c.p, v2(0.3f, 0.6f), &n);
    T_CHECK(v3_length(v3_add(n, c.p.p[1])) < 1e-6f, "flipped disk samples the flipped normal");
}

/* A BVH over random disks finds exactly the nearest hit that a loop over all of them finds. */
static void test_bvh(void)
{
    enum { N = 500 };
    struct prim prims[N], orig[N];
    struct bvh b;
    mc_diag d;
    pcg32 g;
    int i, bad = 0, hits = 0;
    pcg32_seed(&g, 0xb7, 4);
    for (i = 0; i < N; i++) {
        vec3 c = v3(8 * pcg32_float(&g) - 4, 8 * pcg32_float(&g) - 4, 8 * pcg32_float(&g) - 4);
        prims[i] = disk(c, test_rand_dir(&g), 0.05f + 0.5f * pcg32_float(&g));
        prims[i].material = i;
    }
    memcpy(orig, prims, sizeof prims);
    if (mc_bvh_build(&b, prims, N, &d) != MCRT_OK) {
        T_CHECK(0, "bvh build: %s", d.msg);
        return;
    }
    for (i = 0; i < 20000; i++) {
        struct ray r = test_ray(v3s(0.0f), test_rand_dir(&g));
        struct hit hb, hl;
        int j, fb, fl = 0;
        r.o = v3(6 * pcg32_float(&g) - 3, 6 * pcg32_float(&g) - 3, 6 * pcg32_float(&g) - 3);
        hb.t = hl.t = INFINITY;
        fb = mc_bvh_intersect(&b, prims, &r, &hb);
        for (j = 0; j < N; j++)
            if (mc_prim_intersect(&orig[j], &r, &hl)) {
                hl.prim = (uint32_t)j;
                fl = 1;
            }
        hits += fl;
        bad += fb != fl || (fb && (hb.t != hl.t || prims[hb.prim].material != (int)hl.prim));
    }
    T_NOTE("disk BVH: %d of 20000 rays hit, %d disagree with brute force", hits, bad);
    T_CHECK(hits > 5000 && bad == 0, "%d rays disagree", bad);
    mc_bvh_free(&b);
}

int main(void)
{
    test_known();
    test_rim();
    test_surface_on_plane();
    test_bounds();
    test_sample_area();
    test_bvh();
    return t_done();
}
