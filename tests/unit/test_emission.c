/* test_emission.c: emission sampling (mc_light_sample_emission), which photon tracing starts
 * from, for every kind of light: point, area lights on quads, disks, triangles (and so mesh
 * triangles, which are triangle primitives), spheres, a two-sided and a moving emitter, and the
 * environment.
 *
 * For each: chi-square tests (tests/chi2.h) of the sampled directions against the claimed
 * pdf_dir and of the sampled points against pdf_pos; the pdfs returned with each sample equal the
 * closed forms the tests use (to 1e-4 relative: float expressions of the same quantities); each
 * ray's weight is Le·|cos|/(pdf_pos·pdf_dir) (to 1e-4), and the mean weight is the light's power
 * (mc_light_power; area and point lights carry exactly their power in every photon, so the
 * tolerance is float rounding, 1e-4 relative); rays leave the emitting side; the environment's
 * rays start outside the scene's bounding sphere and all cross it. */
#include <stdlib.h>
#include <string.h>

#include "chi2.h"
#include "sample/warp.h"
#include "scene_util.h"
#include "t.h"

#define CHI2_TESTS 12
#define SAMPLES 400000L

static const double PI = 3.14159265358979323846;

static int load(struct scene *s, const char *text) { return t_load_scene(s, text, "test_emission", NULL); }

/* What a chi-square test looks at: the light, the time, the frame that directions are measured
 * in, and which coordinate (direction, or point) is binned. */
enum what { DIRECTION, DIRECTION_LOCAL, POSITION_SPHERE, POSITION_POLAR, POSITION_SQUARE };
struct ctx {
    const struct scene *s;
    const struct light *l;
    float time;
    frame f;           /* DIRECTION: the frame of the emitter's front normal */
    double pdf_dir;    /* DIRECTION: the claimed constant (uniform) or 0: cos/π per side */
    int two_sided;
    enum what what;
    vec3 o, e1, e2;    /* POSITION_*: centre (or corner) and axes */
    float radius;
};

static int draw(const struct ctx *c, pcg32 *g, struct light_emission *e)
{
    vec2 up, ud;
    up.x = pcg32_float(g);
    up.y = pcg32_float(g);
    ud.x = pcg32_float(g);
    ud.y = pcg32_float(g);
    return mc_light_sample_emission(&c->s->light_scene, c->l, c->time, up, ud, e);
}

static int dir_sample(void *ctx, pcg32 *g, vec3 *w)
{
    const struct ctx *c = ctx;
    struct light_emission e;
    if (!draw(c, g, &e))
        return 0;
    if (c->what == DIRECTION_LOCAL) { /* in the frame of the sampled point's own normal */
        frame f = frame_from_normal(e.n);
        *w = frame_to_local(&f, e.d);
    } else if (c->what == POSITION_SPHERE) {
        *w = v3_normalize(v3_sub(e.p, c->o));
        *w = frame_to_local(&c->f, *w);
    } else {
        *w = frame_to_local(&c->f, e.d);
    }
    return 1;
}

static double dir_pdf(void *ctx, vec3 w)
{
    const struct ctx *c = ctx;
    if (c->what == POSITION_SPHERE)
        return 1.0 / (4.0 * PI);
    if (c->pdf_dir > 0.0)
        return c->pdf_dir;
    if (c->two_sided)
        return fabs(w.z) / (2.0 * PI);
    return w.z > 0.0f ? w.z / PI : 0.0;
}

/* Points on a disk as (ρ², φ/2π), uniform on the unit square when the point is; on a rectangle
 * as its (s, t) along perpendicular edges e1, e2. */
static int pos_sample(void *ctx, pcg32 *g, double *x, double *y)
{
    const struct ctx *c = ctx;
    struct light_emission e;
    vec3 q;
    if (!draw(c, g, &e))
        return 0;
    if (c->what == POSITION_SQUARE) {
        q = v3_sub(e.p, c->o);
        *x = v3_dot(q, c->e1) / v3_dot(c->e1, c->e1);
        *y = v3_dot(q, c->e2) / v3_dot(c->e2, c->e2);
    } else {
        /* The environment's disk is centred at centre + R·w, w = −d, normal to w; a disk
         * light's at its centre, normal to its normal (c->f). */
        frame f = c->f;
        vec3 o = c->o;
        double phi;
        if (c->l->kind == LIGHT_ENVIRONMENT) {
            vec3 w = v3_neg(e.d);
            o = v3_madd(c->s->light_scene.center, w, c->radius);
            f = frame_from_normal(w);
        }
        q = frame_to_local(&f, v3_sub(e.p, o));
        *x = ((double)q.x * q.x + (double)q.y * q.y) / ((double)c->radius * c->radius);
        phi = atan2((double)q.y, (double)q.x);
        *y = (phi < 0.0 ? phi + 2.0 * PI : phi) / (2.0 * PI);
        if (fabs(q.z) > 1e-4 * c->radius)
            return -1; /* not on the disk's plane */
    }
    return 1;
}

static double unit_density(void *ctx, double x, double y)
{
    (void)ctx, (void)x, (void)y;
    return 1.0;
}

static void report(const char *name, struct chi2_result r)
{
    T_NOTE("chi2 %s: chi2 %.1f, dof %d, p %.3g, pdf integral %.6f", name, r.chi2, r.dof, r.p,
           r.integral);
    T_CHECK(r.pass, "chi2 %s: %s", name, r.why);
    /* A cosine-weighted direction exactly on the horizon (u on the disk's rim, probability of
     * order 2^-24 per draw) has pdf 0 and gives no ray; nothing else may. */
    T_CHECK(r.missing <= SAMPLES / 100000, "%s: %ld draws without a ray", name, r.missing);
}

static void chi2_dirs(const char *name, struct ctx *c, enum what what)
{
    struct chi2_dir_spec d = chi2_dir_spec_of(name, dir_sample, dir_pdf, c, 0.0);
    c->what = what;
    d.samples = SAMPLES;
    d.seed = 0xe4155;
    d.tests = CHI2_TESTS;
    report(name, chi2_run_directions(&d));
}

static void chi2_points(const char *name, struct ctx *c, enum what what)
{
    struct chi2_spec q = chi2_unit_spec(name, pos_sample, unit_density, c, 40);
    c->what = what;
    q.samples = SAMPLES;
    q.seed = 0xe4156;
    q.tests = CHI2_TESTS;
    report(name, chi2_run(&q));
}

/* The pdfs and weight of every ray against the closed forms, the mean weight against the power,
 * and the side each ray leaves. pdf_pos_exact: 1/area (or 1/(πR²), 1 for a point light). */
static void check_rays(const char *name, const struct ctx *c, double pdf_pos_exact,
                       int check_power)
{
    pcg32 g;
    long i, bad_pdf = 0, bad_w = 0, bad_side = 0, bad_env = 0;
    const long N = 100000;
    double sum = 0.0, power = mc_light_power(&c->s->light_scene, c->l);
    pcg32_seed(&g, 0x9e3779b9, 7);
    for (i = 0; i < N; i++) {
        struct light_emission e;
        double cosn, pd, w;
        if (!draw(c, &g, &e)) {
            bad_pdf++;
            continue;
        }
        cosn = v3_is_zero(e.n) ? 1.0 : v3_dot(e.n, e.d);
        if (c->l->kind == LIGHT_AREA)
            pd = fabs(cosn) / PI / (c->two_sided ? 2.0 : 1.0);
        else
            pd = 1.0 / (4.0 * PI);
        if (fabs(e.pdf_dir - pd) > 1e-4 * pd + 1e-7 || fabs(e.pdf_pos - pdf_pos_exact) > 1e-4 * pdf_pos_exact)
            bad_pdf++;
        w = v3_avg(e.Le) * fabs(cosn) / (e.pdf_pos * e.pdf_dir);
        if (fabs(v3_avg(e.weight) - w) > 1e-4 * w)
            bad_w++;
        if (!(cosn > 0.0))
            bad_side++;
        if (c->l->kind == LIGHT_ENVIRONMENT) {
            /* Starts outside the bounding sphere (to rounding) and its line crosses it. */
            vec3 oc = v3_sub(e.p, c->s->light_scene.center);
            double R = c->s->light_scene.radius, b = v3_dot(oc, e.d);
            double closest2 = v3_dot(oc, oc) - b * b;
            if (v3_length(oc) < R * (1.0 - 1e-5) || b > 0.0 || closest2 > R * R * (1.0 + 1e-4))
                bad_env++;
        }
        sum += v3_avg(e.weight);
    }
    T_CHECK(bad_pdf <= N / 100000, "%s: %ld rays whose pdfs differ from the closed forms", name, bad_pdf);
    T_CHECK(bad_w == 0, "%s: %ld rays whose weight is not Le·|cos|/(pdf_pos·pdf_dir)", name, bad_w);
    T_CHECK(bad_side == 0, "%s: %ld rays leave against their normal", name, bad_side);
    T_CHECK(bad_env == 0, "%s: %ld environment rays miss the bounding sphere", name, bad_env);
    if (check_power)
        T_NEAR(sum / (double)N, power, 1e-4 * power, "%s: mean photon flux is the light's power",
               name);
}

static void test_point(void)
{
    struct scene s;
    struct ctx c;
    if (!load(&s, "point_light { position 0.3 1 -2  intensity 2 3 4 }"))
        return;
    memset(&c, 0, sizeof c);
    c.s = &s;
    c.l = &s.lights[0];
    c.f = frame_from_normal(v3(0, 0, 1));
    c.pdf_dir = 1.0 / (4.0 * PI);
    chi2_dirs("point: directions", &c, DIRECTION);
    check_rays("point", &c, 1.0, 1);
    mc_scene_free(&s);
}

/* A light whose primitive is the scene's only one. */
static int area_ctx(struct scene *s, struct ctx *c, const char *text, float time)
{
    if (!load(s, text))
        return 0;
    memset(c, 0, sizeof *c);
    c->s = s;
    c->l = &s->lights[0];
    c->time = time;
    c->two_sided = (s->prims[c->l->prim].flags & PRIM_TWO_SIDED) != 0;
    return 1;
}

static void test_quad(const char *name, const char *text, float time, vec3 corner_at_time)
{
    struct scene s;
    struct ctx c;
    const struct prim *pr;
    char what[96];
    vec3 n;
    if (!area_ctx(&s, &c, text, time))
        return;
    pr = &s.prims[c.l->prim];
    n = v3_normalize(v3_cross(pr->p[1], pr->p[2]));
    if (pr->flags & PRIM_FLIP)
        n = v3_neg(n);
    c.f = frame_from_normal(n);
    snprintf(what, sizeof what, "%s: directions", name);
    chi2_dirs(what, &c, DIRECTION);
    c.o = corner_at_time;
    c.e1 = pr->p[1];
    c.e2 = pr->p[2];
    snprintf(what, sizeof what, "%s: points", name);
    chi2_points(what, &c, POSITION_SQUARE);
    check_rays(name, &c, 1.0 / mc_prim_area(pr), 1);
    mc_scene_free(&s);
}

static void test_disk(void)
{
    struct scene s;
    struct ctx c;
    const struct prim *pr;
    if (!area_ctx(&s, &c, "disk { center 1 1.5 0.5  normal -0.3 -1 0.2  radius 0.8  emit 3  "
                          "two_sided }", 0.0f))
        return;
    pr = &s.prims[0];
    c.f = frame_from_normal(pr->p[1]);
    chi2_dirs("two-sided disk: directions", &c, DIRECTION);
    c.o = pr->p[0];
    c.radius = pr->p[2].x;
    chi2_points("two-sided disk: points", &c, POSITION_POLAR);
    check_rays("two-sided disk", &c, 1.0 / mc_prim_area(pr), 1);
    mc_scene_free(&s);
}

/* Triangles (mesh faces are triangle primitives): directions about the normal; points through
 * the barycentric map's inverse are left to test_light's area sampling, which shares
 * mc_prim_sample_area; here the mean flux and pdfs. */
static void test_triangle(void)
{
    struct scene s;
    struct ctx c;
    const struct prim *pr;
    if (!area_ctx(&s, &c, "triangle { v0 -1 2 -1  v1 1.5 1.5 0  v2 0 2.5 1  emit 5 }", 0.0f))
        return;
    pr = &s.prims[0];
    c.f = frame_from_normal(v3_normalize(v3_cross(v3_sub(pr->p[1], pr->p[0]),
                                                 v3_sub(pr->p[2], pr->p[0]))));
    chi2_dirs("triangle: directions", &c, DIRECTION);
    check_rays("triangle", &c, 1.0 / mc_prim_area(pr), 1);
    mc_scene_free(&s);
}

static void test_sphere(void)
{
    struct scene s;
    struct ctx c;
    const struct prim *pr;
    if (!area_ctx(&s, &c, "sphere { center 0.5 2 -1  radius 0.7  emit 2 1 3 }", 0.0f))
        return;
    pr = &s.prims[0];
    chi2_dirs("sphere: directions about the normal", &c, DIRECTION_LOCAL);
    c.o = pr->p[0];
    c.f = frame_from_normal(v3(0, 0, 1));
    chi2_dirs("sphere: points", &c, POSITION_SPHERE);
    check_rays("sphere", &c, 1.0 / mc_prim_area(pr), 1);
    mc_scene_free(&s);
}

static void test_environment(void)
{
    struct scene s;
    struct ctx c;
    if (!load(&s, "environment { radiance 0.5 1 2 }\n"
                  "sphere { center 3 0 1  radius 1 }\nquad { corner -2 -1 -1  edge1 1 0 0  "
                  "edge2 0 1 0 }"))
        return;
    memset(&c, 0, sizeof c);
    c.s = &s;
    c.l = &s.lights[s.env_light];
    c.f = frame_from_normal(v3(0, 0, 1));
    c.pdf_dir = 1.0 / (4.0 * PI);
    c.radius = s.light_scene.radius;
    chi2_dirs("environment: directions", &c, DIRECTION);
    chi2_points("environment: points on the disk", &c, POSITION_POLAR);
    check_rays("environment", &c, 1.0 / (PI * c.radius * c.radius), 0);
    mc_scene_free(&s);
}

int main(void)
{
    test_point();
    test_quad("quad", "quad { corner -1 2 -0.5  edge1 2 0 0  edge2 0 0 1.5  emit 4 }", 0.0f,
              v3(-1, 2, -0.5f));
    test_quad("flipped quad", "quad { corner -1 2 -0.5  edge1 2 0 0  edge2 0 0 1.5  emit 4  flip }",
              0.0f, v3(-1, 2, -0.5f));
    /* At time 0.5 the quad has moved by 0.5·(1 0 -2). */
    test_quad("moving quad (t = 0.5)",
              "quad { corner -1 2 -0.5  edge1 2 0 0  edge2 0 1.5 0  emit 4  move 1 0 -2 }", 0.5f,
              v3(-0.5f, 2, -1.5f));
    test_disk();
    test_triangle();
    test_sphere();
    test_environment();
    return t_done();
}
