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
 *   - one time per pass for camera rays and photons (pbrt-v4 #440): the emitting enclosure
 *     moving by 0.3 during the shutter still gives Le/(1 − ρ) (photons traced at another time
 *     than the visible points would land up to 0.3 off them, twice the radius);
 *   - --stats' two error parts, progress, cancellation, --target-error and --time; stiff cases
 *     (scaled and moved scenes, a tiny light, a furnace with glass, albedo 0.99); consistency
 *     on cornell and agreement with the path tracer on cornell-spheres (see each function). */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/rng.h"
#include "integrator/point_grid.h"
#include "file_util.h"
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
static double image_mean(const char *text, const char *integrator, int passes, uint64_t seed,
                         int threads)
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
    o.integrator = integrator;
    px = t_render(text, &o, &w, &h, NULL);
    if (!px)
        return NAN;
    n = (size_t)w * (size_t)h * 3;
    for (i = 0; i < n; i++)
        sum += px[i];
    free(px);
    return sum / (double)n;
}

static void closed_form_by(const char *integrator, const char *what, const char *text, int passes,
                           double exact)
{
    enum { K = 8 };
    double m[K], avg = 0.0, var = 0.0, se;
    int k;
    for (k = 0; k < K; k++) {
        m[k] = image_mean(text, integrator, passes, 1000 + (uint64_t)k, 2);
        avg += m[k] / K;
    }
    for (k = 0; k < K; k++)
        var += (m[k] - avg) * (m[k] - avg) / (K - 1);
    se = sqrt(var / K);
    T_NOTE("%s, %s: %d passes: mean %.5f ± %.5f (se), exact %.5f, relative error %.2e", what,
           integrator, passes, avg, se, exact, (avg - exact) / exact);
    if (se == 0.0) { /* every path gave the exact answer (as the path tracer does in glass) */
        T_CHECK(fabs(avg - exact) < 1e-5 * exact, "%s: mean %.7f without noise, exact %.7f",
                what, avg, exact);
        return;
    }
    T_CHECK(fabs(avg - exact) < 5.0 * se, "%s: mean %.5f, exact %.5f, se %.2e", what, avg, exact,
            se);
    /* The standard error must be a real one: not so large that the check means nothing (1% of
     * the value); zero only where no path has noise (above). */
    T_CHECK(se < 0.01 * exact, "%s: se %.2e", what, se);
}

static void closed_form(const char *what, const char *text, int passes, double exact)
{
    closed_form_by("sppm", what, text, passes, exact);
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
    closed_form("moving emitting sphere (one time per pass)",
                INSIDE_CAMERA "material grey { diffuse 0.8 }\n"
                              "sphere { radius 1  material grey  emit 0.5  flip  move 0.3 0 0 }\n"
                              "integrator { photons 3000  radius 0.15 }\n",
                32, 0.5 / (1.0 - 0.8));
    closed_form("emitting sphere, max_depth 3",
                INSIDE_CAMERA "material grey { diffuse 0.8 }\n"
                              "sphere { radius 1  material grey  emit 0.5  flip }\n"
                              "integrator { photons 3000  radius 0.15  max_depth 3 }\n",
                32, 0.5 * (1.0 + 0.8 + 0.64 + 0.512));
    /* Light tracing (the photons) and path tracing agree where both are exact: the camera
     * inside a glass sphere (radius 3, η = 1.5, lossless) around a white diffuse sphere, under a
     * sky of radiance 1. In equilibrium the radiance inside a lossless dielectric is η² times
     * the radiance outside (Veach 1997 §5.2: radiance/η² is what is conserved), so every pixel is
     * η² = 2.25. The camera path carries the 1/η² of the radiance-mode BTDF; the photons must
     * not (importance mode carries flux, and flux crosses the surface as T): with the radiance
     * mode's factor the photons would give 2.25² = 5.06, without any factor the path tracer 1.
     * The ball of radius r about a point of the sphere cuts exactly πr² of it (as inside), so
     * the photon estimate has no shape bias. */
    {
        static const char *const GLASS =
            "film { width 24 height 24 }\ncamera { eye 0 0 2.2  look 0 0 0  fov 40 }\n"
            "environment { radiance 1 }\nmaterial white { diffuse 1 }\n"
            "material glass { glass ior 1.5 }\n"
            "sphere { radius 3  material glass }\nsphere { radius 1  material white }\n"
            "integrator { photons 20000  radius 0.15 }\n";
        closed_form_by("sppm", "camera inside glass, white sphere in a white sky", GLASS, 32,
                       2.25);
        closed_form_by("path", "camera inside glass, white sphere in a white sky", GLASS, 32,
                       2.25);
    }
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

/* ---- statistics, budgets, progress and cancellation ---- */

struct prog {
    double last;
    int calls, decreasing, stop_after;
};

static int on_progress(void *user, double done)
{
    struct prog *p = user;
    p->decreasing += done < p->last;
    p->last = done;
    return ++p->calls == p->stop_after;
}

static mcrt_render *run(const char *text, int spp, double budget, double target, struct prog *p,
                        mcrt_status *st, mcrt_stats *stats)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r = NULL;
    mcrt_options o;
    *st = MCRT_ERR_INVALID;
    if (s && mcrt_scene_load_string(s, text, strlen(text), "test") == MCRT_OK) {
        mcrt_options_init(&o);
        o.spp = spp;
        o.integrator = "sppm";
        o.time_budget = budget;
        o.target_error = target;
        o.progress = p ? on_progress : NULL;
        o.user = p;
        r = mcrt_render_new(s, &o);
        if (r) {
            *st = mcrt_render_run(r);
            mcrt_render_stats(r, stats, sizeof *stats);
        }
    }
    mcrt_scene_free(s);
    return r;
}

#define ENCLOSURE                                                                              \
    INSIDE_CAMERA "material grey { diffuse 0.8 }\n"                                            \
                  "sphere { radius 1  material grey  emit 0.5  flip }\nintegrator { photons 3000 }\n"

static void test_stats_and_control(void)
{
    mcrt_stats st;
    mcrt_status status;
    struct prog p = {0.0, 0, 0, 0};
    mcrt_render *r = run(ENCLOSURE, 16, 0.0, 0.0, &p, &status, &st);
    T_CHECK(status == MCRT_OK && st.passes == 16, "16 passes: status %d, %d passes", status,
            st.passes);
    T_NEAR(st.est_relmse_bias2 + st.est_relmse_variance, st.est_relmse, 1e-6 * st.est_relmse,
           "the error's two parts add up to est_relmse");
    T_CHECK(st.est_relmse > 0.0 && st.est_relmse_variance > 0.0, "an error estimate (%g, %g)",
            st.est_relmse, st.est_relmse_variance);
    T_CHECK(p.calls > 0 && p.decreasing == 0 && p.last == 1.0,
            "progress: %d calls, %d decreasing, last %g", p.calls, p.decreasing, p.last);
    mcrt_render_free(r);
    /* Cancelled from the progress callback: MCRT_ERR_CANCELLED, the complete passes kept. */
    p.calls = p.decreasing = 0;
    p.last = 0.0;
    p.stop_after = 5;
    r = run(ENCLOSURE, 64, 0.0, 0.0, &p, &status, &st);
    T_CHECK(status == MCRT_ERR_CANCELLED && st.passes < 64, "cancelled: status %d, %d passes",
            status, st.passes);
    mcrt_render_free(r);
    /* A target error stops the passes once the estimate reaches it. */
    r = run(ENCLOSURE, 1, 0.0, 1e-4, NULL, &status, &st);
    T_NOTE("target 1e-4: %d passes, est relMSE %.3g", st.passes, st.est_relmse);
    T_CHECK(status == MCRT_OK && st.est_relmse <= 1e-4 && st.passes >= 2 && st.passes < 100000,
            "target error: %d passes, est %g", st.passes, st.est_relmse);
    mcrt_render_free(r);
    /* A time budget of 0.3 s ends the render (whatever the machine's load, it must end, with
     * at least one pass). */
    r = run(ENCLOSURE, 1, 0.3, 0.0, NULL, &status, &st);
    T_NOTE("time 0.3 s: %d passes in %.2f s", st.passes, st.seconds);
    T_CHECK(status == MCRT_OK && st.passes >= 1, "time budget: %d passes", st.passes);
    mcrt_render_free(r);
    {
        /* The path tracer has no parts. */
        struct t_render_opts o;
        int w, h;
        float *px;
        memset(&o, 0, sizeof o);
        o.spp = 4;
        o.integrator = "path";
        px = t_render(ENCLOSURE, &o, &w, &h, &st);
        T_CHECK(px && isnan(st.est_relmse_bias2) && isnan(st.est_relmse_variance),
                "path: no bias and variance parts");
        free(px);
    }
}

/* ---- stiff cases ---- */

/* The caustic box (glass and mirror spheres, a small light) with every length times `scale` and
 * moved by `offset` along (1 1 1). Its light hangs 0.1 below the ceiling (not cornell-spheres'
 * 0.01, which is about one float ulp at 1e5: there the light and the ceiling overlap and the path
 * tracer's image changes too). Radiance does not change with the units, and the default
 * radius follows the scene's size, so the images agree with the unit box's. */
static void caustic_box(char *buf, size_t size, double scale, double offset)
{
    const double k = scale, o = offset;
#define P3(x, y, z) (x) * k + o, (y) * k + o, (z) * k + o
#define V3(x, y, z) (x) * k, (y) * k, (z) * k
    snprintf(buf, size,
             "film { width 24 height 24 spp 4 }\n"
             "camera { eye %.9g %.9g %.9g  look %.9g %.9g %.9g  fov 40 }\n"
             "material white { diffuse 0.75 }\nmaterial mirror { mirror 0.95 }\n"
             "material glass { glass ior 1.5 }\n"
             "quad { corner %.9g %.9g %.9g  edge1 %.9g %.9g %.9g  edge2 %.9g %.9g %.9g  material white }\n"
             "quad { corner %.9g %.9g %.9g  edge1 %.9g %.9g %.9g  edge2 %.9g %.9g %.9g  material white }\n"
             "quad { corner %.9g %.9g %.9g  edge1 %.9g %.9g %.9g  edge2 %.9g %.9g %.9g  material white }\n"
             "quad { corner %.9g %.9g %.9g  edge1 %.9g %.9g %.9g  edge2 %.9g %.9g %.9g  emit 16 14 11 }\n"
             "sphere { center %.9g %.9g %.9g  radius %.9g  material mirror }\n"
             "sphere { center %.9g %.9g %.9g  radius %.9g  material glass }\n"
             "integrator { photons 4000 }\n",
             P3(0, 1, 3.9), P3(0, 1, 0), P3(-1, 0, 1), V3(2, 0, 0), V3(0, 0, -2), P3(-1, 2, -1),
             V3(2, 0, 0), V3(0, 0, 2), P3(-1, 0, -1), V3(2, 0, 0), V3(0, 2, 0), P3(-0.25, 1.9, -0.25),
             V3(0.5, 0, 0), V3(0, 0, 0.5), P3(-0.45, 0.38, -0.35), 0.38 * k, P3(0.45, 0.38, 0.3),
             0.38 * k);
#undef P3
#undef V3
}

static void test_stiff(void)
{
    static const double cases[][2] = {{1e-3, 0.0}, {1e3, 0.0}, {1.0, 1e5}};
    char text[2048];
    double base;
    int i;
    mcrt_stats st;
    struct t_render_opts o;
    int w, h;
    float *px;
    caustic_box(text, sizeof text, 1.0, 0.0);
    base = image_mean(text, "sppm", 16, 3, 2);
    for (i = 0; i < 3; i++) {
        double m;
        caustic_box(text, sizeof text, cases[i][0], cases[i][1]);
        m = image_mean(text, "sppm", 16, 3, 2);
        T_NOTE("caustic box x %g, moved %g: image mean %.5f (unit box %.5f)", cases[i][0],
               cases[i][1], m, base);
        /* The same random numbers on a scaled copy: only rounding differs, which changes a few
         * paths; the image means measured 0.03% apart scaled and 0.7% moved (whose float
         * positions lose 17 bits); 3% is outside that, and a radius that did not follow the
         * scale (0.36 in a box 0.002 wide, or 1e-4 in one 2000 wide) would be far off. */
        T_CHECK(isfinite(m) && fabs(m - base) < 0.03 * base, "scaled %g moved %g: %g vs %g",
                cases[i][0], cases[i][1], m, base);
    }
    /* A tiny, bright light (radius 1e-3, the same power as a radius 0.1 light of emission 10):
     * no NaN, a finite image. */
    memset(&o, 0, sizeof o);
    o.spp = 8;
    o.integrator = "sppm";
    px = t_render("film { width 24 height 24 }\ncamera { eye 0 1 3.9  look 0 1 0 }\n"
                  "quad { corner -1 0 1  edge1 2 0 0  edge2 0 0 -2 }\n"
                  "quad { corner -1 0 -1  edge1 2 0 0  edge2 0 2 0 }\n"
                  "sphere { center 0 1.5 0  radius 0.001  emit 1e5 }\n"
                  "material glass { glass }\nsphere { center 0.3 0.4 0.2  radius 0.3  material glass }\n",
                  &o, &w, &h, &st);
    T_CHECK(px && st.nan_count == 0, "tiny bright light: %s, %llu NaN", px ? "rendered" : "failed",
            px ? (unsigned long long)st.nan_count : 0ULL);
    if (px) {
        size_t k, bad = 0;
        for (k = 0; k < (size_t)w * (size_t)h * 3; k++)
            bad += !isfinite(px[k]) || px[k] < 0.0f;
        T_CHECK(bad == 0, "tiny bright light: %zu pixels not finite and >= 0", bad);
    }
    free(px);
    /* A white furnace (environment 1) with a white diffuse sphere beside a glass one: every
     * pixel is 1 (energy is conserved everywhere; the glass is lossless). */
    closed_form("white furnace with a glass sphere",
                "film { width 24 height 24 }\ncamera { eye 0 0 4  look 0 0 0  fov 50 }\n"
                "environment { radiance 1 }\nmaterial white { diffuse 1 }\n"
                "material glass { glass ior 1.5 }\n"
                "sphere { center -0.6 0 0  radius 0.5  material white }\n"
                "sphere { center 0.6 0 0  radius 0.5  material glass }\n"
                "integrator { photons 3000 }\n",
                32, 1.0);
    /* An enclosure of albedo 0.99: L = Le/(1 − 0.99) = 50 for Le = 0.5; paths of ~100 bounces. */
    closed_form("enclosure of albedo 0.99",
                INSIDE_CAMERA "material grey { diffuse 0.99 }\n"
                              "sphere { radius 1  material grey  emit 0.5  flip }\n"
                              "integrator { photons 2000  radius 0.15 }\n",
                16, 0.5 / (1.0 - 0.99));
}

/* ---- photons from behind ---- */

/* Photons that arrive on the other side of a surface that only reflects are not counted
 * (Mitsuba #145). Where the shading normal leans far from the geometric one they would not only
 * shrink the radius but add light: a square of two triangles (z = 0, facing +z) whose vertex
 * normals lean 60° towards +x, seen from the front; behind it, a point light and a diffuse wall
 * that sends the light back onto the square's back. Photons from the wall that arrive from
 * behind but above the shading normal's horizon would be given to the front's visible points
 * with a BSDF value above 0. Nothing lights the front (no sky; the light's shadow rays cross
 * the square), so every pixel must be exactly 0, for SPPM and for the path tracer. Without
 * path_vertex.h's through_surface (shadow rays toward the light behind spawned on the light's
 * side, reflected rays leaving through the square) 288 (sppm) and 543 (path) of the 768
 * channels were lit; without deposit's test all 768 (sppm). */
static void test_wrong_side(void)
{
    char dir[] = "/tmp/mcrt-test-sppm-XXXXXX", obj[64], text[1024];
    struct t_render_opts o;
    mcrt_stats st;
    int w, h, k;
    size_t i, lit;
    float *px;
    FILE *f;
    if (!mkdtemp(dir)) {
        T_CHECK(0, "cannot make a folder for the mesh");
        return;
    }
    snprintf(obj, sizeof obj, "%s/tilted.obj", dir);
    f = fopen(obj, "w");
    if (!f || fprintf(f, "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nvn 0.8660254 0 0.5\n"
                         "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n") < 0 || fclose(f) != 0) {
        T_CHECK(0, "cannot write %s", obj);
        return;
    }
    snprintf(text, sizeof text,
             "film { width 16 height 16 }\ncamera { eye 0 0 3  look 0 0 0  fov 40 }\n"
             "mesh { file \"%s\" }\n"
             "quad { corner -3 -3 -1  edge1 6 0 0  edge2 0 6 0 }\n"
             "point_light { position 0 0 -0.5  intensity 10 }\n"
             "integrator { photons 20000  radius 0.3 }\n", obj);
    for (k = 0; k < 2; k++) {
        memset(&o, 0, sizeof o);
        o.spp = 8;
        o.integrator = k ? "path" : "sppm";
        px = t_render(text, &o, &w, &h, &st);
        T_CHECK(px != NULL, "the scene renders");
        if (px) {
            for (i = 0, lit = 0; i < (size_t)w * (size_t)h * 3; i++)
                lit += px[i] != 0.0f;
            T_CHECK(lit == 0, "%s: light from behind: %zu of %zu pixel channels lit", o.integrator,
                    lit, (size_t)w * (size_t)h * 3);
        }
        free(px);
    }
    remove(obj);
    rmdir(dir);
}

/* ---- against the path tracer ---- */

/* Load a scene file with its film replaced by a w × h one (and `extra` appended). */
static char *scene_at(const char *path, int w, int h, const char *extra)
{
    char film[64];
    sprintf(film, "film { width %d height %d }", w, h);
    return t_scene_with_film(path, film, extra);
}

static float *render_with(const char *text, const char *integrator, int spp, uint64_t seed,
                          mcrt_stats *st)
{
    struct t_render_opts o;
    int w, h;
    memset(&o, 0, sizeof o);
    o.spp = spp;
    o.seed = seed;
    o.integrator = integrator;
    return t_render(text, &o, &w, &h, st);
}

static double relmse(const float *x, const float *ref, size_t n)
{
    size_t i;
    double sum = 0.0;
    for (i = 0; i < n; i++)
        sum += ((double)x[i] - ref[i]) * ((double)x[i] - ref[i]) / ((double)ref[i] * ref[i] + 0.01);
    return sum / (double)n;
}

/* Consistency on the Cornell box (24², default radius and photons): against a path-traced
 * reference of 2048 spp, SPPM's relMSE, less the reference's own estimated relMSE, falls from 16
 * to 64 to 256 passes with a log-log slope below −0.5 (the theory's −2/3 once variance and bias
 * shrink together; measured −1.2 here, where the large first radius's bias dominates early), and
 * the image's mean bias shrinks too. */
static void test_consistency(void)
{
    enum { W = 24, N = W * W * 3 };
    char *text = scene_at("scenes/cornell.mcrt", W, W, "");
    enum { P = 4, K = 4 };
    static const int passes[P] = {16, 64, 256, 1024};
    double e[P], bias[P], bias_se[P], lx = 0, ly = 0, lxx = 0, lxy = 0, slope;
    mcrt_stats rst;
    float *ref;
    int i;
    size_t j;
    if (!text) {
        T_CHECK(0, "cannot read scenes/cornell.mcrt");
        return;
    }
    ref = render_with(text, "path", 2048, 77, &rst);
    if (!ref) {
        T_CHECK(0, "reference render");
        free(text);
        return;
    }
    for (i = 0; i < P; i++) {
        double b[K], ss = 0.0;
        int k;
        e[i] = bias[i] = 0.0;
        for (k = 0; k < K; k++) {
            float *x = render_with(text, "sppm", passes[i], 5 + (uint64_t)k, NULL);
            if (!x)
                break;
            e[i] += (relmse(x, ref, N) - rst.est_relmse) / K;
            b[k] = 0.0;
            for (j = 0; j < N; j++)
                b[k] += ((double)x[j] - ref[j]) / N;
            bias[i] += b[k] / K;
            free(x);
        }
        if (k < K) {
            T_CHECK(0, "sppm render");
            break;
        }
        for (k = 0; k < K; k++)
            ss += (b[k] - bias[i]) * (b[k] - bias[i]) / (K - 1);
        bias_se[i] = sqrt(ss / K);
        T_NOTE("cornell %d²: %d passes: relMSE %.3e (reference's own %.2e subtracted), mean bias "
               "%.2e ± %.1e", W, passes[i], e[i], rst.est_relmse, bias[i], bias_se[i]);
        lx += log(passes[i]);
        ly += log(e[i] > 0 ? e[i] : 1e-30);
        lxx += log(passes[i]) * log(passes[i]);
        lxy += log(passes[i]) * log(e[i] > 0 ? e[i] : 1e-30);
    }
    if (i == P) {
        slope = (P * lxy - lx * ly) / (P * lxx - lx * lx);
        T_NOTE("cornell: log-log slope of relMSE against passes %.2f", slope);
        T_CHECK(slope < -0.5, "relMSE falls with passes: slope %.2f", slope);
        T_CHECK(e[0] > e[1] && e[1] > e[2] && e[2] > e[3], "relMSE falls at every step (%.2e %.2e "
                "%.2e %.2e)", e[0], e[1], e[2], e[3]);
        T_CHECK(fabs(bias[P - 1]) < fabs(bias[0]), "mean bias falls (%.2e to %.2e)", bias[0],
                bias[P - 1]);
    }
    free(ref);
    free(text);
}

/* The error estimate: on cornell (24²) and cornell-spheres (32², its caustics), for the random
 * sampler and the scene's (stratified, Sobol), the estimated relMSE within a factor 2 of the true
 * one at 64 and 256 passes, each the mean of 2 seeds; the truth is the relMSE against a
 * path-traced reference of 4096 spp (another seed) less that reference's own estimated relMSE.
 * Measured at 32², 4 seeds: 1.1–1.5 on cornell, 0.73–0.80 on cornell-spheres (sppm.c,
 * pixel_value); the successive differences it replaced read 2.0–2.6 on cornell's stratified
 * sampler, which this check fails. Against a reference of 2048 spp cornell-spheres read 0.59–0.72:
 * that reference's own error (the caustic's rare paths) is larger than its estimate says, so the
 * "truth" came out too high; at 4096 spp 0.73–0.82. */
static void error_estimate(const char *path, int W)
{
    enum { K = 2 };
    static const int passes[2] = {64, 256};
    static const char *const samplers[2] = {"random", NULL};
    size_t N = (size_t)W * (size_t)W * 3;
    char *text = scene_at(path, W, W, "");
    mcrt_stats rst, st;
    float *ref = text ? render_with(text, "path", 4096, 77, &rst) : NULL;
    int i, m, k;
    T_CHECK(ref != NULL, "%s: reference render", path);
    for (m = 0; ref && m < 2; m++)
        for (i = 0; i < 2; i++) {
            double est = 0.0, truth = 0.0;
            for (k = 0; k < K; k++) {
                struct t_render_opts o;
                int w, h;
                float *x;
                memset(&o, 0, sizeof o);
                o.spp = passes[i];
                o.seed = 11 + (uint64_t)k;
                o.integrator = "sppm";
                o.sampler = samplers[m];
                x = t_render(text, &o, &w, &h, &st);
                if (!x)
                    break;
                truth += (relmse(x, ref, N) - rst.est_relmse) / K;
                est += st.est_relmse / K;
                free(x);
            }
            T_NOTE("%s %d², %s sampler, %d passes: estimated relMSE %.3e, true %.3e: ratio %.2f",
                   path, W, samplers[m] ? samplers[m] : "the scene's", passes[i], est, truth,
                   est / truth);
            T_CHECK(k == K && est > 0.5 * truth && est < 2.0 * truth,
                    "%s: error estimate within 2x at %d passes: %.3e vs %.3e", path, passes[i],
                    est, truth);
        }
    free(ref);
    free(text);
}

/* Agreement on caustics: cornell-spheres at 32², SPPM (radius 0.04, 20000 photons, 64 passes)
 * and the path tracer (256 spp), K = 4 seeds each; the image in 16 blocks of 8 × 8 pixels, each
 * block's two means compared by z = Δ / sqrt(se_sppm² + se_path²), the standard errors from the
 * spread over the seeds. With 4 + 4 renders z is about Student's t with 6 degrees of freedom:
 * |z| < 6 fails with probability 0.001 per block, 0.016 over 16 blocks, for a correct
 * implementation; SPPM at the default radius of this small image (0.27) measured |z| = 7.7 in
 * the top corner (its bias of 8%), so the check sees a bias of that size. */
static void test_agreement(void)
{
    enum { W = 32, B = 8, K = 4, NB = (W / B) * (W / B) };
    char *sp = scene_at("scenes/cornell-spheres.mcrt", W, W,
                        "integrator { radius 0.04  photons 20000 }");
    double m[2][NB], m2[2][NB], zmax = 0.0;
    int e, k, b, worst = 0;
    if (!sp) {
        T_CHECK(0, "cannot read scenes/cornell-spheres.mcrt");
        return;
    }
    memset(m, 0, sizeof m);
    memset(m2, 0, sizeof m2);
    for (e = 0; e < 2; e++)
        for (k = 0; k < K; k++) {
            float *x = render_with(sp, e ? "path" : "sppm", e ? 256 : 64, 31 + (uint64_t)k, NULL);
            int px, py;
            if (!x) {
                T_CHECK(0, "render");
                free(sp);
                return;
            }
            for (b = 0; b < NB; b++) {
                double sum = 0.0;
                int bx = (b % (W / B)) * B, by = (b / (W / B)) * B;
                for (py = by; py < by + B; py++)
                    for (px = bx; px < bx + B; px++) {
                        const float *p = &x[((size_t)py * W + (size_t)px) * 3];
                        sum += ((double)p[0] + p[1] + p[2]) / (3.0 * B * B);
                    }
                m[e][b] += sum / K;
                m2[e][b] += sum * sum / K;
            }
            free(x);
        }
    for (b = 0; b < NB; b++) {
        double v0 = (m2[0][b] - m[0][b] * m[0][b]) * K / (K - 1) / K;
        double v1 = (m2[1][b] - m[1][b] * m[1][b]) * K / (K - 1) / K;
        double z = (m[0][b] - m[1][b]) / sqrt(v0 + v1);
        if (fabs(z) > zmax) {
            zmax = fabs(z);
            worst = b;
        }
    }
    T_NOTE("cornell-spheres %d²: largest |z| %.2f (block %d: sppm %.4f, path %.4f)", W, zmax,
           worst, m[0][worst], m[1][worst]);
    T_CHECK(zmax < 6.0, "sppm and path agree on every block: |z| %.2f at block %d", zmax, worst);
    free(sp);
}

int main(void)
{
    test_grid();
    test_closed_forms();
    test_determinism();
    test_stats_and_control();
    test_stiff();
    test_wrong_side();
    test_consistency();
    error_estimate("scenes/cornell.mcrt", 24);
    error_estimate("scenes/cornell-spheres.mcrt", 32);
    test_agreement();
    return t_done();
}
