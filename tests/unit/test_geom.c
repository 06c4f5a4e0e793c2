/* test_geom.c: primitive intersection with known answers, precision (far spheres), watertightness
 * on closed meshes (through brute force and through the BVH), degenerate triangles, surface
 * normals, texture coordinates, area sampling, areas and bounds. */
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/bvh.h"
#include "prim_util.h"
#include "t.h"


static struct prim sphere(vec3 c, float r) { return test_prim(PRIM_SPHERE, c, v3(r, 0, 0), v3s(0)); }

static vec3 rand_in_ball(pcg32 *g, float radius)
{
    for (;;) {
        vec3 p = v3(2 * pcg32_float(g) - 1, 2 * pcg32_float(g) - 1, 2 * pcg32_float(g) - 1);
        if (v3_length2(p) <= 1.0f)
            return v3_scale(p, radius);
    }
}

static void test_triangle(void)
{
    struct prim p = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0));
    struct hit h;
    struct surface s;
    struct ray r = test_ray(v3(0.25f, 0.125f, 1), v3(0, 0, -1));
    T_CHECK(test_hit1(&p, r, &h), "front hit");
    /* Every quantity is exact in binary: t = 1, barycentrics (0.25, 0.125). */
    T_CHECK(h.t == 1.0f && h.u == 0.25f && h.v == 0.125f, "t %g u %g v %g", h.t, h.u, h.v);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.ng.x == 0 && s.ng.y == 0 && s.ng.z == 1, "ng (%g %g %g)", s.ng.x, s.ng.y, s.ng.z);
    T_CHECK(s.ns.z == 1 && s.front == 1, "ns.z %g front %d", s.ns.z, s.front);
    T_CHECK(s.p.x == 0.25f && s.p.y == 0.125f && s.p.z == 0, "p (%g %g %g)", s.p.x, s.p.y, s.p.z);

    /* From below: backfaces are hit too, and the ray arrives on the back. */
    r = test_ray(v3(0.25f, 0.125f, -2), v3(0, 0, 1));
    T_CHECK(test_hit1(&p, r, &h) && h.t == 2.0f, "back hit t %g", h.t);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.front == 0 && s.ng.z == 1, "back: front %d ng.z %g", s.front, s.ng.z);

    /* PRIM_FLIP swaps the sides. */
    p.flags = PRIM_FLIP;
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.front == 1 && s.ng.z == -1 && s.ns.z == -1, "flip: front %d ng.z %g", s.front, s.ng.z);
    p.flags = 0;

    T_CHECK(!test_hit1(&p, test_ray(v3(0.6f, 0.6f, 1), v3(0, 0, -1)), &h), "outside (u + v > 1)");
    T_CHECK(!test_hit1(&p, test_ray(v3(-0.1f, 0.5f, 1), v3(0, 0, -1)), &h), "outside (u < 0)");
    T_CHECK(!test_hit1(&p, test_ray(v3(0.25f, 0.25f, 1), v3(0, 0, 1)), &h), "pointing away (t < 0)");
    T_CHECK(!test_hit1(&p, test_ray(v3(0.25f, 0.25f, 0), v3(0, 0, 1)), &h), "t = 0 is rejected");
    T_CHECK(!test_hit1(&p, test_ray(v3(-1, 0.25f, 0), v3(1, 0, 0)), &h), "ray in the triangle's plane");
    r = test_ray(v3(0.25f, 0.25f, 1), v3(0, 0, -1));
    r.tmax = 1.0f;
    T_CHECK(!test_hit1(&p, r, &h), "t = tmax is rejected");
    r.tmax = 1.0000001f;
    T_CHECK(test_hit1(&p, r, &h), "t just below tmax");
    /* Oblique ray with a non-unit direction: t is in units of |d|. */
    r = test_ray(v3(1, 1, 2), v3(-1.5f, -1.75f, -4));
    T_CHECK(test_hit1(&p, r, &h), "oblique");
    T_NEAR(h.t, 0.5, 1e-7, "oblique t");
    T_NEAR(h.u, 0.25, 1e-7, "oblique u");
    T_NEAR(h.v, 0.125, 1e-7, "oblique v");
}

/* 1 if p reports a hit for r or a miss modifies the hit record. */
static int touched(const struct prim *p, struct ray r)
{
    struct hit h;
    return test_hit1(p, r, &h) || !(h.t == INFINITY && h.u == -1.0f && h.v == -1.0f);
}

/* Zero-area primitives (a point, a segment, a flat quad, a sphere of radius 0), each hit right on
 * its geometry: never a hit, and a miss leaves the hit record untouched (in particular no NaN). */
static void test_degenerate(void)
{
    struct prim pts = test_prim(PRIM_TRIANGLE, v3(0.5f, 0.5f, 0), v3(0.5f, 0.5f, 0), v3(0.5f, 0.5f, 0));
    struct prim seg = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(1, 1, 0), v3(0.5f, 0.5f, 0));
    struct prim quad = test_prim(PRIM_QUAD, v3(0, 0, 0), v3(1, 1, 0), v3(2, 2, 0));
    struct prim zero = sphere(v3(0, 0, 0), 0.0f);
    pcg32 g;
    int i, bad = 0;
    pcg32_seed(&g, 3, 1);
    for (i = 0; i < 1000; i++) {
        vec3 o = v3_add(v3(0.5f, 0.5f, 0), test_rand_dir(&g));
        float s = pcg32_float(&g);
        bad += touched(&pts, test_ray(o, v3_sub(v3(0.5f, 0.5f, 0), o)));
        bad += touched(&seg, test_ray(o, v3_sub(v3(s, s, 0), o)));
        bad += touched(&quad, test_ray(o, v3_sub(v3(2 * s, 2 * s, 0), o)));
        bad += touched(&zero, test_ray(o, v3_sub(v3s(0), o)));
    }
    T_CHECK(bad == 0, "%d of 4000 rays hit or changed the record", bad);
    T_CHECK(mc_prim_area(&pts) == 0 && mc_prim_area(&seg) == 0, "zero areas");
}

static void test_sphere(void)
{
    struct prim p = sphere(v3(0, 0, 0), 1.0f);
    struct hit h;
    struct surface s;
    struct ray r = test_ray(v3(0, 0, 5), v3(0, 0, -1));
    T_CHECK(test_hit1(&p, r, &h) && h.t == 4.0f, "outside hit t %g", h.t);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.ng.z == 1 && s.front == 1 && s.p.z == 1, "outside: ng.z %g front %d", s.ng.z, s.front);
    r = test_ray(v3(0, 0, 0), v3(1, 0, 0));
    T_CHECK(test_hit1(&p, r, &h) && h.t == 1.0f, "from inside t %g", h.t);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.ng.x == 1 && s.front == 0, "inside: ng.x %g front %d", s.ng.x, s.front);
    p.flags = PRIM_FLIP;
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.ng.x == -1 && s.front == 1, "flipped: ng.x %g front %d", s.ng.x, s.front);
    p.flags = 0;
    T_CHECK(!test_hit1(&p, test_ray(v3(0, 1.001f, 5), v3(0, 0, -1)), &h), "passes beside");
    T_CHECK(!test_hit1(&p, test_ray(v3(0, 0, 5), v3(0, 0, 1)), &h), "pointing away");
    r = test_ray(v3(0, 0, 5), v3(0, 0, -1));
    r.tmax = 4.0f;
    T_CHECK(!test_hit1(&p, r, &h), "t = tmax rejected");
    r.tmax = 5.5f; /* the near root is at 4 */
    T_CHECK(test_hit1(&p, r, &h) && h.t == 4.0f, "nearest root first");

    /* Oblique, non-unit direction: the hit point lies on the sphere and is reprojected there. */
    {
        pcg32 g;
        int i, bad = 0;
        float worst = 0;
        pcg32_seed(&g, 5, 1);
        p = sphere(v3(1, 2, 3), 0.75f);
        for (i = 0; i < 1000; i++) {
            vec3 o = v3_add(p.p[0], v3_scale(test_rand_dir(&g), 3.0f));
            vec3 target = v3_add(p.p[0], rand_in_ball(&g, 0.7f));
            r = test_ray(o, v3_scale(v3_sub(target, o), 0.5f + pcg32_float(&g)));
            if (!test_hit1(&p, r, &h)) {
                bad++;
                continue;
            }
            mc_prim_surface(&p, NULL, &r, &h, &s);
            worst = fmaxf(worst, fabsf(v3_length(v3_sub(s.p, p.p[0])) - 0.75f));
            bad += !(fabsf(v3_length(s.ng) - 1) < 1e-6f && s.front == 1);
        }
        T_CHECK(bad == 0, "%d oblique sphere rays wrong", bad);
        /* The reprojected point is within float rounding (a few ulps of |p| ~ 4) of the sphere. */
        T_CHECK(worst < 4e-6f, "reprojected point off the sphere by %g", worst);
    }
}

/* A unit sphere 10^5 away: the discriminant and c = |f|² − r² cancel catastrophically in float
 * (|f|² = 1e10 has an ulp of 1024). The reference root is computed in long double. */
static void test_far_sphere(void)
{
    struct prim p = sphere(v3(0, 0, -1e5f), 1.0f);
    struct hit h;
    pcg32 g;
    int i, bad = 0;
    T_CHECK(test_hit1(&p, test_ray(v3s(0), v3(0, 0, -1)), &h) && h.t == 99999.0f, "on-axis t %.9g", h.t);
    pcg32_seed(&g, 9, 1);
    for (i = 0; i < 1000; i++) {
        /* Aim within 0.99 of the centre, so that the ray hits and is not grazing. */
        float a = 2 * MC_PI * pcg32_float(&g), rho = 0.99f * sqrtf(pcg32_float(&g));
        vec3 d = v3_normalize(v3(rho * cosf(a), rho * sinf(a), -1e5f));
        long double fx = 0, fy = 0, fz = 1e5L, dx = d.x, dy = d.y, dz = d.z;
        long double b = fx * dx + fy * dy + fz * dz, aa = dx * dx + dy * dy + dz * dz;
        long double c = fx * fx + fy * fy + fz * fz - 1.0L;
        long double t_ref = (-b - sqrtl(b * b - aa * c)) / aa;
        float ulp = nextafterf((float)t_ref, INFINITY) - (float)t_ref;
        if (!test_hit1(&p, test_ray(v3s(0), d), &h) || fabsl((long double)h.t - t_ref) > ulp)
            bad++;
    }
    /* The double-precision root rounded to float is within 1 ulp of the exact root. */
    T_CHECK(bad == 0, "%d of 1000 far-sphere roots off by more than 1 ulp", bad);
}

static void test_quad(void)
{
    struct prim p = test_prim(PRIM_QUAD, v3(0, 0, 0), v3(2, 0, 0), v3(0, 1, 0));
    struct hit h;
    struct surface s;
    struct ray r = test_ray(v3(1.5f, 0.25f, 2), v3(0, 0, -1));
    T_CHECK(test_hit1(&p, r, &h), "hit");
    T_CHECK(h.t == 2.0f && h.u == 0.75f && h.v == 0.25f, "t %g s %g t %g", h.t, h.u, h.v);
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.ng.z == 1 && s.front == 1 && s.p.x == 1.5f && s.p.y == 0.25f, "surface");
    r = test_ray(v3(1.5f, 0.25f, -2), v3(0, 0, 1));
    T_CHECK(test_hit1(&p, r, &h), "back hit");
    mc_prim_surface(&p, NULL, &r, &h, &s);
    T_CHECK(s.front == 0, "back side");
    T_CHECK(!test_hit1(&p, test_ray(v3(2.1f, 0.5f, 1), v3(0, 0, -1)), &h), "beyond e1");
    T_CHECK(!test_hit1(&p, test_ray(v3(1, 1.1f, 1), v3(0, 0, -1)), &h), "beyond e2");
    T_CHECK(!test_hit1(&p, test_ray(v3(-0.1f, 0.5f, 1), v3(0, 0, -1)), &h), "before the corner");
    /* A slanted parallelogram: the dual basis recovers (s, t) of a point built from them. */
    p = test_prim(PRIM_QUAD, v3(1, 2, 3), v3(1, 0.5f, 0.25f), v3(-0.25f, 1, 0.5f));
    {
        vec3 target = v3_add(v3_add(p.p[0], v3_scale(p.p[1], 0.3f)), v3_scale(p.p[2], 0.6f));
        vec3 o = v3_add(target, v3(0.5f, -1, 3));
        r = test_ray(o, v3_sub(target, o));
        T_CHECK(test_hit1(&p, r, &h), "slanted hit");
        T_NEAR(h.t, 1.0, 1e-6, "slanted t");
        T_NEAR(h.u, 0.3, 1e-6, "slanted s");
        T_NEAR(h.v, 0.6, 1e-6, "slanted t param");
    }
}

static void test_shading_normals(void)
{
    vec3 normals[9];
    struct prim p = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0));
    struct ray r = test_ray(v3(0.25f, 0.25f, 1), v3(0, 0, -1));
    struct hit h;
    struct surface s;
    vec3 want;
    normals[0] = v3(0, 0, 1);
    normals[1] = v3_normalize(v3(1, 0, 1));
    normals[2] = v3_normalize(v3(0, 1, 1));
    normals[3] = normals[4] = normals[5] = v3(0, 0, -1);
    normals[6] = normals[7] = normals[8] = v3s(0);
    p.normals = 0;
    T_CHECK(test_hit1(&p, r, &h), "hit");
    mc_prim_surface(&p, normals, &r, &h, &s);
    want = v3_normalize(v3_add(v3_add(v3_scale(normals[0], 0.5f), v3_scale(normals[1], 0.25f)),
                               v3_scale(normals[2], 0.25f)));
    T_NEAR(s.ns.x, want.x, 1e-6, "interpolated ns.x");
    T_NEAR(s.ns.y, want.y, 1e-6, "interpolated ns.y");
    T_NEAR(s.ns.z, want.z, 1e-6, "interpolated ns.z");
    T_NEAR(v3_length(s.ns), 1, 1e-6, "unit ns");
    p.flags = PRIM_FLIP;
    mc_prim_surface(&p, normals, &r, &h, &s);
    T_CHECK(s.ng.z == -1 && s.ns.z < 0 && s.front == 0, "flipped ns.z %g", s.ns.z);
    p.flags = 0;
    p.normals = 3; /* given against the winding: turned to ng's side */
    mc_prim_surface(&p, normals, &r, &h, &s);
    T_CHECK(s.ns.z == 1, "opposite normals turned: ns.z %g", s.ns.z);
    p.normals = 6; /* zero-length: falls back to ng */
    mc_prim_surface(&p, normals, &r, &h, &s);
    T_CHECK(s.ns.z == 1 && s.ns.x == 0 && s.ns.y == 0, "zero normals fall back to ng");
}

/* ---- Watertightness on closed meshes ---- */

struct mesh {
    vec3 v[1024];
    int tri[2048][3];
    int nv, nt;
};

/* The icosahedron, subdivided `levels` times with midpoints pushed to the unit sphere; shared
 * vertices are shared by index, so neighbouring triangles have bitwise identical edges. */
static void icosphere(struct mesh *m, int levels)
{
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                 {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    const float t = (1.0f + sqrtf(5.0f)) / 2.0f;
    const vec3 v0[12] = {v3(-1, t, 0), v3(1, t, 0), v3(-1, -t, 0), v3(1, -t, 0),
                         v3(0, -1, t), v3(0, 1, t), v3(0, -1, -t), v3(0, 1, -t),
                         v3(t, 0, -1), v3(t, 0, 1), v3(-t, 0, -1), v3(-t, 0, 1)};
    int i, l;
    m->nv = 12;
    m->nt = 20;
    for (i = 0; i < 12; i++)
        m->v[i] = v3_normalize(v0[i]);
    for (i = 0; i < 20; i++)
        memcpy(m->tri[i], f[i], sizeof f[i]);
    for (l = 0; l < levels; l++) {
        int nt = m->nt, tri[2048][3], k, n = 0;
        /* Midpoint of edge (a, b), created once per edge by a linear search (meshes are small). */
        for (i = 0; i < nt; i++) {
            int mid[3], e;
            for (e = 0; e < 3; e++) {
                int a = m->tri[i][e], b = m->tri[i][(e + 1) % 3], j, found = -1;
                vec3 p = v3_normalize(v3_add(m->v[a], m->v[b]));
                for (j = 0; j < m->nv && found < 0; j++)
                    if (m->v[j].x == p.x && m->v[j].y == p.y && m->v[j].z == p.z)
                        found = j;
                if (found < 0) {
                    found = m->nv;
                    m->v[m->nv++] = p;
                }
                mid[e] = found;
            }
            k = n;
            tri[k][0] = m->tri[i][0], tri[k][1] = mid[0], tri[k][2] = mid[2];
            tri[k + 1][0] = m->tri[i][1], tri[k + 1][1] = mid[1], tri[k + 1][2] = mid[0];
            tri[k + 2][0] = m->tri[i][2], tri[k + 2][1] = mid[2], tri[k + 2][2] = mid[1];
            tri[k + 3][0] = mid[0], tri[k + 3][1] = mid[1], tri[k + 3][2] = mid[2];
            n += 4;
        }
        memcpy(m->tri, tri, sizeof(int[3]) * (size_t)n);
        m->nt = n;
    }
}

/* The cube [-1,1]³, each face a g×g grid of quads cut into two triangles. Vertices on shared
 * cube edges are computed by the same expression on both faces, hence bitwise equal. */
static void cube(struct mesh *m, int g)
{
    int face, i, j;
    m->nv = m->nt = 0;
    for (face = 0; face < 6; face++) {
        int axis = face / 2, u = (axis + 1) % 3, w = (axis + 2) % 3;
        float side = face % 2 ? 1.0f : -1.0f;
        int base = m->nv;
        for (j = 0; j <= g; j++)
            for (i = 0; i <= g; i++) {
                float c[3];
                c[axis] = side;
                c[u] = -1.0f + 2.0f * (float)i / (float)g;
                c[w] = -1.0f + 2.0f * (float)j / (float)g;
                m->v[m->nv++] = v3(c[0], c[1], c[2]);
            }
        for (j = 0; j < g; j++)
            for (i = 0; i < g; i++) {
                int a = base + j * (g + 1) + i, b = a + 1, c = a + g + 2, d = a + g + 1;
                /* Alternate the diagonal so that both kinds of interior edge occur. */
                int flip = (i + j) % 2;
                int *t0 = m->tri[m->nt++], *t1 = m->tri[m->nt++];
                t0[0] = a, t0[1] = b, t0[2] = flip ? d : c;
                t1[0] = flip ? b : a, t1[1] = c, t1[2] = d;
            }
    }
}

static struct prim *mesh_prims(const struct mesh *m)
{
    struct prim *p = malloc((size_t)m->nt * sizeof *p);
    int i;
    for (i = 0; i < m->nt; i++)
        p[i] = test_prim(PRIM_TRIANGLE, m->v[m->tri[i][0]], m->v[m->tri[i][1]], m->v[m->tri[i][2]]);
    return p;
}

static int brute_hit(const struct prim *p, int n, const struct ray *r)
{
    struct ray_prep q;
    struct hit h;
    int i, found = 0;
    mc_ray_prep(&q, r);
    h.t = r->tmax;
    for (i = 0; i < n; i++)
        found |= mc_prim_intersect_prep(&p[i], &q, &h);
    return found;
}

/* Count the rays from o that miss the closed mesh: random directions, then rays aimed exactly at
 * every vertex and every edge midpoint (unnormalised directions pass exactly through a vertex). */
struct miss_count { long rays, bvh, brute; };

static void shoot(const struct bvh *b, const struct prim *p, int n, struct ray r, int brute,
                  struct miss_count *mc)
{
    struct hit h;
    mc->rays++;
    mc->bvh += !mc_bvh_intersect(b, p, &r, &h);
    if (brute)
        mc->brute += !brute_hit(p, n, &r);
}

static void aimed_rays(const struct mesh *m, const struct bvh *b, const struct prim *p, vec3 o,
                       struct miss_count *mc)
{
    int i, e;
    for (i = 0; i < m->nv; i++) {
        shoot(b, p, m->nt, test_ray(o, v3_sub(m->v[i], o)), 1, mc);
        shoot(b, p, m->nt, test_ray(o, v3_normalize(v3_sub(m->v[i], o))), 1, mc);
    }
    for (i = 0; i < m->nt; i++)
        for (e = 0; e < 3; e++) {
            vec3 a = m->v[m->tri[i][e]], c = m->v[m->tri[i][(e + 1) % 3]];
            shoot(b, p, m->nt, test_ray(o, v3_sub(v3_scale(v3_add(a, c), 0.5f), o)), 1, mc);
        }
}

static void test_watertight_mesh(const char *name, const struct mesh *m, int random_rays,
                                 int brute_random, float origin_radius)
{
    struct prim *p = mesh_prims(m);
    struct bvh b;
    mc_diag d;
    pcg32 g;
    struct miss_count mc = {0, 0, 0};
    int i;
    T_CHECK(mc_bvh_build(&b, p, (size_t)m->nt, &d) == MCRT_OK, "build: %s", d.msg);
    pcg32_seed(&g, 21, (uint64_t)m->nt);
    for (i = 0; i < random_rays; i++)
        shoot(&b, p, m->nt, test_ray(rand_in_ball(&g, origin_radius), test_rand_dir(&g)), i < brute_random,
              &mc);
    aimed_rays(m, &b, p, v3s(0), &mc);
    for (i = 0; i < 20; i++)
        aimed_rays(m, &b, p, rand_in_ball(&g, origin_radius), &mc);
    T_CHECK(mc.bvh == 0, "%s: %ld of %ld rays escaped through the BVH", name, mc.bvh, mc.rays);
    T_CHECK(mc.brute == 0, "%s: %ld rays escaped through brute force", name, mc.brute);
    T_NOTE("%s: %d triangles, %ld rays (brute force on %d random + all aimed), 0 misses allowed",
           name, m->nt, mc.rays, brute_random);
    mc_bvh_free(&b);
    free(p);
}

/* Axis-aligned and diagonal rays from the cube's centre and from grid points hit its edges and
 * corners exactly, and give zero direction components (infinite 1/d in the slab test). */
static void test_watertight_axis_rays(const struct mesh *m)
{
    struct prim *p = mesh_prims(m);
    struct bvh b;
    mc_diag d;
    struct miss_count mc = {0, 0, 0};
    int x, y, z, dx, dy, dz;
    T_CHECK(mc_bvh_build(&b, p, (size_t)m->nt, &d) == MCRT_OK, "build: %s", d.msg);
    for (x = -2; x <= 2; x++)
        for (y = -2; y <= 2; y++)
            for (z = -2; z <= 2; z++)
                for (dx = -1; dx <= 1; dx++)
                    for (dy = -1; dy <= 1; dy++)
                        for (dz = -1; dz <= 1; dz++) {
                            vec3 o = v3(0.25f * (float)x, 0.25f * (float)y, 0.25f * (float)z);
                            if (dx == 0 && dy == 0 && dz == 0)
                                continue;
                            shoot(&b, p, m->nt, test_ray(o, v3((float)dx, (float)dy, (float)dz)), 1, &mc);
                        }
    T_CHECK(mc.bvh == 0 && mc.brute == 0, "cube axis rays: %ld BVH, %ld brute misses of %ld",
            mc.bvh, mc.brute, mc.rays);
    mc_bvh_free(&b);
    free(p);
}

static void test_watertight(void)
{
    static struct mesh m;
    icosphere(&m, 0);
    test_watertight_mesh("icosahedron", &m, 1000000, 1000000, 0.5f);
    icosphere(&m, 2);
    test_watertight_mesh("icosphere level 2", &m, 1000000, 20000, 0.5f);
    cube(&m, 4);
    test_watertight_mesh("cube 4x4 per face", &m, 1000000, 20000, 0.9f);
    test_watertight_axis_rays(&m);
}

/* ---- Areas, bounds and area sampling ---- */

static void test_area_bounds(void)
{
    struct prim t = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0));
    struct prim q = test_prim(PRIM_QUAD, v3(1, 1, 1), v3(2, 0, 0), v3(0, 3, 0));
    struct prim s = sphere(v3(1, 2, 3), 2.0f);
    struct aabb b;
    T_NEAR(mc_prim_area(&t), 0.5, 1e-7, "triangle area");
    T_NEAR(mc_prim_area(&q), 6.0, 1e-6, "quad area");
    T_NEAR(mc_prim_area(&s), 16.0 * MC_PI, 1e-5, "sphere area");
    b = mc_prim_bounds(&t);
    T_CHECK(b.lo.x == 0 && b.lo.y == 0 && b.lo.z == 0 && b.hi.x == 1 && b.hi.y == 1 && b.hi.z == 0,
            "triangle bounds are exact");
    b = mc_prim_bounds(&s);
    T_CHECK(b.lo.x <= -1 && b.lo.y <= 0 && b.lo.z <= 1 && b.hi.x >= 3 && b.hi.y >= 4 &&
                b.hi.z >= 5, "sphere bounds contain it");
    T_CHECK(b.lo.x > -1.000001f && b.hi.z < 5.000001f, "sphere bounds tight");
    b = mc_prim_bounds(&q);
    T_CHECK(b.lo.x <= 1 && b.lo.y <= 1 && b.hi.x >= 3 && b.hi.y >= 4 && b.lo.z <= 1 && b.hi.z >= 1,
            "quad bounds contain it");
}

/* Mean of N uniform samples against the centroid. The tolerance is 5 standard errors, with the
 * per-coordinate variance of the uniform distribution computed exactly (var_of below). */
static void check_sampling(const char *name, const struct prim *p, vec3 mean_ref, vec3 var,
                           vec3 n_ref)
{
    enum { N = 100000 };
    pcg32 g;
    double sum[3] = {0, 0, 0};
    int i, bad_n = 0, off = 0;
    pcg32_seed(&g, 31, p->kind);
    for (i = 0; i < N; i++) {
        vec3 n, q = mc_prim_sample_area(p, v2(pcg32_float(&g), pcg32_float(&g)), &n);
        sum[0] += q.x;
        sum[1] += q.y;
        sum[2] += q.z;
        if (p->kind == PRIM_SPHERE) {
            vec3 radial = v3_scale(v3_sub(q, p->p[0]), 1.0f / p->p[1].x);
            off += fabsf(v3_length(radial) - 1) > 1e-5f;
            n_ref = (p->flags & PRIM_FLIP) ? v3_neg(radial) : radial;
        } else {
            /* On the plane of the primitive: distance along the normal from p0 within rounding. */
            off += fabsf(v3_dot(v3_sub(q, p->p[0]), n_ref)) > 1e-5f;
        }
        bad_n += v3_length(v3_sub(n, n_ref)) > 1e-5f;
    }
    T_NEAR(sum[0] / N, mean_ref.x, 5 * sqrt(var.x / N), "%s mean x", name);
    T_NEAR(sum[1] / N, mean_ref.y, 5 * sqrt(var.y / N), "%s mean y", name);
    T_NEAR(sum[2] / N, mean_ref.z, 5 * sqrt(var.z / N), "%s mean z", name);
    T_CHECK(off == 0, "%s: %d samples off the surface", name, off);
    T_CHECK(bad_n == 0, "%s: %d samples with a wrong normal", name, bad_n);
}

/* Variance of one coordinate of a uniform point in a triangle with those vertex coordinates. */
static double var_of(double a, double b, double c)
{
    return (a * a + b * b + c * c - a * b - b * c - c * a) / 18.0;
}

static void test_sampling(void)
{
    struct prim t = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(3, 0, 1), v3(1, 2, 0));
    struct prim q = test_prim(PRIM_QUAD, v3(1, 0, 0), v3(2, 0, 0), v3(0, 0, 1));
    struct prim s = sphere(v3(1, 2, 3), 0.5f);
    vec3 nt = v3_normalize(v3_cross(t.p[1], t.p[2]));
    pcg32 g;
    int i, corner = 0;
    enum { N = 100000 };
    check_sampling("triangle", &t, v3(4.0f / 3, 2.0f / 3, 1.0f / 3),
                   v3((float)var_of(0, 3, 1), (float)var_of(0, 0, 2), (float)var_of(0, 1, 0)), nt);
    t.flags = PRIM_FLIP;
    check_sampling("flipped triangle", &t, v3(4.0f / 3, 2.0f / 3, 1.0f / 3),
                   v3((float)var_of(0, 3, 1), (float)var_of(0, 0, 2), (float)var_of(0, 1, 0)),
                   v3_neg(nt));
    /* Quad: uniform in (s, t), so each coordinate's variance is Σ e_i² / 12. */
    check_sampling("quad", &q, v3(2, 0, 0.5f), v3(4.0f / 12, 0, 1.0f / 12), v3(0, -1, 0));
    /* Sphere: each coordinate of a uniform point on a sphere of radius r has variance r²/3. */
    check_sampling("sphere", &s, s.p[0], v3s(0.25f / 3), v3s(0));

    /* Uniformity beyond the mean: the corner sub-triangle b0 > 1/2 has a quarter of the area.
     * Binomial standard error sqrt(p(1-p)/N) = 0.00137; the tolerance is 5 of them. */
    t.flags = 0;
    pcg32_seed(&g, 41, 1);
    for (i = 0; i < N; i++) {
        vec3 n, p = mc_prim_sample_area(&t, v2(pcg32_float(&g), pcg32_float(&g)), &n);
        /* b0 from the point: the barycentric of p0 = (0,0,0) is 1 − b1 − b2, solved in 2D. */
        float b1 = (2 * p.x - 1 * p.y) / 6.0f, b2 = p.y / 2.0f;
        corner += 1 - b1 - b2 > 0.5f;
    }
    T_NEAR((double)corner / N, 0.25, 5 * sqrt(0.25 * 0.75 / N), "corner fraction");
}

/* The uv of the hit seen along ray o + t·d, (-1, -1) for a miss. */
static vec2 uv_at(const struct prim *p, vec3 o, vec3 d)
{
    struct hit h;
    struct ray r = test_ray(o, d);
    if (!test_hit1(p, r, &h))
        return v2(-1.0f, -1.0f);
    return mc_prim_uv(p, NULL, &r, &h);
}

/* The texture coordinates of each shape at known points (mc_prim_uv in prim.h; man/mcrt.5).
 * The tolerance, 1e-6, is 8 float ulps of 1: the hit point and atan2f round by a few ulps. */
static void test_uv(void)
{
    const float tol = 1e-6f;
    struct prim p = sphere(v3(1, 2, 3), 2.0f);
    vec2 uv;
    pcg32 g;
    int i;
    uv = uv_at(&p, v3(1, 2, -10), v3(0, 0, 1)); /* towards -z from the centre: the map's centre */
    T_NEAR(uv.x, 0.5, tol, "sphere -z u");
    T_NEAR(uv.y, 0.5, tol, "sphere -z v");
    uv = uv_at(&p, v3(10, 2, 3), v3(-1, 0, 0));
    T_NEAR(uv.x, 0.75, tol, "sphere +x u");
    T_NEAR(uv.y, 0.5, tol, "sphere +x v");
    uv = uv_at(&p, v3(-10, 2, 3), v3(1, 0, 0));
    T_NEAR(uv.x, 0.25, tol, "sphere -x u");
    uv = uv_at(&p, v3(1, 10, 3), v3(0, -1, 0));
    T_NEAR(uv.y, 1.0, tol, "sphere north pole v");
    uv = uv_at(&p, v3(1, -10, 3), v3(0, 1, 0));
    T_NEAR(uv.y, 0.0, tol, "sphere south pole v");
    /* 45 degrees north, towards -z: v = 3/4. */
    uv = uv_at(&p, v3(1, 2 + 20, 3 - 20), v3_normalize(v3(0, -1, 1)));
    T_NEAR(uv.x, 0.5, tol, "sphere 45N u");
    T_NEAR(uv.y, 0.75, tol, "sphere 45N v");
    /* Random points: (u, v) mapped back by the environment map's formula (light/envmap.c) give
     * the outward direction (1e-5: the hit point's rounding relative to the radius). */
    pcg32_seed(&g, 17, 1);
    for (i = 0; i < 1000; i++) {
        vec3 d = test_rand_dir(&g), o = v3_madd(p.p[0], d, 10.0f), back;
        float theta, phi;
        uv = uv_at(&p, o, v3_neg(d));
        theta = MC_PI * (1.0f - uv.y);
        phi = 2.0f * MC_PI * (uv.x - 0.5f);
        back = v3(sinf(theta) * sinf(phi), cosf(theta), -sinf(theta) * cosf(phi));
        if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)
            || v3_length(v3_sub(back, d)) > 1e-5f)
            break;
    }
    T_CHECK(i == 1000, "sphere uv round trip failed at %d: u %g v %g", i, uv.x, uv.y);

    p = test_prim(PRIM_QUAD, v3(0, 0, 0), v3(2, 0, 0), v3(0, 1, 0));
    uv = uv_at(&p, v3(1.5f, 0.25f, 2), v3(0, 0, -1));
    T_CHECK(uv.x == 0.75f && uv.y == 0.25f, "quad uv %g %g", uv.x, uv.y);
    p.flags = PRIM_FLIP;
    uv = uv_at(&p, v3(1.5f, 0.25f, 2), v3(0, 0, -1));
    T_CHECK(uv.x == 0.75f && uv.y == 0.25f, "flipped quad uv %g %g", uv.x, uv.y);

    p = test_prim(PRIM_DISK, v3(1, 2, 3), v3(0, 0, 1), v3(2, 0, 0));
    uv = uv_at(&p, v3(1.5f, 2.25f, 10), v3(0, 0, -1)); /* w = (0.5, 0.25, 0) */
    T_NEAR(uv.x, 0.625, tol, "disk +z u");
    T_NEAR(uv.y, 0.5625, tol, "disk +z v");
    uv = uv_at(&p, v3(1, 2, 10), v3(0, 0, -1));
    T_NEAR(uv.x, 0.5, tol, "disk centre u");
    T_NEAR(uv.y, 0.5, tol, "disk centre v");
    p = test_prim(PRIM_DISK, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0)); /* t = +x, b = -z */
    uv = uv_at(&p, v3(0.5f, 5, -0.25f), v3(0, -1, 0));
    T_NEAR(uv.x, 0.75, tol, "disk +y u");
    T_NEAR(uv.y, 0.625, tol, "disk +y v");

    p = test_prim(PRIM_TRIANGLE, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0));
    uv = uv_at(&p, v3(0.25f, 0.5f, 1), v3(0, 0, -1));
    T_NEAR(uv.x, 0.25, tol, "triangle u");
    T_NEAR(uv.y, 0.5, tol, "triangle v");
    /* A mesh triangle's own texture coordinates (slot 3), interpolated by the barycentrics:
     * b = (0.25, 0.25, 0.5) gives 0.25 (0.5, 1) + 0.25 (1, 0) + 0.5 (0, 0.5). Flat (zero
     * normals): the shading normal stays geometric. */
    {
        static const vec3 normals[6] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1},
                                        {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        static const vec2 uvs[6] = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 1}, {1, 0}, {0, 0.5f}};
        struct hit h;
        struct surface s;
        struct ray r = test_ray(v3(0.25f, 0.5f, 1), v3(0, 0, -1));
        p.normals = 3;
        T_CHECK(test_hit1(&p, r, &h), "mesh triangle hit");
        uv = mc_prim_uv(&p, uvs, &r, &h);
        T_NEAR(uv.x, 0.375, tol, "mesh u");
        T_NEAR(uv.y, 0.5, tol, "mesh v");
        mc_prim_surface(&p, normals, &r, &h, &s);
        T_CHECK(s.ns.z == 1.0f, "flat mesh triangle: ns = ng");
        uv = mc_prim_uv(&p, NULL, &r, &h);
        T_NEAR(uv.x, 0.25, tol, "mesh without uvs: own u");
    }
}

int main(void)
{
    test_triangle();
    test_degenerate();
    test_sphere();
    test_far_sphere();
    test_quad();
    test_shading_normals();
    test_uv();
    test_watertight();
    test_area_bounds();
    test_sampling();
    return t_done();
}
