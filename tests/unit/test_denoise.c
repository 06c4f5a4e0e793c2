/* test_denoise.c: the NFOR denoiser (src/denoise/nfor.h) on synthetic half buffers whose truth is
 * known: a true image T, and halves A = T + noise and B = T + noise of independent Gaussian noise
 * of standard deviation SIGMA, with noise-free or noisy features. Checks: a flat image stays flat
 * and keeps its mean, a step edge and a one-pixel bright line keep their contrast, the estimated
 * error is unbiased and within a factor 2 of the true one over 24 noise seeds, the result is the
 * same for 1, 2 and 3 threads, fireflies are found and their energy kept without a halo, and
 * mcrt_denoise_file refuses an input layer holding a NaN.
 * Each tolerance is derived from the noise, next to its check. With an argument FILE it also
 * writes the flat case's result there, so that tests/denoise.sh can compare the bits of the SSE2
 * copy (test_denoise_sse) and the AVX2 one. */
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "core/rng.h"
#include "denoise/firefly.h"
#include "denoise/nfor.h"
#include "io/image.h"
#include "mcrt.h"
#include "t.h"

enum { W = 64, H = 48, N = W * H };
#define SIGMA 0.1 /* the noise of one half; the raw mean's is SIGMA/sqrt(2) */

struct bufs {
    float truth[N * 3], half[2][N * 3], feat[2][2][N]; /* two feature planes per half */
    float rgb[N * 3], mse[N * 3];
    float var[N * 3]; /* each half's variance, SIGMA², as a film of independent samples gives it */
};

static double gauss(pcg32 *g)
{
    double u = pcg32_double(g), v = pcg32_double(g);
    return sqrt(-2.0 * log(1.0 - u)) * cos(6.283185307179586 * v);
}

/* Halves = truth + noise; feature 0 = f0 (with noise fsigma per half), feature 1 = 1. */
static void make(struct bufs *b, const float *f0, double fsigma, uint64_t seed)
{
    pcg32 g;
    int i, h;
    pcg32_seed(&g, seed, 7);
    for (h = 0; h < 2; h++) {
        for (i = 0; i < N * 3; i++)
            b->half[h][i] = (float)(b->truth[i] + SIGMA * gauss(&g));
        for (i = 0; i < N; i++) {
            b->feat[h][0][i] = (float)(f0[i] + fsigma * gauss(&g));
            b->feat[h][1][i] = 1.0f;
        }
    }
}

/* The denoiser on b, each half's own variance SIGMA² but edge_scale times that in the columns
 * W/2 − 2 to W/2, where the step of main has its edge (as stratified samples' s²/n overstate it
 * there): those whose 3×3 mean changes across them by half of itself or more (nfor.c,
 * EDGE_GRADIENT; 0.2 -> 0.4, 0.2 -> 0.6 and 0.4 -> 0.8 across the three). */
static mcrt_status run_with(struct bufs *b, int threads, double edge_scale)
{
    struct nfor_input in;
    mc_diag d;
    int h, i;
    in.width = W;
    in.height = H;
    in.nfeatures = 2;
    in.emission[0] = in.emission[1] = NULL;
    in.depth[0] = in.depth[1] = NULL;
    for (i = 0; i < N * 3; i++)
        b->var[i] = (float)(SIGMA * SIGMA
                            * (i / 3 % W >= W / 2 - 2 && i / 3 % W <= W / 2 ? edge_scale : 1.0));
    for (h = 0; h < 2; h++) {
        in.color[h] = b->half[h];
        in.color_var[h] = b->var;
        in.feature[h][0] = b->feat[h][0];
        in.feature[h][1] = b->feat[h][1];
    }
    return mc_nfor_denoise(&in, threads, b->rgb, b->mse, NULL, NULL, &d);
}

static mcrt_status run(struct bufs *b, int threads) { return run_with(b, threads, 1.0); }

static double mean(const float *v, size_t n)
{
    double s = 0.0;
    size_t i;
    for (i = 0; i < n; i++)
        s += v[i];
    return s / (double)n;
}

/* The relMSE of the denoised image, true (est 0) or from the denoiser's per-pixel estimate
 * (est 1), over the true (truth² + 0.01): this checks the error estimate itself, apart from the
 * estimate of the denominator, which is the film's (render/film.h). */
static double relmse(const struct bufs *b, int est)
{
    double s = 0.0;
    int i;
    for (i = 0; i < N * 3; i++)
        s += (est ? b->mse[i] : (b->rgb[i] - b->truth[i]) * (b->rgb[i] - b->truth[i]))
             / (b->truth[i] * b->truth[i] + 0.01);
    return s / (N * 3);
}

enum { STEP_SEEDS = 24 };

/* The mean of the n values v, and its standard error (their sample standard deviation over √n)
 * into *se. */
static double mean_se(const double *v, int n, double *se)
{
    double m = 0.0, var = 0.0;
    int i;
    for (i = 0; i < n; i++)
        m += v[i] / n;
    for (i = 0; i < n; i++)
        var += (v[i] - m) * (v[i] - m) / (n - 1);
    *se = sqrt(var / n);
    return m;
}

/* The error estimate (nfor.h, step 4) against the truth on the step f0 of main, the own
 * variances edge_scale times the truth on its edge (run_with). It is unbiased for this noise,
 * Gaussian and independent between pixels, but one image's estimate is noisy: each pixel's term
 * is about n_A·n_B, the product of its halves' noises, of standard deviation Var(half), and at
 * this reduction (the raw image's relMSE 0.054, the denoised one's about 0.0005) the estimate of
 * one image spreads by about three times the truth. So the check is over 24 noise seeds: the
 * mean of est − true within 3 standard errors of 0 (the spread measured over the seeds), and the
 * mean estimate within the factor 2 of the mean truth (NFOR's own estimate, which leaves
 * out the covariance of a half with the other's filtered result, measured 0.2 of the truth
 * here). */
static double step_estimate(struct bufs *b, const float *f0, double edge_scale,
                            double d[STEP_SEEDS])
{
    double dm, se, em = 0.0, tm = 0.0;
    int s;
    for (s = 0; s < STEP_SEEDS; s++) {
        double est, tru;
        make(b, f0, 0.0, 100 + (uint64_t)s);
        T_CHECK(run_with(b, 2, edge_scale) == MCRT_OK, "denoise");
        est = relmse(b, 1);
        tru = relmse(b, 0);
        d[s] = est - tru;
        em += est / STEP_SEEDS;
        tm += tru / STEP_SEEDS;
    }
    dm = mean_se(d, STEP_SEEDS, &se);
    T_NOTE("step, own variances %g times the truth on the edge: relMSE raw %.4g, denoised true "
           "%.4g, estimated %.4g (means of %d seeds; est - true %.3g, standard error %.3g)",
           edge_scale, SIGMA * SIGMA / 2 * (0.5 / (0.04 + 0.01) + 0.5 / (0.64 + 0.01)), tm, em,
           STEP_SEEDS, dm, se);
    T_CHECK(fabs(dm) < 3.0 * se, "step (own variances %g times): est - true %.3g, standard error "
            "%.3g", edge_scale, dm, se);
    T_CHECK(em > tm / 2 && em < tm * 2, "step (own variances %g times): estimated %.4g, true %.4g",
            edge_scale, em, tm);
    return tm;
}

/* Fireflies (denoise/firefly.h): flat halves of Gaussian noise (b) and the same halves with five
 * one-pixel outliers in one half each (c). mc_firefly_split finds those five, in their halves,
 * and nothing in b: a firefly's var exceeds 16 times its window's, which the channel mean of
 * Gaussian noise does with probability P(χ²₃ > 48) = 2e-10 a pixel. The denoised c less the
 * denoised b is what the fireflies did to the image: its sum is their energy (the outliers' excess
 * over 2, the image being the halves' mean), within what replacing each outlier's half by the
 * other half changes (that difference, of standard deviation √2·SIGMA a channel, times a column
 * sum of the filter near 1: 4 standard deviations over the 15 channels), and no pixel moves by
 * more than a raw pixel's standard error SIGMA/√2 (no halo above the noise). Without the split the
 * regression put a blotch of the outliers' energy around each. */
static void fireflies(struct bufs *b, struct bufs *c)
{
    static const int at[5][3] = {{10, 10, 0}, {40, 30, 0}, {30, 5, 1}, {55, 40, 1}, {2, 24, 0}};
    static const float excess[3] = {20.0f, 8.0f, 3.0f};
    static float v[N], vbox[N], m[N], mbox[N], a[N * 3], bb[N * 3];
    static float f0[N];
    struct firefly *ff;
    double energy = 0.0, moved = 0.0, peak = 0.0, tol;
    int i, k, c3, count, x, y, dx, dy, found;
    for (i = 0; i < N * 3; i++)
        b->truth[i] = 0.5f;
    for (i = 0; i < N; i++)
        f0[i] = 0.3f;
    make(b, f0, 0.05, 4);
    memcpy(c, b, sizeof *c);
    for (k = 0; k < 5; k++)
        for (c3 = 0; c3 < 3; c3++) {
            c->half[at[k][2]][(at[k][1] * W + at[k][0]) * 3 + c3] += excess[c3];
            energy += 0.5 * excess[c3];
        }
    for (k = 0; k < 2; k++) {
        const struct bufs *s = k ? c : b;
        memcpy(a, s->half[0], sizeof a);
        memcpy(bb, s->half[1], sizeof bb);
        for (i = 0; i < N; i++)
            for (v[i] = m[i] = 0.0f, c3 = 0; c3 < 3; c3++) {
                v[i] += (a[3 * i + c3] - bb[3 * i + c3]) * (a[3 * i + c3] - bb[3 * i + c3]) / 6.0f;
                m[i] += (a[3 * i + c3] + bb[3 * i + c3]) / 6.0f;
            }
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                float sum = 0.0f, msum = 0.0f;
                for (dy = -4; dy <= 4; dy++)
                    for (dx = -4; dx <= 4; dx++) {
                        int xx = x + dx < 0 ? 0 : x + dx >= W ? W - 1 : x + dx;
                        int yy = y + dy < 0 ? 0 : y + dy >= H ? H - 1 : y + dy;
                        sum += v[yy * W + xx];
                        msum += m[yy * W + xx];
                    }
                vbox[y * W + x] = sum / 81.0f;
                mbox[y * W + x] = msum / 81.0f;
            }
        T_CHECK(mc_firefly_split(a, bb, v, vbox, mbox, 81, W, H, &ff, &count) == 0, "split");
        if (!k) {
            T_CHECK(count == 0, "fireflies: %d found in Gaussian noise", count);
        } else {
            for (found = 0, i = 0; i < count; i++)
                for (x = 0; x < 5; x++)
                    found += ff[i].pixel == at[x][1] * W + at[x][0] && ff[i].half == at[x][2];
            T_CHECK(count == 5 && found == 5, "fireflies: %d found, %d of them the 5 put in",
                    count, found);
        }
        free(ff);
    }
    T_CHECK(run(b, 2) == MCRT_OK && run(c, 2) == MCRT_OK, "denoise");
    for (i = 0; i < N * 3; i++) {
        double dv = (double)c->rgb[i] - (double)b->rgb[i];
        moved += dv;
        peak = fabs(dv) > peak ? fabs(dv) : peak;
    }
    tol = 4.0 * sqrt(15.0) * sqrt(2.0) * SIGMA;
    T_NOTE("fireflies: energy %.4g kept as %.4g; the largest change of a pixel %.4g", energy,
           moved, peak);
    T_NEAR(moved, energy, tol, "fireflies: their energy is kept");
    T_CHECK(peak < SIGMA / sqrt(2.0), "fireflies: a pixel moved by %.4g", peak);
}

/* mcrt_denoise_file refuses an input with a value that is not finite: exit status 2 in mcrt
 * denoise (MCRT_ERR_INVALID), a message naming the layer and the pixel, the output untouched.
 * The same file without it denoises. */
static void not_finite_input(void)
{
    static const char *const names[] = {"A", "B", "albedo.A", "albedo.B", "normal.A", "normal.B",
                                        "depth.A", "depth.B", "emission.A", "emission.B",
                                        "variance.A", "variance.B", "emission.var"};
    enum { LW = 8, LH = 6, NL = sizeof names / sizeof names[0] };
    static float planes[NL][LW * LH * 3];
    struct image_layer layers[NL];
    char dir[] = "/tmp/test_denoise.XXXXXX", in[64], out[64], err[256], kept[8] = "";
    mcrt_status st;
    mc_diag d;
    FILE *f;
    int l, i;
    if (!mc_image_supported("exr")) {
        T_SKIP("the denoiser's EXR input: built without OpenEXR");
        return;
    }
    if (!mkdtemp(dir)) {
        T_CHECK(0, "mkdtemp");
        return;
    }
    snprintf(in, sizeof in, "%s/in.exr", dir);
    snprintf(out, sizeof out, "%s/out.exr", dir);
    for (l = 0; l < NL; l++) {
        for (i = 0; i < LW * LH * 3; i++)
            planes[l][i] = l < 2 ? 0.5f + 0.1f * (float)l : l == NL - 1 ? 0.0f : 0.3f;
        layers[l].name = names[l];
        layers[l].rgb = planes[l];
    }
    T_CHECK(mc_image_write_layers(in, layers, NL, LW, LH, &d) == MCRT_OK, "write: %s", d.msg);
    st = mcrt_denoise_file(in, out, 1, NULL, NULL, NULL, err, sizeof err);
    T_CHECK(st == MCRT_OK, "a finite input denoises: %s", err);
    planes[5][3 * (2 * LW + 3) + 1] = NAN; /* normal.B, pixel (3, 2), green */
    T_CHECK(mc_image_write_layers(in, layers, NL, LW, LH, &d) == MCRT_OK, "write: %s", d.msg);
    f = fopen(out, "w");
    T_CHECK(f && fputs("keep", f) >= 0 && fclose(f) == 0, "writing %s", out);
    st = mcrt_denoise_file(in, out, 1, NULL, NULL, NULL, err, sizeof err);
    f = fopen(out, "r");
    T_CHECK(f && fgets(kept, sizeof kept, f), "reading %s", out);
    if (f)
        fclose(f);
    T_CHECK(st == MCRT_ERR_INVALID && strstr(err, "layer normal.B, pixel (3, 2)") &&
                strcmp(kept, "keep") == 0,
            "a NaN in normal.B: status %d, '%s', the output '%s'", (int)st, err, kept);
    T_NOTE("a NaN in the input: '%s'", err);
    remove(in);
    remove(out);
    rmdir(dir);
}

int main(int argc, char **argv)
{
    static struct bufs b, c;
    static float f0[N];
    double raw_mean, sum, sum2, tm, d1[STEP_SEEDS], d2[STEP_SEEDS];
    int i, x, y, t;

    /* Flat: T = 0.5 everywhere, a noisy flat feature. The raw mean of all N·3 values has the
     * standard error (SIGMA/√2)/√(3N) = 0.0007 (0.14% of 0.5): the denoised mean must stay within
     * the 1% of it. Flat: the denoised pixels' standard deviation must be below a third
     * of the raw's SIGMA/√2 (a window of 19² pixels averages far more). */
    for (i = 0; i < N * 3; i++)
        b.truth[i] = 0.5f;
    for (i = 0; i < N; i++)
        f0[i] = 0.3f;
    make(&b, f0, 0.05, 1);
    T_CHECK(run(&b, 2) == MCRT_OK, "denoise");
    raw_mean = 0.5 * (mean(b.half[0], N * 3) + mean(b.half[1], N * 3));
    T_NEAR(mean(b.rgb, N * 3), raw_mean, 0.01 * raw_mean, "flat: the mean is kept");
    for (sum = sum2 = 0.0, i = 0; i < N * 3; i++) {
        sum += b.rgb[i];
        sum2 += b.rgb[i] * b.rgb[i];
    }
    sum = sqrt(sum2 / (N * 3) - (sum / (N * 3)) * (sum / (N * 3)));
    T_NOTE("flat: denoised std %.4g against the raw %.4g", sum, SIGMA / sqrt(2.0));
    T_CHECK(sum < SIGMA / sqrt(2.0) / 3.0, "flat: std %.4g", sum);

    if (argc > 1) {
        FILE *f = fopen(argv[1], "wb");
        T_CHECK(f && fwrite(b.rgb, sizeof b.rgb, 1, f) == 1 && fwrite(b.mse, sizeof b.mse, 1, f) == 1
                    && fclose(f) == 0,
                "writing %s", argv[1]);
    }

    /* 1, 2 and 3 threads: bit for bit the same. */
    memcpy(&c, &b, sizeof c);
    for (t = 1; t <= 3; t += 2) {
        T_CHECK(run(&c, t) == MCRT_OK, "denoise");
        T_CHECK(memcmp(c.rgb, b.rgb, sizeof b.rgb) == 0 && memcmp(c.mse, b.mse, sizeof b.mse) == 0,
                "%d threads differ from 2", t);
    }

    /* Step edge: 0.2 left of x = 32, 0.8 right of it, in the colour and (noise-free) in the
     * feature. The mean over a column of H·3 values has the raw standard error
     * (SIGMA/√2)/√(3H) = 0.006; the denoised columns next to the edge must keep their value
     * within 0.03 (5 of those), i.e. the edge keeps its contrast and does not bleed. */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            float v = x < W / 2 ? 0.2f : 0.8f;
            f0[y * W + x] = v;
            for (i = 0; i < 3; i++)
                b.truth[(y * W + x) * 3 + i] = v;
        }
    make(&b, f0, 0.0, 2);
    T_CHECK(run(&b, 2) == MCRT_OK, "denoise");
    for (x = W / 2 - 2; x < W / 2 + 2; x++) {
        for (sum = 0.0, y = 0; y < H; y++)
            for (i = 0; i < 3; i++)
                sum += b.rgb[(y * W + x) * 3 + i];
        T_NEAR(sum / (3 * H), x < W / 2 ? 0.2 : 0.8, 0.03, "step: column %d", x);
    }
    /* The error estimate against the truth (step_estimate). */
    step_estimate(&b, f0, 1.0, d1);
    /* The same with the own variances twice the truth on the edge's three columns (run_with),
     * seed by seed against the renders above, so that the halves' noise, common to both, drops
     * out: the estimate's miss moves by under a quarter of the truth. The edge's own ratio
     * (nfor.c, EDGE_GRADIENT) takes the doubling out: measured -0.13 of the truth, the standard
     * error 0.01, where it was +0.66 without that ratio, as the estimate's covariance term,
     * 2·Var·L_ii, took the variances as they were. What is left is the box ratio of OWN_R
     * around the edge, which the edge's doubled variances pull down for the smooth pixels too
     * (+0.12 with that box leaving the edge out, but on make bench-denoise's scenes the
     * estimate read further from the truth that way: cornell-spheres at 400² and 64 spp 0.88
     * against 1.00, two renders of ten outside 2× against none). */
    tm = step_estimate(&b, f0, 2.0, d2);
    {
        double moved[STEP_SEEDS], m, se;
        for (i = 0; i < STEP_SEEDS; i++)
            moved[i] = d2[i] - d1[i];
        m = mean_se(moved, STEP_SEEDS, &se);
        T_NOTE("step, own variances 2 times on the edge: est - true moved by %.3g of the truth, "
               "standard error %.3g", m / tm, se / tm);
        T_CHECK(fabs(m) < 0.25 * tm, "step, own variances 2 times on the edge: est - true moved "
                "by %.3g of the truth", m / tm);
    }

    /* A one-pixel bright line, 5 on 0.5, at y = 20, marked by a noisy feature, its own noise
     * (0.05 per half) prefiltered. The line's mean over W·3 values has the raw standard error
     * (SIGMA/√2)/√(3W) = 0.005: it must stay within 0.05 of 5 (10 of those, 1% of the
     * contrast), and the rows beside it within 0.05 of 0.5 (no halo). */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            float v = y == 20 ? 5.0f : 0.5f;
            f0[y * W + x] = y == 20 ? 1.0f : 0.0f;
            for (i = 0; i < 3; i++)
                b.truth[(y * W + x) * 3 + i] = v;
        }
    make(&b, f0, 0.05, 3);
    T_CHECK(run(&b, 2) == MCRT_OK, "denoise");
    for (y = 19; y <= 21; y++) {
        for (sum = 0.0, x = 0; x < W; x++)
            for (i = 0; i < 3; i++)
                sum += b.rgb[(y * W + x) * 3 + i];
        T_NEAR(sum / (3 * W), y == 20 ? 5.0 : 0.5, 0.05, "line: row %d", y);
    }
    for (i = 0; i < N * 3 && isfinite(b.rgb[i]); i++)
        ;
    T_CHECK(i == N * 3, "no NaN");
    fireflies(&b, &c);
    not_finite_input();
    return t_done();
}
