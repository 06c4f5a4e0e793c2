/* test_film.c: the film's error estimates (src/render/film.c): the variance of a pixel mean from
 * its Welford sums, and the estimated relative MSE against its definition on samples of known
 * distribution. */
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
    /* Samples 1, 2, 3, 6 on R: mean 3, sample variance (4 + 1 + 0 + 9)/3 = 14/3, of the mean
     * 14/12. G constant: 0. Pixel 1 has one sample: no estimate, 0. */
    static const float r[4] = {1.0f, 2.0f, 3.0f, 6.0f};
    int i;
    T_CHECK(mc_film_init(&f, 2, 1) == 0, "init");
    for (i = 0; i < 4; i++)
        mc_film_add(&f.pixels[0], v3(r[i], 0.5f, (float)i));
    mc_film_add(&f.pixels[1], v3(1.0f, 1.0f, 1.0f));
    mc_film_variance(&f, var);
    T_NEAR(var[0], 14.0 / 12.0, 1e-6, "R variance of the mean");
    T_CHECK(var[1] == 0.0f, "constant G: %g", var[1]);
    T_NEAR(var[2], (2.25 + 0.25 + 0.25 + 2.25) / 3.0 / 4.0, 1e-6, "B variance of the mean");
    T_CHECK(var[3] == 0.0f && var[4] == 0.0f && var[5] == 0.0f, "one sample: 0");
    /* Only pixel 0 counts: (14/12/(9 + 0.01) + 0 + (5/12)/(2.25 + 0.01)) / 3. */
    T_NEAR(mc_film_est_relmse(&f), (14.0 / 12.0 / 9.01 + 5.0 / 12.0 / 2.26) / 3.0, 1e-9,
           "est relmse by hand");
    mc_film_free(&f);
    T_CHECK(mc_film_init(&f, 1, 1) == 0 && isnan(mc_film_est_relmse(&f)), "no samples: NaN");
    mc_film_free(&f);
}

static void test_est_relmse(void)
{
    enum { W = 64, H = 64, N = 16 };
    struct film f;
    pcg32 rng;
    int i, k;
    double mu = 1.0, sigma = 0.5, expect, est;
    pcg32_seed(&rng, 7, 3);
    T_CHECK(mc_film_init(&f, W, H) == 0, "init");
    for (i = 0; i < W * H; i++)
        for (k = 0; k < N; k++)
            mc_film_add(&f.pixels[i], v3((float)(mu + sigma * gauss(&rng)),
                                         (float)(mu + sigma * gauss(&rng)),
                                         (float)(mu + sigma * gauss(&rng))));
    est = mc_film_est_relmse(&f);
    /* Var(mean) = v = sigma²/N, and s² is independent of the mean m for Gaussian samples, so
     * E[est] = v·E[1/(m² + c)], c = 0.01. By the delta method to second order,
     * E[1/(m² + c)] = (1 + v(3mu² − c)/(mu² + c)²)/(mu² + c) (the next term is 0.1% here).
     * Noise: s² of N Gaussian samples has relative sd sqrt(2/(N-1)) = 0.37, averaged over
     * 3·W·H = 12288 channels: 0.33%; tolerance 2% (6 sd). */
    expect = sigma * sigma / N;
    expect *= (1.0 + expect * (3.0 * mu * mu - 0.01) / ((mu * mu + 0.01) * (mu * mu + 0.01))) /
              (mu * mu + 0.01);
    T_NOTE("est relmse %.6g, expected %.6g", est, expect);
    T_NEAR(est / expect, 1.0, 0.02, "estimated relMSE of Gaussian samples");
    mc_film_free(&f);
}

int main(void)
{
    test_variance();
    test_est_relmse();
    return t_done();
}
