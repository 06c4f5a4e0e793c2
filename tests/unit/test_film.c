/* test_film.c: the film's error estimates (src/render/film.c): the variance of a pixel mean from
 * the halves (A − B)²·nA·nB/n² and from the pooled sample variance, and each half's own, by
 * hand; and the estimated relative MSE of Gaussian samples (with its denominator A·B) against
 * its expectation, both ways. */
#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "render/film.h"
#include "t.h"

/* A standard normal variate (Box-Muller). */
static double gauss(pcg32 *r)
{
    double u1 = 1.0 - pcg32_double(r), u2 = pcg32_double(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

static void test_variance(void)
{
    struct film f;
    float var[2 * 3];
    double v[3];
    /* R samples 1, 2 in half 0 and 3, 6 in half 1: A = 1.5, B = 4.5, (A − B)²/4 = 2.25; pooled:
     * mean 3, sample variance (4 + 1 + 0 + 9)/3 = 14/3, of the mean 14/12. G constant: 0 both
     * ways. B: 0, 1 | 2, 3: A = 0.5, B = 2.5, 1 by halves; pooled 5/12. Pixel 1 has one sample:
     * no estimate, 0. */
    static const float r[4] = {1.0f, 2.0f, 3.0f, 6.0f};
    int i;
    T_CHECK(mc_film_init(&f, 2, 1) == 0, "init");
    for (i = 0; i < 4; i++)
        mc_film_add(&f.pixels[0].half[i / 2], v3(r[i], 0.5f, (float)i));
    mc_film_add(&f.pixels[1].half[0], v3(1.0f, 1.0f, 1.0f));
    mc_film_variance(&f, var);
    T_NEAR(var[0], 2.25, 1e-6, "R variance of the mean, halves");
    T_CHECK(var[1] == 0.0f, "constant G: %g", var[1]);
    T_NEAR(var[2], 1.0, 1e-6, "B variance of the mean, halves");
    T_CHECK(var[3] == 0.0f && var[4] == 0.0f && var[5] == 0.0f, "one half empty: 0");
    /* The denominators are A·B + 0.01 (film.h): R 6.75, G 0.25, B 1.25. */
    T_NEAR(mc_film_est_relmse(&f), (2.25 / 6.76 + 1.0 / 1.26) / 3.0, 1e-9, "est relmse, halves");
    f.pooled = 1;
    mc_film_variance(&f, var);
    T_NEAR(var[0], 14.0 / 12.0, 1e-6, "R variance of the mean, pooled");
    T_NEAR(var[2], (2.25 + 0.25 + 0.25 + 2.25) / 3.0 / 4.0, 1e-6, "B, pooled");
    T_CHECK(var[3] == 0.0f, "one sample: 0");
    T_NEAR(mc_film_est_relmse(&f), (14.0 / 12.0 / 6.76 + 5.0 / 12.0 / 1.26) / 3.0, 1e-9,
           "est relmse, pooled");
    /* Each half's own s²/n: R 1, 2 -> 0.5/2 and 3, 6 -> 4.5/2; B 0, 1 and 2, 3 -> 0.5/2 each;
     * pixel 1's other half is empty: 0. */
    mc_film_half_variance(&f, 0, var);
    T_NEAR(var[0], 0.25, 1e-6, "half A's own variance, R");
    T_CHECK(var[1] == 0.0f, "half A's own variance, constant G: %g", var[1]);
    T_NEAR(var[2], 0.25, 1e-6, "half A's own variance, B");
    T_CHECK(var[3] == 0.0f, "half A's own variance, the other half empty: %g", var[3]);
    mc_film_half_variance(&f, 1, var);
    T_NEAR(var[0], 2.25, 1e-6, "half B's own variance, R");
    /* Unequal halves, 1 | 2, 3: (A − B)²·nA·nB/n² = (1 − 2.5)²·2/9 = 0.5. */
    mc_film_clear(&f);
    f.pooled = 0;
    mc_film_add(&f.pixels[0].half[0], v3s(1.0f));
    mc_film_add(&f.pixels[0].half[1], v3s(2.0f));
    mc_film_add(&f.pixels[0].half[1], v3s(3.0f));
    T_CHECK(mc_film_pixel_variance(&f, &f.pixels[0], v) && fabs(v[0] - 0.5) < 1e-12,
            "unequal halves: %g", v[0]);
    /* A half of one sample has no s²: (A − B)²·n_B/n = (1 − 2.5)²·2/3 = 1.5; B's own 0.5/2. */
    mc_film_half_variance(&f, 0, var);
    T_NEAR(var[0], 1.5, 1e-6, "a half of one sample: from the halves' difference");
    mc_film_half_variance(&f, 1, var);
    T_NEAR(var[0], 0.25, 1e-6, "the other half's own");
    mc_film_free(&f);
    T_CHECK(mc_film_init(&f, 1, 1) == 0 && isnan(mc_film_est_relmse(&f)), "no samples: NaN");
    mc_film_free(&f);
}

/* The halves of each pass split as mc_film_half_split says: passes of 1 sample alternate. */
static void test_split(void)
{
    T_CHECK(mc_film_half_split(8, 0) == 4 && mc_film_half_split(8, 1) == 4, "even");
    T_CHECK(mc_film_half_split(7, 0) == 4 && mc_film_half_split(7, 1) == 3, "odd");
    T_CHECK(mc_film_half_split(1, 0) == 1 && mc_film_half_split(1, 1) == 0, "one sample");
}

/* N Gaussian samples per pixel (mean mu, sd sigma) split into halves: the estimate's mean over
 * W·H pixels against its expectation. */
static void test_est_relmse(int pooled)
{
    enum { W = 128, H = 128, N = 16 };
    struct film f;
    pcg32 rng;
    int i, k;
    double mu = 1.0, sigma = 0.25, c = 0.01, v, d, expect, est, tol;
    pcg32_seed(&rng, 7, 3);
    T_CHECK(mc_film_init(&f, W, H) == 0, "init");
    f.pooled = pooled;
    for (i = 0; i < W * H; i++)
        for (k = 0; k < N; k++)
            mc_film_add(&f.pixels[i].half[k & 1], v3((float)(mu + sigma * gauss(&rng)),
                                                     (float)(mu + sigma * gauss(&rng)),
                                                     (float)(mu + sigma * gauss(&rng))));
    est = mc_film_est_relmse(&f);
    /* Var(mean) = v = sigma²/N. With A = mu + u + w, B = mu + u − w (u, w independent N(0, v)),
     * the estimate of a channel is V/(D − w²) with D = (mu + u)² + c the denominator, since
     * A·B = (mu + u)² − w², and V = w² (halves) or the pooled s²/N. To second order in v:
     *   E[V/(D − w²)] = E[V]·E[1/D] + E[V w²]/(mu² + c)², E[1/D] = (1 + v(3mu² − c)/(mu² + c)²)
     * /(mu² + c) (delta method), E[w⁴] = 3v² for the halves and E[s²/N · w²] = v²(N + 1)/(N − 1)
     * pooled (s² = v(χ²_{N−2} + w²/v)·N/(N − 1)). The terms dropped are O(v²) = 1.5e-5 here.
     * Noise: a channel's estimate has relative sd sqrt(2/(N − 1)) = 0.37 pooled and sqrt(2) =
     * 1.41 from the halves (a χ² of one degree of freedom), over 3·W·H = 49152 channels: 0.17%
     * and 0.64%; tolerance 6 sd. */
    v = sigma * sigma / N;
    d = mu * mu + c;
    expect = v * (1.0 + v * (3.0 * mu * mu - c) / (d * d)) / d
             + (pooled ? v * v * (N + 1.0) / (N - 1.0) : 3.0 * v * v) / (d * d);
    tol = 6.0 * (pooled ? sqrt(2.0 / (N - 1)) : sqrt(2.0)) / sqrt(3.0 * W * H);
    T_NOTE("%s: est relmse %.6g, expected %.6g (%+.2f%%, tolerance %.2f%%)",
           pooled ? "pooled" : "halves", est, expect, 100.0 * (est / expect - 1.0), 100.0 * tol);
    T_NEAR(est / expect, 1.0, tol, "estimated relMSE of Gaussian samples, %s",
           pooled ? "pooled" : "halves");
    mc_film_free(&f);
}

int main(void)
{
    test_variance();
    test_split();
    test_est_relmse(1);
    test_est_relmse(0);
    return t_done();
}
