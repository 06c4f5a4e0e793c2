/* test_strategies.c: the path tracer's ways of finding light (integrator strategy mis, bsdf,
 * light) estimate the same image, and MIS earns its keep (Veach 1997, ch. 9): at equal spp it has
 * the lowest error on a glossy scene, where each single strategy fails somewhere (BSDF sampling
 * under a tiny bright light, light sampling on near-mirror lobes under a large one), and light
 * sampling beats BSDF sampling under a small light.
 *
 * Agreement: on a scene every strategy handles (large lights), 8×8 blocks of the difference of two
 * independent renders, |z| ≤ 4.5 per block (p = 6.8e-6 each; 2 × 64 blocks: family-wise < 1e-3,
 * Šidák).
 * Error: relMSE against a 1024-spp MIS reference with another seed, mean over pixels and channels
 * of (x − ref)²/(ref² + 0.01). Single strategies leave fireflies, whose heavy tail makes a standard
 * error from the pixel spread meaningless, so the ordering is a rank test instead: eight renders
 * per strategy with different seeds, and a one-sided Mann-Whitney test (Mann and Whitney 1947)
 * of the worse strategy's errors above the better one's at p < 0.001 (its exact null
 * distribution: at most 4 of the 64 pairs inverted). MIS's own errors have that tail too: on the
 * glossy scene, 40 seeds at 32 spp ranged 0.0030 to 0.032 (median 0.0036), and seeds 1-8 put
 * one MIS render (0.019) above one light-only render (0.016), which complete separation of the
 * renders, the test before (5 seeds), would have failed. */
#include <math.h>
#include <stdlib.h>

#include "render_util.h"
#include "t.h"

/* Veach's MIS test in miniature (Veach 1997, fig. 9.2): glossy surfaces of several roughnesses
 * under a tiny bright light and a large dim one, direct lighting only (max_depth 1), so that the
 * comparison is between the two ways of sampling the same integral, without caustic paths that
 * no unidirectional strategy samples well. */
static const char glossy[] =
    "film { width 64 height 48 }\ncamera { eye 0 1.2 4.5 look 0 0.4 0 fov 40 }\n"
    "integrator { max_depth 1 }\n"
    "material a { metal 0.9 roughness 0.08 }\nmaterial b { metal 0.9 0.7 0.4 roughness 0.35 }\n"
    "material c { plastic 0.2 0.3 0.7 roughness 0.6 }\n"
    "sphere { center -1.1 0.45 0 radius 0.45 material a }\n"
    "sphere { center 0 0.45 0 radius 0.45 material b }\n"
    "sphere { center 1.1 0.45 0 radius 0.45 material c }\n"
    "quad { corner -5 0 5 edge1 10 0 0 edge2 0 0 -10 }\n"
    "sphere { center -1.5 2.5 1 radius 0.08 emit 300 }\n"
    "quad { corner 1 3 -1.5 edge1 2.5 0 0 edge2 0 0 2.5 emit 3 }\n"
    "environment { radiance 0.05 }\n";

/* Large, dim lights only: BSDF sampling finds them often enough for a z-test on its mean. */
static const char broad[] =
    "film { width 64 height 48 }\ncamera { eye 0 1.2 4.5 look 0 0.4 0 fov 40 }\n"
    "material b { metal 0.9 0.7 0.4 roughness 0.35 }\nmaterial c { plastic 0.2 0.3 0.7 roughness 0.6 }\n"
    "sphere { center -0.6 0.45 0 radius 0.45 material b }\n"
    "sphere { center 0.6 0.45 0 radius 0.45 material c }\n"
    "quad { corner -5 0 5 edge1 10 0 0 edge2 0 0 -10 }\n"
    "quad { corner -2 3 -2 edge1 4 0 0 edge2 0 0 4 emit 2 }\n"
    "environment { radiance 0.3 }\n";

static const char small_light[] =
    "film { width 64 height 48 }\ncamera { eye 0 2 4 look 0 0 0 fov 45 }\n"
    "quad { corner -4 0 4 edge1 8 0 0 edge2 0 0 -8 }\n"
    "sphere { center 0.3 0.5 0 radius 0.3 }\n"
    "sphere { center -0.5 1.5 0.5 radius 0.05 emit 400 }\n";

static float *render(const char *text, const char *integrator, int spp, uint64_t seed, int *w, int *h)
{
    struct t_render_opts o = {0, 2, 0, 0, NULL, NULL};
    o.spp = spp;
    o.seed = seed;
    o.integrator = integrator;
    return t_render(text, &o, w, h, NULL);
}

/* relMSE of x against ref over n pixels, and its standard error. */
static void rel_mse(const float *x, const float *ref, int n, double *mean, double *se)
{
    double sum = 0.0, sum2 = 0.0;
    int i, c;
    for (i = 0; i < n; i++) {
        double e = 0.0;
        for (c = 0; c < 3; c++) {
            double d = (double)x[3 * i + c] - ref[3 * i + c], r = ref[3 * i + c];
            e += d * d / (r * r + 0.01) / 3.0;
        }
        sum += e;
        sum2 += e * e;
    }
    *mean = sum / n;
    *se = sqrt(fmax(0.0, sum2 / n - *mean * *mean) / (n - 1));
}

/* Worst 8×8-block |z| of a − b (green channel). */
static double worst_block_z(const float *a, const float *b, int w, int h)
{
    double worst = 0.0;
    int bx, by, x, y;
    for (by = 0; by < 8; by++)
        for (bx = 0; bx < 8; bx++) {
            double sum = 0.0, sum2 = 0.0, m, se;
            int n = 0;
            for (y = by * h / 8; y < (by + 1) * h / 8; y++)
                for (x = bx * w / 8; x < (bx + 1) * w / 8; x++) {
                    double d = (double)a[3 * (y * w + x) + 1] - b[3 * (y * w + x) + 1];
                    sum += d;
                    sum2 += d * d;
                    n++;
                }
            m = sum / n;
            se = sqrt(fmax(0.0, sum2 / n - m * m) / (n - 1));
            if (se > 0.0 && fabs(m) / se > worst)
                worst = fabs(m) / se;
        }
    return worst;
}

static const char *const names[] = {"mis", "bsdf", "light"};

enum { SEEDS = 8 };

/* relMSE of strategy `name` at spp for SEEDS seeds, into e; its smallest and largest. */
static int errors(const char *text, const float *ref, const char *name, int spp, double e[SEEDS],
                  double *lo, double *hi)
{
    int s, w, h;
    *lo = INFINITY;
    *hi = 0.0;
    for (s = 0; s < SEEDS; s++) {
        double se;
        float *img = render(text, name, spp, (uint64_t)(1 + s), &w, &h);
        if (!img)
            return 0;
        rel_mse(img, ref, w * h, &e[s], &se);
        *lo = fmin(*lo, e[s]);
        *hi = fmax(*hi, e[s]);
        free(img);
    }
    return 1;
}

/* The one-sided Mann-Whitney test that b's values lie above a's (SEEDS each): U, the pairs with
 * a_i >= b_j, and P(U <= u) if both came from one continuous distribution, exactly: the count of
 * the C(2·SEEDS, SEEDS) orderings with U <= u, by the recurrence on the largest of all values
 * (it is an a, adding the j b's below it to U, or a b, adding nothing). */
static double mann_whitney_p(const double a[SEEDS], const double b[SEEDS], int *u)
{
    enum { N = SEEDS, MAXU = SEEDS * SEEDS };
    static double c[N + 1][N + 1][MAXU + 1];
    double below = 0.0, all = 0.0;
    int i, j, k;
    for (*u = 0, i = 0; i < N; i++)
        for (j = 0; j < N; j++)
            *u += a[i] >= b[j];
    for (i = 0; i <= N; i++)
        for (j = 0; j <= N; j++)
            for (k = 0; k <= MAXU; k++)
                c[i][j][k] = i == 0 || j == 0 ? (k == 0)
                                              : (k >= j ? c[i - 1][j][k - j] : 0.0) + c[i][j - 1][k];
    for (k = 0; k <= MAXU; k++) {
        all += c[N][N][k];
        below += k <= *u ? c[N][N][k] : 0.0;
    }
    return below / all;
}

static void test_agreement(void)
{
    int w, h, i;
    float *img[3];
    for (i = 0; i < 3; i++)
        img[i] = render(broad, names[i], 256, (uint64_t)(10 + i), &w, &h);
    T_CHECK(img[0] && img[1] && img[2], "rendered");
    for (i = 1; i < 3 && img[0] && img[1] && img[2]; i++) {
        double z = worst_block_z(img[i], img[0], w, h);
        T_CHECK(z <= 4.5, "%s vs mis: worst block |z| %.2f (limit 4.5)", names[i], z);
        T_NOTE("broad lights, 256 spp: %s vs mis, worst block |z| = %.2f", names[i], z);
    }
    for (i = 0; i < 3; i++)
        free(img[i]);
}

static void test_glossy(void)
{
    int w, h, i;
    float *ref = render(glossy, "mis", 1024, 99, &w, &h);
    double lo[3], hi[3], e[3][SEEDS];
    T_CHECK(ref != NULL, "reference");
    if (!ref)
        return;
    for (i = 0; i < 3; i++) {
        T_CHECK(errors(glossy, ref, names[i], 32, e[i], &lo[i], &hi[i]), "%s rendered", names[i]);
        T_NOTE("glossy scene, 32 spp, %d seeds: %-5s relMSE %.3e .. %.3e", SEEDS, names[i], lo[i],
               hi[i]);
    }
    for (i = 1; i < 3; i++) {
        int u;
        double p = mann_whitney_p(e[0], e[i], &u);
        T_CHECK(p < 1e-3, "MIS not below %s: %d of %d pairs inverted, p = %.2g (limit 0.001)",
                names[i], u, SEEDS * SEEDS, p);
        T_NOTE("glossy scene: MIS below %s, %d of %d pairs inverted, p = %.2g", names[i], u,
               SEEDS * SEEDS, p);
    }
    free(ref);
}

static void test_small_light(void)
{
    int w, h;
    float *ref = render(small_light, "mis", 1024, 99, &w, &h);
    double llo, lhi, blo, bhi, le[SEEDS], be[SEEDS], p;
    int u;
    T_CHECK(ref != NULL, "reference");
    if (!ref)
        return;
    T_CHECK(errors(small_light, ref, "light", 16, le, &llo, &lhi)
                && errors(small_light, ref, "bsdf", 16, be, &blo, &bhi),
            "rendered");
    T_NOTE("small light, 16 spp, %d seeds: light relMSE %.3e .. %.3e, bsdf %.3e .. %.3e", SEEDS,
           llo, lhi, blo, bhi);
    p = mann_whitney_p(le, be, &u);
    T_CHECK(p < 1e-3, "light sampling not below BSDF sampling: %d of %d pairs inverted, p = %.2g",
            u, SEEDS * SEEDS, p);
    free(ref);
}

int main(void)
{
    test_agreement();
    test_glossy();
    test_small_light();
    return t_done();
}
