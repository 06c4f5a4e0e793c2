/* test_diff.c: image comparison (src/diff, mcrt_diff) and EXR layers (src/io): a diff of an image
 * with itself is exactly zero; a known perturbation gives the known statistics; the z-test accepts
 * pure noise of the stated variance and rejects exactly the pixels shifted by 10 sigma; named EXR
 * layers round-trip. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/rng.h"
#include "diff/diff.h"
#include "io/image.h"
#include "mcrt.h"
#include "t.h"

enum { W = 64, H = 48 };

static float *alloc_image(float value)
{
    float *p = malloc(W * H * 3 * sizeof *p);
    size_t i;
    for (i = 0; p && i < W * H * 3; i++)
        p[i] = value;
    return p;
}

/* A standard normal variate (Box-Muller). */
static double gauss(pcg32 *r)
{
    double u1 = 1.0 - pcg32_double(r), u2 = pcg32_double(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

static void test_stats(void)
{
    float *a = alloc_image(0.5f), *b = alloc_image(0.5f);
    struct image t = {W, H, a}, r = {W, H, b};
    struct diff_rect whole = {0, 0, W, H}, crop = {8, 4, 24, 20};
    struct diff_stats s;
    int x, y;
    mc_diff_stats(&t, &r, whole, &s);
    T_CHECK(s.mse == 0.0 && s.relmse == 0.0 && s.max_abs == 0.0 && s.bias == 0.0 &&
                isinf(s.psnr), "an image against itself: mse %g psnr %g", s.mse, s.psnr);
    /* +0.1 on R inside the crop window only. Per channel e² = 0.01 on 1 of 3 channels. */
    for (y = crop.y0; y < crop.y1; y++)
        for (x = crop.x0; x < crop.x1; x++)
            a[3 * (y * W + x)] += 0.1f;
    mc_diff_stats(&t, &r, crop, &s);
    /* Float rounding of 0.5 + 0.1 makes e = 0.1 within 3e-8: tolerances 1e-6 relative. */
    T_CHECK(s.pixels == 16 * 16, "crop pixels %zu", s.pixels);
    T_NEAR(s.mse, 0.01 / 3.0, 1e-8, "crop mse");
    T_NEAR(s.relmse, 0.01 / (0.25 + 0.01) / 3.0, 1e-8, "crop relmse");
    T_NEAR(s.psnr, -10.0 * log10(0.01 / 3.0), 1e-5, "crop psnr");
    T_NEAR(s.max_abs, 0.1, 1e-7, "crop max error");
    T_NEAR(s.bias_rgb[0], 0.1, 1e-7, "crop bias R");
    T_CHECK(s.bias_rgb[1] == 0.0 && s.bias_rgb[2] == 0.0, "G, B unbiased");
    T_NEAR(s.bias, 0.1 / 3.0, 1e-7, "crop bias");
    mc_diff_stats(&t, &r, whole, &s);
    T_NEAR(s.mse, 0.01 / 3.0 * 256.0 / (W * H), 1e-8, "whole mse (the crop's share)");
    free(a);
    free(b);
}

static void test_ztest(void)
{
    float *a = alloc_image(1.0f), *b = alloc_image(1.0f), *v = alloc_image(0.0f);
    float *zimg = malloc(W * H * sizeof *zimg), rgb[4 * 3], zs[4];
    struct image t = {W, H, a}, r = {W, H, b}, var = {W, H, v};
    struct diff_rect whole = {0, 0, W, H};
    struct diff_ztest z;
    pcg32 rng;
    size_t i, shifted = 0;
    pcg32_seed(&rng, 5, 1);
    /* TEST = REF + N(0, sigma²) with the variance reported exactly: a correct render. */
    for (i = 0; i < W * H * 3; i++) {
        double sigma = 0.01 + 0.1 * (double)(i % 7);
        a[i] += (float)(sigma * gauss(&rng));
        v[i] = (float)(sigma * sigma);
    }
    z.floor = 0.0;
    z.alpha = 0.01;
    mc_diff_ztest(&t, &r, &var, whole, &z, zimg);
    /* Šidák level for 3·W·H tests; z_crit is where erfc(z/√2) equals it (bisection to 1e-12). */
    T_NEAR(z.alpha_test, 1.0 - pow(0.99, 1.0 / (3.0 * W * H)), 1e-15, "Sidak level");
    T_NEAR(erfc(z.z_crit / sqrt(2.0)) / z.alpha_test, 1.0, 1e-6, "z_crit matches the level");
    T_NOTE("noise only: %zu of %zu pixels rejected, max z %.3f, z_crit %.3f", z.rejected,
           z.pixels, z.max_z, z.z_crit);
    /* The family-wise false-rejection chance is alpha = 1%; with this fixed seed none occurs. */
    T_CHECK(z.rejected == 0 && z.agree == 1.0, "pure noise rejected %zu pixels", z.rejected);
    /* Shift every 37th pixel's G by 10 sigma: |z| >= 10 - 4.5 (noise beyond 4.5 sigma has chance
     * 7e-6 per channel) > z_crit = 4.9, so exactly those pixels are rejected. */
    for (i = 0; i < W * H; i += 37) {
        a[3 * i + 1] += (float)(10.0 * sqrt(v[3 * i + 1]));
        shifted++;
    }
    mc_diff_ztest(&t, &r, &var, whole, &z, zimg);
    T_CHECK(z.rejected == shifted, "rejected %zu of %zu shifted pixels", z.rejected, shifted);
    T_NEAR(z.agree, 1.0 - (double)shifted / (W * H), 1e-12, "agree fraction");
    T_CHECK(zimg[37] >= 5.5f && zimg[1] < z.z_crit, "z image: %g at a shifted pixel", zimg[37]);
    /* A floor turns a zero variance into a finite z; without one an error is infinitely
     * significant. */
    memset(v, 0, W * H * 3 * sizeof *v);
    z.floor = 1e3;
    mc_diff_ztest(&t, &r, &var, whole, &z, NULL);
    T_CHECK(z.rejected == 0, "a large floor accepts everything (rejected %zu)", z.rejected);
    z.floor = 0.0;
    mc_diff_ztest(&t, &r, &var, whole, &z, NULL);
    T_CHECK(z.rejected == W * H && isinf(z.max_z), "zero variance, no floor: rejected %zu",
            z.rejected);
    zs[0] = 0.0f, zs[1] = 0.5f, zs[2] = 1.5f, zs[3] = 9.0f;
    mc_diff_zcolour(zs, 4, 1.0, rgb);
    T_CHECK(rgb[0] == 0.0f && rgb[2] == 0.0f && rgb[5] == 0.5f && rgb[6] == 1.0f &&
                rgb[7] == 0.5f && rgb[9] == 1.0f && rgb[10] == 1.0f, "false colours");
    free(a);
    free(b);
    free(v);
    free(zimg);
}

/* Named EXR layers round-trip, through the public mcrt_diff too. */
static void test_layers(void)
{
    char dir[] = "/tmp/mcrt-diff-XXXXXX", p[128], q[128], err[256];
    float *a = alloc_image(0.25f), *b = alloc_image(2.0f);
    struct image_layer layers[2];
    struct image im = {0, 0, NULL};
    mc_diag d;
    mcrt_diff_options o;
    mcrt_diff_result res;
    if (!mkdtemp(dir)) {
        T_CHECK(0, "mkdtemp");
        return;
    }
    snprintf(p, sizeof p, "%s/a.exr", dir);
    snprintf(q, sizeof q, "%s/a.pfm", dir);
    a[5] = 3.0f;
    b[7] = 0.5f;
    layers[0].name = NULL;
    layers[0].rgb = a;
    layers[1].name = "variance";
    layers[1].rgb = b;
    if (mc_image_supported("exr")) {
        T_CHECK(mc_image_write_layers(p, layers, 2, W, H, &d) == MCRT_OK, "write: %s", d.msg);
        T_CHECK(mc_image_read_layer(p, "variance", &im, &d) == MCRT_OK && im.width == W &&
                    memcmp(im.rgb, b, W * H * 3 * sizeof *b) == 0, "variance layer back: %s", d.msg);
        mc_image_free(&im);
        T_CHECK(mc_image_read(p, &im, &d) == MCRT_OK &&
                    memcmp(im.rgb, a, W * H * 3 * sizeof *a) == 0, "main layer back: %s", d.msg);
        mc_image_free(&im);
        T_CHECK(mc_image_read_layer(p, "albedo", &im, &d) == MCRT_ERR_IO &&
                    strstr(d.msg, "albedo"), "a missing layer: %s", d.msg);
        mcrt_diff_options_init(&o);
        o.layer = "variance";
        T_CHECK(mcrt_diff(p, p, &o, &res, sizeof res, err, sizeof err) == MCRT_OK && res.whole.mse == 0.0 &&
                    res.width == W && !err[0], "mcrt_diff of a layer with itself: %s", err);
        unlink(p);
    } else {
        T_SKIP("EXR layers written, read back and compared: built without OpenEXR");
    }
    T_CHECK(mc_image_write_layers(q, layers, 2, W, H, &d) == MCRT_ERR_UNSUPPORTED,
            "PFM refuses layers");
    T_CHECK(access(q, F_OK) != 0, "and leaves no file");
    mcrt_diff_options_init(&o);
    T_CHECK(mcrt_diff(q, q, &o, &res, sizeof res, err, sizeof err) != MCRT_OK && res.width == 0 &&
                strstr(err, "a.pfm"), "a missing image: %s", err);
    rmdir(dir);
    free(a);
    free(b);
}

int main(void)
{
    test_stats();
    test_ztest();
    test_layers();
    return t_done();
}
