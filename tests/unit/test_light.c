/* test_light.c: the emitters against independent answers. For every emitter type — quad, disk,
 * triangle, an emitting mesh, a sphere seen from afar, from close by and from inside, the
 * environment, and moving and spinning emitters at a fixed time — the irradiance at a point of a
 * Lambertian plane estimated by light sampling (mc_light_sample and a shadow ray) equals the one
 * estimated by cosine-weighted hemisphere sampling (rays that hit the emitter), and the closed
 * forms where they exist: πL·r²/(r²+h²) on a disk's axis, πL·(r/d)² facing a sphere, πL inside
 * one, Lambert's polygon formula for quads and triangles. Then chi-square tests of the sampled
 * directions against mc_light_pdf, the MIS pdf consistency (the pdf of a sampled direction, found
 * by tracing it as the integrator does, equals the one returned with it), and selection in
 * proportion to power.
 *
 * Tolerances: an estimate is a mean of N independent terms; its standard error se is the sample
 * standard deviation over √N. Two independent estimates agree when |a − b| < 4·√(se_a² + se_b²),
 * an estimate and an exact value when |a − x| < 4·se_a: the two-sided probability that a correct
 * implementation fails one such check is 6e-5 (normal approximation, good at these N). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "chi2.h"
#include "scene_util.h"
#include "sample/warp.h"
#include "t.h"

/* Chi-square tests in this binary (the Šidák correction divides 0.01 among them). */
#define CHI2_TESTS 8
/* Terms per irradiance estimate. */
#define N_IRR (1L << 19)

static const double PI = 3.14159265358979323846;

/* The emitters the tests share. Seen from the origin, all face it. QUAD's front is
 * (2 0.5 0) x (0 0 1.5) = (0.75 -3 0), down; TRIANGLE's (v1 - v0) x (v2 - v0) = (-1.5 -4 1.75).
 * MOVING_QUAD is QUAD at time 0.7; MOVING_SPHERE is at (0 3 0) then. MESH is an icosahedron
 * stretched so that its triangles differ in area (and so in selection probability). */
#define QUAD "quad { corner -1 2 -0.5  edge1 2 0.5 0  edge2 0 0 1.5  emit 4 }"
#define MOVING_QUAD                                                                            \
    "quad { corner -1.35 2 0.2  edge1 2 0.5 0  edge2 0 0 1.5  emit 4  move 0.5 0 -1 }"
#define DISK "disk { center 1 1.5 0.5  normal -0.3 -1 0.2  radius 0.8  emit 3 }"
#define TRIANGLE "triangle { v0 -1 2 -1  v1 1.5 1.5 0  v2 0 2.5 1  emit 5 }"
#define MESH_AT "mesh { file \"ico.obj\"  scale 1 1.5 1  "
#define MESH MESH_AT "translate 0.5 3 0.3  emit 2 }"
#define SPINNING_MESH MESH_AT "translate 0.5 3 0.3  emit 2  spin 0 0 1 60 }"
#define ROTATED_MESH MESH_AT "rotate 0 0 1 42  translate 0.5 3 0.3  emit 2 }"
#define MOVING_SPHERE "sphere { center -1.4 3 0  radius 1  emit 2  move 2 0 0 }"
#define SPHERE_HORIZON "sphere { center 1.2 0.4 0  radius 1  emit 2 }"
#define SPHERE_INSIDE "sphere { center 0.3 0.5 0  radius 2  emit 2  two_sided }"

/* The shading point (of the plane y = 0) and its normal. */
static const vec3 ORIGIN = {0.0f, 0.0f, 0.0f};
static const vec3 UP = {0.0f, 1.0f, 0.0f};

/* Load scene text (OBJ paths relative to dir) and prepare it. */
static int load(struct scene *s, const char *text, const char *dir)
{
    return t_load_scene(s, text, "test_light", dir);
}

static struct ray make_ray(vec3 o, vec3 d, float tmax, float time)
{
    struct ray r;
    r.o = o;
    r.d = d;
    r.tmax = tmax;
    r.time = time;
    return r;
}

/* ---- the two irradiance estimators ---- */

struct est {
    double mean, se;
};

struct acc {
    double sum, sum2;
    long n;
};

static void acc_add(struct acc *a, double x)
{
    a->sum += x;
    a->sum2 += x * x;
    a->n++;
}

static struct est acc_est(const struct acc *a)
{
    struct est e;
    e.mean = a->sum / (double)a->n;
    e.se = sqrt(fmax(0.0, a->sum2 / (double)a->n - e.mean * e.mean) / (double)(a->n - 1));
    return e;
}

/* Light sampling: a light chosen by the scene's alias table, a direction from mc_light_sample,
 * and a shadow ray that stops short of the sampled point by 1e-4 of its distance (the sampled
 * point carries a relative error of a few 1e-7; nothing else lies that close to a light in these
 * scenes). Each term is L·cosθ·V/(pmf·pdf) (pdf 1 for a delta light). */
static struct est irradiance_light(const struct scene *s, vec3 p, vec3 n, float time, uint64_t seed)
{
    struct acc a;
    pcg32 g;
    long i;
    memset(&a, 0, sizeof a);
    pcg32_seed(&g, seed, 1);
    for (i = 0; i < N_IRR; i++) {
        struct light_sample ls;
        float pmf, c;
        double e = 0.0;
        int li = mc_alias_sample(&s->light_select.power, pcg32_double(&g), &pmf);
        vec2 u;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        if (li >= 0 && mc_light_sample(&s->light_scene, &s->lights[li], p, time, u, &ls)
            && (c = v3_dot(ls.wi, n)) > 0.0f) {
            struct ray r = make_ray(p, ls.wi, isinf(ls.dist) ? INFINITY : ls.dist * (1.0f - 1e-4f),
                                    time);
            if (!mc_scene_occluded(s, &r))
                e = (double)v3_avg(ls.L) * c / ((double)pmf * (ls.delta ? 1.0 : ls.pdf));
        }
        acc_add(&a, e);
    }
    return acc_est(&a);
}

/* Cosine-weighted hemisphere sampling about n: a term is π·Le of what the ray sees (cosθ/pdf = π),
 * the emitted radiance of the primitive it hits first or the environment's when it escapes. */
static struct est irradiance_bsdf(const struct scene *s, vec3 p, vec3 n, float time, uint64_t seed)
{
    struct acc a;
    frame f = frame_from_normal(n);
    pcg32 g;
    long i;
    memset(&a, 0, sizeof a);
    pcg32_seed(&g, seed, 2);
    for (i = 0; i < N_IRR; i++) {
        vec2 u;
        struct ray r;
        struct hit h;
        double e = 0.0;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        r = make_ray(p, frame_to_world(&f, mc_warp_cosine_hemisphere(u)), INFINITY, time);
        h.t = INFINITY;
        if (mc_scene_intersect(s, &r, &h)) {
            struct surface sf;
            mc_scene_surface(s, &r, &h, &sf);
            e = PI * v3_avg(mc_light_emitted(&s->prims[h.prim], &sf));
        } else if (s->env_light >= 0) {
            e = PI * v3_avg(mc_environment_radiance(&s->lights[s->env_light], r.d));
        }
        acc_add(&a, e);
    }
    return acc_est(&a);
}

/* The terms are float expressions, whose rounding (a few ulps) may shift a mean by ~1e-6 of its
 * value: that matters only for the estimators of zero variance (hemisphere sampling under a uniform
 * sky, or inside an emitting sphere), so 1e-5 of the value is added to the noise tolerance. */
#define ROUNDING 1e-5

static void check_agree(const char *what, struct est a, struct est b)
{
    double tol = 4.0 * sqrt(a.se * a.se + b.se * b.se) + ROUNDING * fabs(b.mean);
    T_NOTE("%s: light sampling %.5f ± %.5f, BSDF sampling %.5f ± %.5f (difference %.2f σ)", what,
           a.mean, a.se, b.mean, b.se, (a.mean - b.mean) / (tol / 4.0));
    T_NEAR(a.mean, b.mean, tol, "%s: light vs BSDF sampling", what);
}

static void check_exact(const char *what, const char *name, struct est a, double x)
{
    T_NOTE("%s: %s %.5f ± %.5f, exact %.5f (difference %.2g)", what, name, a.mean, a.se, x,
           a.mean - x);
    T_NEAR(a.mean, x, 4.0 * a.se + ROUNDING * x, "%s: %s vs exact", what, name);
}

/* At the origin at `time`: light sampling against BSDF sampling, and both against the exact
 * irradiance when it is known (exact >= 0). */
static void irradiance_case(const char *what, const struct scene *s, float time, double exact,
                            uint64_t seed)
{
    struct est l = irradiance_light(s, ORIGIN, UP, time, seed),
               b = irradiance_bsdf(s, ORIGIN, UP, time, seed);
    check_agree(what, l, b);
    if (exact >= 0.0) {
        check_exact(what, "light sampling", l, exact);
        check_exact(what, "BSDF sampling", b, exact);
    }
}

/* Lambert's formula (Arvo 1995, "Applications of Irradiance Tensors", eq. 3 ff.) for the
 * irradiance at p (normal n) from a polygon of radiance L wholly above p's horizon:
 * E = (L/2)·|Σ Θi·(n·γi)|, Θi the angle the edge (vi, vi+1) subtends at p and γi the unit normal
 * of the plane through p and that edge. In double. */
static double lambert_polygon(const vec3 *v, int nv, vec3 p, vec3 n, double L)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < nv; i++) {
        vec3 va = v[i], vb = v[(i + 1) % nv];
        double a[3] = {(double)va.x - p.x, (double)va.y - p.y, (double)va.z - p.z};
        double b[3] = {(double)vb.x - p.x, (double)vb.y - p.y, (double)vb.z - p.z};
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double theta = atan2(lc, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        sum += theta * (c[0] * n.x + c[1] * n.y + c[2] * n.z) / lc;
    }
    return 0.5 * L * fabs(sum);
}

/* A quad light tilted above the plane; then the same quad partly hidden by a black square. */
static void test_quad(void)
{
    struct scene s;
    vec3 v[4];
    if (!load(&s, QUAD, NULL))
        return;
    v[0] = s.prims[0].p[0];
    v[1] = v3_add(v[0], s.prims[0].p[1]);
    v[2] = v3_add(v[1], s.prims[0].p[2]);
    v[3] = v3_add(v[0], s.prims[0].p[2]);
    irradiance_case("quad", &s, 0.5f, lambert_polygon(v, 4, ORIGIN, UP, 4.0), 11);
    mc_scene_free(&s);

    if (!load(&s, QUAD "\nquad { corner -0.4 1 -0.3  edge1 0 0 0.5  edge2 0.6 0 0 }", NULL))
        return;
    irradiance_case("quad, partly occluded", &s, 0.5f, -1.0, 12);
    mc_scene_free(&s);
}

/* A disk facing the plane on its axis (exact: πL·r²/(r²+h²)), and a tilted disk off to the side. */
static void test_disk(void)
{
    struct scene s;
    const double L = 3.0, r = 1.5, h = 2.0;
    if (load(&s, "disk { center 0 2 0  normal 0 -1 0  radius 1.5  emit 3 }", NULL)) {
        irradiance_case("disk on its axis", &s, 0.5f, PI * L * r * r / (r * r + h * h), 21);
        mc_scene_free(&s);
    }
    if (load(&s, DISK, NULL)) {
        irradiance_case("tilted disk off the axis", &s, 0.5f, -1.0, 22);
        mc_scene_free(&s);
    }
}

static void test_triangle(void)
{
    struct scene s;
    if (!load(&s, TRIANGLE, NULL))
        return;
    irradiance_case("triangle", &s, 0.5f, lambert_polygon(s.prims[0].p, 3, ORIGIN, UP, 5.0), 31);
    mc_scene_free(&s);
}

/* ---- an emitting mesh ---- */

static char tmpdir[64];

/* Write the unit icosahedron (12 vertices (0, ±1, ±φ) and cyclic, normalised; 20 faces wound
 * counter-clockwise seen from outside; vn = the vertex position) to tmpdir/ico.obj. */
static int write_icosahedron(void)
{
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t},  {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    char path[128];
    FILE *fp;
    int i;
    snprintf(path, sizeof path, "%s/ico.obj", tmpdir);
    fp = fopen(path, "w");
    if (!fp)
        return 0;
    for (i = 0; i < 12; i++) {
        double l = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
        fprintf(fp, "v %.17g %.17g %.17g\nvn %.17g %.17g %.17g\n", v[i][0] / l, v[i][1] / l,
                v[i][2] / l, v[i][0] / l, v[i][1] / l, v[i][2] / l);
    }
    for (i = 0; i < 20; i++)
        fprintf(fp, "f %d//%d %d//%d %d//%d\n", f[i][0] + 1, f[i][0] + 1, f[i][1] + 1, f[i][1] + 1,
                f[i][2] + 1, f[i][2] + 1);
    return fclose(fp) == 0;
}

static void test_mesh(void)
{
    struct scene s;
    if (!load(&s, MESH, tmpdir))
        return;
    T_CHECK(s.prim_count == 20 && s.light_count == 20, "%zu prims, %zu lights", s.prim_count,
            s.light_count);
    irradiance_case("emitting mesh (20 triangles)", &s, 0.5f, -1.0, 41);
    mc_scene_free(&s);
}

/* Spheres: facing the centre, the irradiance is πL·(r/d)² for any d > r (the visible cap lies
 * above the horizon); from d = 1.02 r the cone is 157° wide. A sphere cut by the horizon has no
 * simple closed form. */
static void test_sphere(void)
{
    struct scene s;
    if (load(&s, "sphere { center 0 4 0  radius 1  emit 2 }", NULL)) {
        irradiance_case("sphere from afar (d = 4r)", &s, 0.5f, PI * 2.0 / 16.0, 51);
        mc_scene_free(&s);
    }
    if (load(&s, "sphere { center 0 1.02 0  radius 1  emit 2 }", NULL)) {
        irradiance_case("sphere close by (d = 1.02r)", &s, 0.5f, PI * 2.0 / (1.02 * 1.02), 52);
        mc_scene_free(&s);
    }
    if (load(&s, SPHERE_HORIZON, NULL)) {
        irradiance_case("sphere cut by the horizon", &s, 0.5f, -1.0, 53);
        mc_scene_free(&s);
    }
    /* Inside, where the sphere is sampled by area: it fills every direction, so E = πL. */
    if (load(&s, SPHERE_INSIDE, NULL)) {
        irradiance_case("inside a two-sided sphere (by area)", &s, 0.5f, PI * 2.0, 54);
        mc_scene_free(&s);
    }
}

/* The constant environment: πL on an open plane; then under a black square and beside a black
 * sphere. */
static void test_environment(void)
{
    struct scene s;
    if (load(&s, "environment { radiance 0.7 }", NULL)) {
        irradiance_case("environment", &s, 0.5f, PI * 0.7, 61);
        mc_scene_free(&s);
    }
    if (load(&s,
             "environment { radiance 0.7 }\n"
             "quad { corner -1 1 -1  edge1 0 0 2  edge2 1.5 0 0 }\n"
             "sphere { center 1.5 0.5 0  radius 0.7 }\n",
             NULL)) {
        irradiance_case("environment, partly occluded", &s, 0.5f, -1.0, 62);
        mc_scene_free(&s);
    }
}

/* Scene a at time ta and scene b at time tb hold the same emitters, possibly in another order:
 * each light of a samples, for the same u, the same point with the same pdf and radiance as the
 * light of b whose sample at u = (1/3, 1/3) is nearest. The geometry of the two differs by the
 * rounding of a float rigid map (a few ulps of coordinates below 5): points must agree to 1e-5,
 * pdfs to 1e-3 relative (measured: below 1e-4). */
static void same_samples(const char *what, const struct scene *a, float ta, const struct scene *b,
                         float tb)
{
    vec2 u0 = v2(1.0f / 3.0f, 1.0f / 3.0f);
    double worst_p = 0.0, worst_pdf = 0.0;
    size_t i, j;
    int k, n = 0, ok = a->light_count == b->light_count;
    for (i = 0; ok && i < a->light_count; i++) {
        struct light_sample la, lb;
        size_t best = 0;
        double best_d = INFINITY;
        if (!mc_light_sample(&a->light_scene, &a->lights[i], ORIGIN, ta, u0, &la))
            continue;
        for (j = 0; j < b->light_count; j++)
            if (mc_light_sample(&b->light_scene, &b->lights[j], ORIGIN, tb, u0, &lb)
                && v3_length(v3_sub(la.point, lb.point)) < best_d) {
                best_d = v3_length(v3_sub(la.point, lb.point));
                best = j;
            }
        for (k = 0; k < 64; k++) {
            vec2 u = v2((k % 8 + 0.5f) / 8.0f, (k / 8 + 0.5f) / 8.0f);
            int sa = mc_light_sample(&a->light_scene, &a->lights[i], ORIGIN, ta, u, &la),
                sb = mc_light_sample(&b->light_scene, &b->lights[best], ORIGIN, tb, u, &lb);
            if (!sa || !sb) {
                ok &= sa == sb;
                continue;
            }
            worst_p = fmax(worst_p, v3_length(v3_sub(la.point, lb.point)));
            worst_pdf = fmax(worst_pdf, fabs(la.pdf - lb.pdf) / lb.pdf);
            ok &= v3_length(v3_sub(la.wi, lb.wi)) < 1e-5f && v3_avg(la.L) == v3_avg(lb.L);
            n++;
        }
    }
    T_NOTE("%s: %d samples, largest distance %.2g, largest relative pdf difference %.2g", what, n,
           worst_p, worst_pdf);
    T_CHECK(ok && n > 0 && worst_p <= 1e-5 && worst_pdf <= 1e-3, "%s: samples differ", what);
}

/* Moving emitters at time 0.7. The sphere moves from (-1.4, 3, 0) to (0, 3, 0), where it faces the
 * point: exact πL/9. The moving quad samples as a static quad placed where it is then, and so does
 * a mesh spun by 60°·0.7 about its box centre as one rotated by 42°. */
static void test_moving(void)
{
    struct scene s, t;
    if (load(&s, MOVING_SPHERE, NULL)) {
        T_CHECK(s.motion_count == 1 && s.prims[0].motion == 1, "the sphere moves");
        irradiance_case("moving sphere", &s, 0.7f, PI * 2.0 / 9.0, 71);
        mc_scene_free(&s);
    }
    if (load(&s, MOVING_QUAD, NULL)) {
        if (load(&t, QUAD, NULL)) {
            same_samples("moving quad vs the static one", &s, 0.7f, &t, 0.0f);
            mc_scene_free(&t);
        }
        irradiance_case("moving quad", &s, 0.7f, -1.0, 73);
        mc_scene_free(&s);
    }
    if (load(&s, SPINNING_MESH, tmpdir)) {
        if (load(&t, ROTATED_MESH, tmpdir)) {
            same_samples("spinning mesh vs the static one", &s, 0.7f, &t, 0.0f);
            mc_scene_free(&t);
        }
        irradiance_case("spinning mesh", &s, 0.7f, -1.0, 75);
        mc_scene_free(&s);
    }
}

/* ---- the pdf of a direction, found as the integrator finds it ---- */

/* mc_light_pdf for direction w from p: the ray is traced, and when it first hits l's primitive,
 * or escapes for the environment, the pdf is asked for with that hit; else 0. */
static double pdf_along(const struct scene *s, const struct light *l, vec3 p, float time, vec3 w)
{
    struct ray r = make_ray(p, w, INFINITY, time);
    struct hit h;
    struct surface sf;
    h.t = INFINITY;
    if (!mc_scene_intersect(s, &r, &h))
        return l->kind == LIGHT_ENVIRONMENT
                   ? mc_light_pdf(&s->light_scene, l, p, time, w, INFINITY, NULL)
                   : 0.0;
    if (l->kind != LIGHT_AREA || h.prim != l->prim)
        return 0.0;
    mc_scene_surface(s, &r, &h, &sf);
    return mc_light_pdf(&s->light_scene, l, p, time, w, h.t, &sf);
}

/* What a chi-square test of one light needs: the scene (whose first light is tested), the shading
 * point and time, and for the test in directions a frame whose z points into the light. */
struct light_ctx {
    const struct scene *s;
    const struct light *l;
    vec3 p;
    float time;
    frame f;
};

static int sample_wi(const struct light_ctx *c, pcg32 *g, vec3 *wi)
{
    struct light_sample ls;
    vec2 u;
    u.x = pcg32_float(g);
    u.y = pcg32_float(g);
    if (!mc_light_sample(&c->s->light_scene, c->l, c->p, c->time, u, &ls))
        return 0;
    *wi = ls.wi;
    return 1;
}

static int dir_sample(void *ctx, pcg32 *g, vec3 *w)
{
    const struct light_ctx *c = (const struct light_ctx *)ctx;
    vec3 wi;
    if (!sample_wi(c, g, &wi))
        return 0;
    *w = frame_to_local(&c->f, wi);
    return 1;
}

static double dir_pdf(void *ctx, vec3 w)
{
    const struct light_ctx *c = (const struct light_ctx *)ctx;
    return pdf_along(c->s, c->l, c->p, c->time, v3_normalize(frame_to_world(&c->f, w)));
}

/* Quads and triangles are tested in coordinates of the square [0, 1]² on the light, to which a
 * direction is carried by tracing it: a quad's (s, t) along its edges, and for a triangle
 * x = b1 + b2, y = b2/(b1 + b2), the inverse of b1 = x(1 − y), b2 = x·y (Jacobian x). There the
 * light's rim is the domain's edge. In (θ, φ), by contrast, a straight edge runs along a circle
 * θ = const near its point closest to the axis, and where that happens within the outer 1/16 of
 * a row of cells, the cells' quadrature lattice (chi2.h) misses a lit sliver many cells long:
 * samples there count as strays and reject the test, at any resolution. The density at (x, y) is
 * mc_light_pdf of the direction to that point (traced as the integrator does) times the
 * Jacobian of direction by (x, y): cosθl/dist² · |e1 × e2| · (x for the triangle). A moving
 * light's point is carried to the world by its motion at the context's time. */
static int square_sample(void *ctx, pcg32 *g, double *x, double *y)
{
    const struct light_ctx *c = (const struct light_ctx *)ctx;
    struct ray r;
    struct hit h;
    vec3 wi;
    if (!sample_wi(c, g, &wi))
        return 0;
    r = make_ray(c->p, wi, INFINITY, c->time);
    h.t = INFINITY;
    if (!mc_scene_intersect(c->s, &r, &h) || h.prim != c->l->prim)
        return -1;
    if (c->s->prims[h.prim].kind == PRIM_QUAD) {
        *x = h.u;
        *y = h.v;
    } else {
        *x = (double)h.u + h.v;
        *y = *x > 0.0 ? h.v / *x : 0.0;
    }
    return 1;
}

static double square_density(void *ctx, double x, double y)
{
    const struct light_ctx *c = (const struct light_ctx *)ctx;
    const struct prim *pr = &c->s->prims[c->l->prim];
    int quad = pr->kind == PRIM_QUAD;
    vec3 e1 = quad ? pr->p[1] : v3_sub(pr->p[1], pr->p[0]);
    vec3 e2 = quad ? pr->p[2] : v3_sub(pr->p[2], pr->p[0]);
    float a = (float)(quad ? x : x * (1.0 - y)), b = (float)(quad ? y : x * y);
    vec3 q = v3_add(pr->p[0], v3_add(v3_scale(e1, a), v3_scale(e2, b))), n = v3_cross(e1, e2), w;
    double dist;
    if (pr->motion) {
        struct rigid m;
        mc_motion_at(&c->s->motions[pr->motion - 1], c->time, &m);
        q = rigid_point(&m, q);
        n = rigid_vector(&m, n);
    }
    w = v3_sub(q, c->p);
    dist = v3_length(w);
    w = v3_scale(w, (float)(1.0 / dist));
    return pdf_along(c->s, c->l, c->p, c->time, w) * fabs(v3_dot(n, w)) / (dist * dist)
           * (quad ? 1.0 : x);
}

/* Chi-square of the sampled directions of the scene's one light from the origin at `time`
 * against mc_light_pdf, with 10^6 samples: quads and triangles on the square (above, 40 × 40
 * cells), disks and spheres in (θ, φ) over the cone of half-angle theta_max about the direction to
 * `toward`, in 120 × 240 cells. A sphere's cone is the domain itself (theta_max is its
 * half-angle); a disk's rim has no straight stretch and crosses the rows of cells transversally. */
static void chi2_light(const char *name, const char *text, float time, vec3 toward,
                       double theta_max)
{
    struct scene s;
    struct light_ctx c;
    struct chi2_result r;
    if (!load(&s, text, NULL))
        return;
    c.s = &s;
    c.l = &s.lights[0];
    c.p = ORIGIN;
    c.time = time;
    c.f = frame_from_normal(v3_normalize(toward));
    if (s.prims[c.l->prim].kind == PRIM_QUAD || s.prims[c.l->prim].kind == PRIM_TRIANGLE) {
        struct chi2_spec q = chi2_unit_spec(name, square_sample, square_density, &c, 40);
        q.samples = 1000000;
        q.seed = 0x11647;
        q.tests = CHI2_TESTS;
        r = chi2_run(&q);
    } else {
        struct chi2_dir_spec d;
        d = chi2_dir_spec_of(name, dir_sample, dir_pdf, &c, theta_max);
        d.ntheta = 120;
        d.nphi = 240;
        d.samples = 1000000;
        d.seed = 0x11647;
        d.tests = CHI2_TESTS;
        r = chi2_run_directions(&d);
    }
    T_NOTE("chi2 %s: chi2 %.1f, dof %d, p %.3g, pdf integral %.6f, %ld draws without a sample",
           name, r.chi2, r.dof, r.p, r.integral, r.missing);
    T_CHECK(r.pass, "chi2 %s: %s", name, r.why);
    /* The whole light lies in the domain, so the pdf integrates to 1 up to the quadrature error
     * of the cells its rim crosses (measured below 1e-4 here), and every draw gave a sample. */
    T_NEAR(r.integral, 1.0, 1e-3, "%s: pdf integral", name);
    T_CHECK(r.missing == 0, "%s: %ld draws without a sample", name, r.missing);
    mc_scene_free(&s);
}

static void test_chi2(void)
{
    chi2_light("quad", QUAD, 0.5f, ORIGIN, 0.0);
    chi2_light("triangle", TRIANGLE, 0.5f, ORIGIN, 0.0);
    chi2_light("moving quad (t = 0.7)", MOVING_QUAD, 0.7f, ORIGIN, 0.0);
    /* Seen from the origin, the disk's rim is at most 25.3° off the direction to its centre. */
    chi2_light("disk", DISK, 0.5f, v3(1, 1.5f, 0.5f), 26.5 * PI / 180.0);
    /* Cones of half-angle asin(1/3) = 19.5° and asin(1/1.02) = 78.6°. */
    chi2_light("sphere (cone, d = 3r)", "sphere { center 0 3 0  radius 1  emit 2 }", 0.5f,
               v3(0, 3, 0), asin(1.0 / 3.0));
    chi2_light("sphere (cone, d = 1.02r)", "sphere { center 0 1.02 0  radius 1  emit 2 }", 0.5f,
               v3(0, 1, 0), asin(1.0 / 1.02));
    chi2_light("moving sphere (t = 0.7)", MOVING_SPHERE, 0.7f, v3(0, 3, 0), asin(1.0 / 3.0));
}

/* ---- MIS consistency: the pdf a sampled direction is later found with ---- */

/* For 10^5 draws over the scene's lights: the ray toward each sample first hits the light's
 * primitive at the sampled distance (to 1e-4), and mc_light_pdf there equals the pdf returned with
 * the sample (to 1e-3: both are float expressions of the same quantities, measured to agree within
 * 5e-5, and cosθ at the light loses relative precision only near grazing). A mesh sample may
 * legitimately fail when it lies within rounding of a silhouette edge that the ray grazes: the
 * rate measured over 10^6 draws of the mesh below is 4e-6; at most 1e-4 of them may. At least a
 * fifth of the draws give a sample (a convex emitter shows p a third of its area or more). */
static void mis_case(const char *what, const char *text, float time)
{
    const vec3 p = ORIGIN;
    struct scene s;
    pcg32 g;
    long i, n = 0, bad = 0;
    const long N = 100000;
    double worst = 0.0;
    if (!load(&s, text, tmpdir))
        return;
    pcg32_seed(&g, 0x6d6973, 3);
    for (i = 0; i < N; i++) {
        struct light_sample ls;
        float pmf;
        int li = mc_alias_sample(&s.light_select.power, pcg32_double(&g), &pmf);
        vec2 u;
        double q, rel;
        u.x = pcg32_float(&g);
        u.y = pcg32_float(&g);
        if (li < 0 || !mc_light_sample(&s.light_scene, &s.lights[li], p, time, u, &ls))
            continue;
        n++;
        if (s.lights[li].kind == LIGHT_AREA) {
            struct ray r = make_ray(p, ls.wi, INFINITY, time);
            struct hit h;
            h.t = INFINITY;
            if (!mc_scene_intersect(&s, &r, &h) || h.prim != s.lights[li].prim
                || fabs(h.t - ls.dist) > 1e-4 * ls.dist) {
                bad++;
                continue;
            }
        }
        q = pdf_along(&s, &s.lights[li], p, time, ls.wi);
        rel = fabs(q - ls.pdf) / ls.pdf;
        worst = fmax(worst, rel);
        bad += !(rel <= 1e-3);
    }
    T_NOTE("MIS pdf, %s: %ld samples, largest relative difference %.2e, %ld inconsistent", what, n,
           worst, bad);
    T_CHECK(n >= N / 5 && bad <= n / 10000, "%s: %ld of %ld samples inconsistent", what, bad, n);
    mc_scene_free(&s);
}

static void test_mis(void)
{
    mis_case("quad", QUAD, 0.5f);
    mis_case("disk", DISK, 0.5f);
    mis_case("triangle", TRIANGLE, 0.5f);
    mis_case("mesh", MESH, 0.5f);
    mis_case("sphere (cone)", SPHERE_HORIZON, 0.5f);
    mis_case("sphere (by area, from inside)", SPHERE_INSIDE, 0.5f);
    mis_case("environment", "environment { radiance 0.7 }", 0.5f);
    mis_case("moving quad", MOVING_QUAD, 0.7f);
    mis_case("spinning mesh", SPINNING_MESH, 0.7f);
}

/* ---- selection by power ---- */

/* Six lights of known power Φ (scalar: the mean over RGB). An area light radiating L from one side
 * of area A has Φ = π·A·L (twice that two-sided); a point light of intensity I, 4π·I. The table
 * must give each light its power over the total, and 4·10^6 draws must be distributed so
 * (chi-square, 5 degrees of freedom). */
static void test_selection(void)
{
    struct scene s;
    const double phi[6] = {
        PI * 2.0 * 3.0,                 /* quad 2 × 1, emit 3 */
        2.0 * PI * 1.0 * 1.0,           /* quad 1 × 1, emit 1, two-sided */
        PI * (PI * 0.25) * 2.0,         /* disk r = 0.5, emit 1 2 3 */
        PI * (4.0 * PI * 0.09) * 5.0,   /* sphere r = 0.3, emit 5 */
        PI * 0.5 * 4.0,                 /* triangle of area 0.5, emit 4 */
        4.0 * PI * 10.0                 /* point light, intensity 10 */
    };
    double total = 0.0, count[6] = {0}, chi2 = 0.0, p, alpha;
    const long N = 4000000;
    pcg32 g;
    long i;
    int k, ok = 1;
    if (!load(&s,
              "quad { corner 0 5 0  edge1 0 0 1  edge2 2 0 0  emit 3 }\n"
              "quad { corner 3 5 0  edge1 0 0 1  edge2 1 0 0  emit 1  two_sided }\n"
              "disk { center -2 5 0  normal 0 -1 0  radius 0.5  emit 1 2 3 }\n"
              "sphere { center 0 3 3  radius 0.3  emit 5 }\n"
              "triangle { v0 0 4 -2  v1 0 4 -3  v2 1 4 -2  emit 4 }\n"
              "point_light { position 0 6 0  intensity 10 }\n",
              NULL))
        return;
    T_CHECK(s.light_count == 6, "%zu lights", s.light_count);
    if (s.light_count != 6) {
        mc_scene_free(&s);
        return;
    }
    for (k = 0; k < 6; k++)
        total += phi[k];
    /* The point light comes first (parsed), then the area lights in primitive order, which the BVH
     * has permuted: identify each area light by its primitive's kind and flags. */
    for (k = 0; k < 6; k++) {
        const struct light *l = &s.lights[k];
        int which = 5;
        if (l->kind == LIGHT_AREA) {
            const struct prim *pr = &s.prims[l->prim];
            which = pr->kind == PRIM_QUAD ? ((pr->flags & PRIM_TWO_SIDED) ? 1 : 0)
                    : pr->kind == PRIM_DISK ? 2
                    : pr->kind == PRIM_SPHERE ? 3
                                              : 4;
        }
        T_NEAR(mc_light_power(&s.light_scene, l), phi[which], 1e-5 * phi[which],
               "power of light %d", which);
        T_NEAR(mc_alias_pmf(&s.light_select.power, (size_t)k), phi[which] / total, 1e-6,
               "selection probability of light %d", which);
        count[k] = 0.0;
    }
    pcg32_seed(&g, 0x616c6961, 4);
    for (i = 0; i < N; i++) {
        int li = mc_alias_sample(&s.light_select.power, pcg32_double(&g), NULL);
        if (li < 0 || li >= 6) {
            ok = 0;
            break;
        }
        count[li] += 1.0;
    }
    T_CHECK(ok, "alias sample out of range");
    for (k = 0; k < 6; k++) {
        double e = N * (double)mc_alias_pmf(&s.light_select.power, (size_t)k);
        chi2 += (count[k] - e) * (count[k] - e) / e;
    }
    p = chi2_p_value(chi2, 5);
    alpha = 1.0 - pow(1.0 - CHI2_SIGNIFICANCE, 1.0 / CHI2_TESTS);
    T_NOTE("selection by power: chi2 %.2f, dof 5, p %.3f", chi2, p);
    T_CHECK(p > alpha, "selection frequencies: chi2 %.2f, p %.3g <= %.3g", chi2, p, alpha);
    mc_scene_free(&s);
}

int main(void)
{
    char path[128];
    snprintf(tmpdir, sizeof tmpdir, "/tmp/mcrt-test-light-XXXXXX");
    if (!mkdtemp(tmpdir) || !write_icosahedron()) {
        T_CHECK(0, "cannot write the icosahedron under %s", tmpdir);
        return t_done();
    }
    test_quad();
    test_disk();
    test_triangle();
    test_mesh();
    test_sphere();
    test_environment();
    test_moving();
    test_chi2();
    test_mis();
    test_selection();
    snprintf(path, sizeof path, "%s/ico.obj", tmpdir);
    remove(path);
    rmdir(tmpdir);
    return t_done();
}
