/* test_select.c: light selection (light/select.h) on scenes of many lights of every kind: the
 * selection pmf sums to 1 over the lights at random points and normals (to 1e-9 for the tree,
 * whose pmf is a product of doubles; to 1e-6 for the power table's float pmfs); the pmf returned
 * with a sample equals mc_light_select_pmf exactly (the MIS weight of a BSDF sample that hits a
 * light uses the latter); the choices follow the pmf (chi-square); the tree never gives
 * probability 0 to a light that sends light to the point (its bounds are conservative); and on
 * 10^4 small emitting triangles the tree's next-event estimate of the irradiance on a floor has
 * the same mean as the power table's and a far smaller variance.
 *
 * Tolerances: the chi-square tests are at 0.01 Šidák-corrected over the CHI2_TESTS of this
 * binary. The means are compared at 4 standard errors (two-sided 6e-5 for a correct
 * implementation). The variance ratio must exceed 4: measured 8.5 (the note). */
#include <stdlib.h>
#include <string.h>

#include "chi2.h"
#include "scene_util.h"
#include "t.h"

#define CHI2_TESTS 3

static int load(struct scene *s, const char *text) { return t_load_scene(s, text, "test_select", NULL); }

static float uniform(pcg32 *g, float lo, float hi) { return lo + (hi - lo) * pcg32_float(g); }

static vec3 random_direction(pcg32 *g)
{
    float z = uniform(g, -1.0f, 1.0f), phi = uniform(g, 0.0f, 6.2831853f), r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return v3(r * cosf(phi), r * sinf(phi), z);
}

/* A scene of every kind of light: `tris` emitting triangles of random orientation (every third
 * two-sided) and brightness in a 6×3×6 box, quads, a disk, spheres (one inverted), a moving quad,
 * point lights and, when env, an environment. Returns malloc'd text. */
static char *many_lights(int tris, int env, uint64_t seed)
{
    size_t cap = 4096 + (size_t)tris * 200, len;
    char *t = malloc(cap);
    pcg32 g;
    int i;
    if (!t)
        return NULL;
    pcg32_seed(&g, seed, 7);
    len = (size_t)snprintf(t, cap,
                           "camera { shutter 0 1 }\n"
                           "quad { corner -1 4 -1 edge1 2 0 0 edge2 0 0 2 emit 3 }\n"
                           "quad { corner 2 1 2 edge1 0 1 0 edge2 0 0 1 emit 5 two_sided }\n"
                           "quad { corner -3 0 0 edge1 0 0 1 edge2 0 1 0 emit 2 move 0.5 0 0 }\n"
                           "disk { center 0 2 -3 normal 0 0 1 radius 0.5 emit 4 }\n"
                           "sphere { center 1 1 1 radius 0.3 emit 6 }\n"
                           "sphere { center 0 1 0 radius 5 emit 0.2 flip }\n"
                           "point_light { position 1 3 -1 intensity 20 }\n"
                           "point_light { position -2 0.5 2 intensity 4 }\n%s",
                           env ? "environment { radiance 0.5 }\n" : "");
    for (i = 0; i < tris; i++) {
        vec3 c = v3(uniform(&g, -3, 3), uniform(&g, 0, 3), uniform(&g, -3, 3));
        vec3 a = v3_scale(random_direction(&g), 0.2f), b = v3_scale(random_direction(&g), 0.2f);
        len += (size_t)snprintf(t + len, cap - len,
                                "triangle { v0 %g %g %g v1 %g %g %g v2 %g %g %g emit %g%s }\n", c.x,
                                c.y, c.z, c.x + a.x, c.y + a.y, c.z + a.z, c.x + b.x, c.y + b.y,
                                c.z + b.z, uniform(&g, 0.5f, 10.0f), i % 3 ? "" : " two_sided");
    }
    return t;
}

static void set_kind(struct scene *s, enum light_select_kind k) { s->light_select.kind = k; }

/* A choice and a pmf at p, n, each from a shading point of its own (light/select.h). */
static int sample_at(const struct light_select *ls, vec3 p, vec3 n, double u, double *pmf)
{
    struct light_select_at at;
    mc_light_select_at(&at, p, n);
    return mc_light_select_sample(ls, &at, u, pmf);
}
static double pmf_at(const struct light_select *ls, vec3 p, vec3 n, int light)
{
    struct light_select_at at;
    mc_light_select_at(&at, p, n);
    return mc_light_select_pmf(ls, &at, light);
}

/* Sum of the pmf over every light at 300 random points (in and around the lights' box) with random
 * normals (a tenth zero), and whether each sample's pmf equals mc_light_select_pmf bit for bit,
 * both from a fresh shading point and from the one the sample chose at (as the path tracer asks:
 * its top computed by the sample, light/select.h). */
static void test_sums(const char *what, int env)
{
    char *text = many_lights(300, env, 11);
    struct scene s;
    pcg32 g;
    int k, i, kind;
    if (!text || !load(&s, text)) {
        free(text);
        return;
    }
    free(text);
    pcg32_seed(&g, 0x73756d, 1);
    for (kind = 0; kind < LIGHT_SELECT_COUNT; kind++) {
        double worst = 0.0, tol = kind == LIGHT_SELECT_TREE ? 1e-9 : 1e-6;
        long mismatched = 0, chosen = 0;
        set_kind(&s, (enum light_select_kind)kind);
        for (k = 0; k < 300; k++) {
            vec3 p = v3(uniform(&g, -8, 8), uniform(&g, -2, 6), uniform(&g, -8, 8));
            vec3 n = k % 10 ? random_direction(&g) : v3s(0.0f);
            double sum = 0.0;
            for (i = 0; i < (int)s.light_count; i++)
                sum += pmf_at(&s.light_select, p, n, i);
            if (fabs(sum - 1.0) > worst)
                worst = fabs(sum - 1.0);
            for (i = 0; i < 20; i++) {
                struct light_select_at at;
                double pmf;
                int li;
                mc_light_select_at(&at, p, n);
                li = mc_light_select_sample(&s.light_select, &at, pcg32_double(&g), &pmf);
                chosen += li >= 0;
                mismatched += li < 0 || !(pmf > 0.0) || pmf != pmf_at(&s.light_select, p, n, li)
                              || pmf != mc_light_select_pmf(&s.light_select, &at, li);
            }
        }
        T_NOTE("%s, %s: largest |sum of pmf - 1| over 300 points %.2e", what, mc_light_select_names[kind],
               worst);
        T_CHECK(worst <= tol, "%s, %s: the pmf sums to 1 within %.1e (%.2e)", what,
                mc_light_select_names[kind], tol, worst);
        T_CHECK(mismatched == 0, "%s, %s: %ld of %ld samples' pmf differ from mc_light_select_pmf",
                what, mc_light_select_names[kind], mismatched, chosen);
    }
    mc_scene_free(&s);
}

/* 10^6 choices at each of three points against N·pmf per light (cells expecting under 5 pooled). */
static void test_chi2(void)
{
    static const float pts[3][6] = {{0, 0, 0, 0, 1, 0}, {2.5f, 1.2f, 2.5f, -1, 0, 0}, {7, 1, -6, 0.6f, 0.8f, 0}};
    char *text = many_lights(60, 1, 12);
    struct scene s;
    double *count, alpha = 1.0 - pow(1.0 - CHI2_SIGNIFICANCE, 1.0 / CHI2_TESTS);
    const long N = 1000000;
    int k;
    if (!text || !load(&s, text)) {
        free(text);
        return;
    }
    free(text);
    count = calloc(s.light_count, sizeof *count);
    for (k = 0; k < 3 && count; k++) {
        vec3 p = v3(pts[k][0], pts[k][1], pts[k][2]), n = v3(pts[k][3], pts[k][4], pts[k][5]);
        double chi2 = 0.0, pool_e = 0.0, pool_o = 0.0, pv;
        long i, none = 0;
        int dof = -1;
        pcg32 g;
        size_t j;
        pcg32_seed(&g, 0x636869, (uint64_t)k);
        memset(count, 0, s.light_count * sizeof *count);
        for (i = 0; i < N; i++) {
            double pmf;
            int li = sample_at(&s.light_select, p, n, pcg32_double(&g), &pmf);
            if (li < 0)
                none++;
            else
                count[li] += 1.0;
        }
        for (j = 0; j < s.light_count; j++) {
            double e = N * pmf_at(&s.light_select, p, n, (int)j);
            if (e < 5.0) {
                pool_e += e;
                pool_o += count[j];
                continue;
            }
            chi2 += (count[j] - e) * (count[j] - e) / e;
            dof++;
        }
        if (pool_e >= 5.0) {
            chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            dof++;
        }
        pv = dof > 0 ? chi2_p_value(chi2, dof) : 0.0;
        T_NOTE("tree selection at point %d: chi2 %.1f, dof %d, p %.3f", k, chi2, dof, pv);
        T_CHECK(none == 0 && dof > 0 && pv > alpha, "point %d: chi2 %.1f dof %d p %.3g <= %.3g, %ld none",
                k, chi2, dof, pv, alpha, none);
    }
    free(count);
    mc_scene_free(&s);
}

/* For random points and normals and every static light, a random point on the light that sends
 * light toward p and arrives at a cosine above 1e-3: the light's pmf there must be positive. */
static void test_conservative(void)
{
    char *text = many_lights(300, 0, 13);
    struct scene s;
    pcg32 g;
    long tried = 0, zero = 0;
    int k;
    size_t i;
    if (!text || !load(&s, text)) {
        free(text);
        return;
    }
    free(text);
    pcg32_seed(&g, 0x636f6e, 2);
    for (k = 0; k < 2000; k++) {
        vec3 p = v3(uniform(&g, -6, 6), uniform(&g, -1, 5), uniform(&g, -6, 6)), n = random_direction(&g);
        for (i = 0; i < s.light_count; i++) {
            const struct light *l = &s.lights[i];
            vec3 q, nq = v3s(0.0f), w;
            if (l->kind == LIGHT_POINT)
                q = l->position;
            else if (l->kind == LIGHT_AREA && !s.prims[l->prim].motion) {
                const struct prim *pr = &s.prims[l->prim];
                q = mc_prim_sample_area(pr, v2(pcg32_float(&g), pcg32_float(&g)), &nq);
                if (!(pr->flags & PRIM_TWO_SIDED) && !(v3_dot(nq, v3_sub(p, q)) > 1e-3f * v3_length(v3_sub(p, q))))
                    continue;
            } else
                continue;
            w = v3_normalize(v3_sub(q, p));
            if (!(fabsf(v3_dot(w, n)) > 1e-3f))
                continue;
            tried++;
            zero += !(pmf_at(&s.light_select, p, n, (int)i) > 0.0);
        }
    }
    T_NOTE("conservative bounds: %ld (point, light) pairs that receive light, %ld with pmf 0", tried, zero);
    T_CHECK(tried > 100000 && zero == 0, "%ld of %ld lit pairs have pmf 0", zero, tried);
    mc_scene_free(&s);
}

/* Next-event estimate of the irradiance at p (normal n), ignoring occlusion: L·cos θ / (pmf·pdf). */
static double nee(const struct scene *s, vec3 p, vec3 n, pcg32 *g)
{
    struct light_sample ls;
    double pmf;
    int li = sample_at(&s->light_select, p, n, pcg32_double(g), &pmf);
    vec2 u;
    u.x = pcg32_float(g);
    u.y = pcg32_float(g);
    if (li < 0 || !mc_light_sample(&s->light_scene, &s->lights[li], p, 0.0f, u, &ls))
        return 0.0;
    return v3_avg(ls.L) * fmax(0.0, v3_dot(ls.wi, n)) / (pmf * ls.pdf);
}

/* 10^4 triangles of side 0.1 scattered 1 to 3 above a 40×40 floor, facing down: at 16 floor points,
 * 20000 samples each by both strategies. */
static void test_many(void)
{
    const int T = 10000, P = 16, N = 20000;
    size_t cap = (size_t)T * 160 + 64, len = 0;
    char *text = malloc(cap);
    struct scene s;
    pcg32 g;
    int i, k, kind;
    double var[LIGHT_SELECT_COUNT] = {0.0, 0.0}, worst_z = 0.0;
    if (!text)
        return;
    pcg32_seed(&g, 0x6d616e79, 3);
    for (i = 0; i < T; i++) {
        float x = uniform(&g, -20, 20), y = uniform(&g, 1, 3), z = uniform(&g, -20, 20);
        len += (size_t)snprintf(text + len, cap - len,
                                "triangle { v0 %g %g %g v1 %g %g %g v2 %g %g %g emit %g }\n", x, y, z,
                                x + 0.1, y, z, x, y, z + 0.1, uniform(&g, 1, 4));
    }
    if (!load(&s, text)) {
        free(text);
        return;
    }
    free(text);
    for (k = 0; k < P; k++) {
        vec3 p = v3(uniform(&g, -18, 18), 0.0f, uniform(&g, -18, 18)), n = v3(0, 1, 0);
        double mean[LIGHT_SELECT_COUNT], se2[LIGHT_SELECT_COUNT], z;
        for (kind = 0; kind < LIGHT_SELECT_COUNT; kind++) {
            double sum = 0.0, sum2 = 0.0;
            set_kind(&s, (enum light_select_kind)kind);
            for (i = 0; i < N; i++) {
                double e = nee(&s, p, n, &g);
                sum += e;
                sum2 += e * e;
            }
            mean[kind] = sum / N;
            se2[kind] = fmax(0.0, sum2 / N - mean[kind] * mean[kind]) / (N - 1);
            var[kind] += se2[kind] * N;
        }
        z = fabs(mean[0] - mean[1]) / sqrt(se2[0] + se2[1]);
        worst_z = fmax(worst_z, z);
    }
    T_NOTE("10^4 triangles, %d points x %d samples: variance power / tree = %.1f; worst |z| of the means %.2f",
           P, N, var[LIGHT_SELECT_POWER] / var[LIGHT_SELECT_TREE], worst_z);
    T_CHECK(worst_z < 4.0, "tree and power means differ: |z| %.2f", worst_z);
    T_CHECK(var[LIGHT_SELECT_POWER] > 4.0 * var[LIGHT_SELECT_TREE],
            "tree variance %.3g not below a quarter of power's %.3g", var[LIGHT_SELECT_TREE],
            var[LIGHT_SELECT_POWER]);
    mc_scene_free(&s);
}

int main(void)
{
    test_sums("with an environment", 1);
    test_sums("without", 0);
    test_chi2();
    test_conservative();
    test_many();
    return t_done();
}
