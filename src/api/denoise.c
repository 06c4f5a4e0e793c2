/* denoise.c: a render's layers to the denoiser and back (see denoise.h). */
#include "api/denoise.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"

#include "core/alloc.h"
#include "denoise/nfor.h"
#include "io/image.h"
#include "render/film.h"

const char *const mc_denoise_layer_names[DENOISE_LAYERS] = {"albedo", "normal", "depth",
                                                            "emission", "variance"};

/* The film of the halves a and b: one sample standing for each half of a pixel, for the film's
 * estimates from its halves (render/film.h). Returns 0, or -1 when out of memory. */
static int halves_film(struct film *f, const float *a, const float *b, int w, int h)
{
    size_t i, n = (size_t)w * (size_t)h;
    int c;
    if (mc_film_init(f, w, h) != 0)
        return -1;
    for (i = 0; i < n; i++) {
        for (c = 0; c < 3; c++) {
            f->pixels[i].half[0].mean[c] = a[3 * i + c];
            f->pixels[i].half[1].mean[c] = b[3 * i + c];
        }
        f->pixels[i].half[0].count = f->pixels[i].half[1].count = 1;
    }
    return 0;
}

/* The relative MSE of the denoised image from its per-pixel error estimate mse: the mean of
 * mse/(μ² + ε) (film.h's ε), the sum floored at 0, μ² the denoiser's mean_sq: the denoised
 * value's square, with the noise of the light it adds back unfiltered allowed for (nfor.h), close
 * to μ² where the denoiser worked; the film's A·B (mc_film_mean_squared), unbiased for μ² but of one
 * degree of freedom, made the estimate 20 times the truth on the Cornell box at 16 spp, its small
 * values in dark noisy pixels dividing the small errors left there.
 *
 * Its standard deviation into *sd: the terms' own variances mse_var (nfor.h), independent from
 * pixel to pixel as the halves' noise is, summed over the same denominators squared. This is what
 * makes one render's estimate stray (the README's denoiser section: on the Cornell box at 160²
 * and 16 spp, 1.22e-4 to 1.31e-4 predicted on ten seeds, 1.3e-4 seen, against errors of 4e-4 to
 * 7e-4); it does not see what neither half sampled (a caustic's missed paths). */
static double denoised_relmse(const float *mean_sq, const float *mse, const float *mse_var,
                              size_t n3, double *sd)
{
    double s = 0.0, v = 0.0;
    size_t i;
    for (i = 0; i < n3; i++) {
        double q = (double)mean_sq[i] + MC_RELMSE_EPS;
        s += mse[i] / q;
        v += mse_var[i] / (q * q);
    }
    *sd = sqrt(v) / (double)n3;
    return s > 0.0 ? s / (double)n3 : 0.0;
}

/* The feature planes: albedo R, G, B, normal x, y, z, depth. The emission is no feature but a
 * part of the colour taken out (denoise.h). */
#define NPLANES 7

mcrt_status mc_denoise_layers(const float *const halves[2],
                              const float *layer[DENOISE_LAYERS][2], const float *emission_var,
                              int width, int height,
                              int threads, float *rgb, double *est_relmse, double *est_sd,
                              double *est_raw, mc_diag *d)
{
    size_t n = (size_t)width * (size_t)height, n3 = n * 3, i;
    float *buf = mc_malloc((3 * n3 + n * NPLANES * 2) * sizeof *buf);
    float *mse = buf, *mse_var = buf + n3, *mean_sq = buf + 2 * n3;
    double sd;
    struct nfor_input in;
    mcrt_status st;
    int h, p;
    if (!buf)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser (%dx%d)", width,
                       height);
    in.width = width;
    in.height = height;
    in.nfeatures = NPLANES;
    for (h = 0; h < 2; h++) {
        float *planes = buf + 3 * n3 + (size_t)h * NPLANES * n;
        in.color[h] = halves[h];
        in.emission[h] = layer[DENOISE_EMISSION][h];
        in.color_var[h] = layer[DENOISE_VARIANCE][h];
        in.emission_var = emission_var;
        in.depth[h] = planes + (size_t)(NPLANES - 1) * n; /* the last plane (below) */
        for (p = 0; p < NPLANES; p++) {
            const float *src = layer[p < 3 ? DENOISE_ALBEDO : p < 6 ? DENOISE_NORMAL : DENOISE_DEPTH][h];
            in.feature[h][p] = planes + (size_t)p * n;
            for (i = 0; i < n; i++)
                planes[(size_t)p * n + i] = src[3 * i + (p < 6 ? p % 3 : 0)];
        }
    }
    st = mc_nfor_denoise(&in, threads, rgb, mse, mse_var, mean_sq, d);
    if (st == MCRT_OK)
        *est_relmse = denoised_relmse(mean_sq, mse, mse_var, n3, &sd);
    if (st == MCRT_OK && est_sd)
        *est_sd = sd;
    if (st == MCRT_OK && est_raw) {
        struct film f;
        if (halves_film(&f, halves[0], halves[1], width, height) != 0)
            st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser");
        else
            *est_raw = mc_film_est_relmse(&f);
        mc_film_free(&f);
    }
    free(buf);
    return st;
}

/* The public mcrt_denoise_file (mcrt.h): the layers read, checked, denoised and written. */
mcrt_status mcrt_denoise_file(const char *in, const char *out, int threads, double *est_raw,
                              double *est_denoised, double *est_denoised_sd, char *error,
                              size_t error_size)
{
    struct image im[3 + 2 * DENOISE_LAYERS]; /* A, B, the layers by half, emission.var */
    char names[3 + 2 * DENOISE_LAYERS][32];
    const char *name[3 + 2 * DENOISE_LAYERS];
    const float *halves[2], *layer[DENOISE_LAYERS][2];
    struct image_layer outl[2];
    float *rgb = NULL, *raw = NULL;
    double est = 0.0, sd = 0.0;
    mc_diag d;
    mcrt_status st = MCRT_OK;
    int i, k, w = 0, h = 0;
    d.msg[0] = '\0';
    memset(im, 0, sizeof im);
    if (!in || !out) {
        st = mc_fail(&d, MCRT_ERR_INVALID, "mcrt_denoise_file: %s is NULL", in ? "out" : "in");
        goto done;
    }
    if (!mc_image_layered(in) || !mc_image_layered(out)) {
        st = mc_fail(&d, MCRT_ERR_UNSUPPORTED, "%s: the denoiser reads and writes EXR images only",
                     mc_image_layered(in) ? out : in);
        goto done;
    }
    for (i = 0; i < 3 + 2 * DENOISE_LAYERS; i++) {
        if (i < 2)
            snprintf(names[i], sizeof names[i], "%c", i ? 'B' : 'A');
        else if (i == 2 + 2 * DENOISE_LAYERS)
            snprintf(names[i], sizeof names[i], "%s", MC_DENOISE_EMISSION_VAR);
        else
            snprintf(names[i], sizeof names[i], "%s.%c", mc_denoise_layer_names[(i - 2) / 2],
                     i % 2 ? 'B' : 'A');
        name[i] = names[i];
    }
    /* All the layers in one pass over the file. */
    if ((st = mc_image_read_layers(in, name, 3 + 2 * DENOISE_LAYERS, im, &d)) != MCRT_OK) {
        /* An input that cannot be read at all is malformed; one without a layer is the wrong
         * input (the first one missing named). Either is bad input, which the caller tells from
         * out of memory. */
        struct image any;
        if (st == MCRT_ERR_NOMEM)
            goto done;
        if (mc_image_read(in, &any, NULL) != MCRT_OK) {
            st = MCRT_ERR_PARSE; /* d holds why it cannot be read */
            goto done;
        }
        mc_image_free(&any);
        for (i = 0; i < 3 + 2 * DENOISE_LAYERS; i++)
            if (mc_image_read_layer(in, name[i], &any, NULL) != MCRT_OK)
                break;
            else
                mc_image_free(&any);
        st = mc_fail(&d, MCRT_ERR_INVALID, "%s: no layer %s; denoise an EXR saved by "
                                           "mcrt render --denoise", in, name[i]);
        goto done;
    }
    /* The layers of one EXR share its data window: one size. */
    w = im[0].width;
    h = im[0].height;
    /* mcrt writes no value that is not finite (a NaN or infinite sample is never added, film.h);
     * one in the input would spread over every window that holds it. */
    for (i = 0; i < 3 + 2 * DENOISE_LAYERS; i++) {
        size_t j, n3 = (size_t)w * (size_t)h * 3;
        for (j = 0; j < n3 && isfinite(im[i].rgb[j]); j++)
            ;
        if (j < n3) {
            st = mc_fail(&d, MCRT_ERR_INVALID, "%s: layer %s, pixel (%d, %d): %g is not a finite "
                                               "number", in, name[i], (int)(j / 3 % (size_t)w),
                         (int)(j / 3 / (size_t)w), (double)im[i].rgb[j]);
            goto done;
        }
    }
    for (k = 0; k < 2; k++) {
        halves[k] = im[k].rgb;
        for (i = 0; i < DENOISE_LAYERS; i++)
            layer[i][k] = im[2 + 2 * i + k].rgb;
    }
    rgb = mc_malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    raw = mc_malloc((size_t)w * (size_t)h * 3 * sizeof *raw);
    if (!rgb || !raw) {
        st = mc_fail(&d, MCRT_ERR_NOMEM, "out of memory for a %dx%d image", w, h);
        goto done;
    }
    st = mc_denoise_layers(halves, layer, im[2 + 2 * DENOISE_LAYERS].rgb, w, h, threads > 0 ? threads : mc_default_threads(), rgb,
                           &est, &sd, est_raw, &d);
    if (st != MCRT_OK)
        goto done;
    for (i = 0; i < w * h * 3; i++)
        raw[i] = 0.5f * (halves[0][i] + halves[1][i]);
    outl[0].name = NULL;
    outl[0].rgb = rgb;
    outl[1].name = "raw";
    outl[1].rgb = raw;
    if ((st = mc_image_write_layers(out, outl, 2, w, h, &d)) != MCRT_OK)
        goto done;
    if (est_denoised)
        *est_denoised = est;
    if (est_denoised_sd)
        *est_denoised_sd = sd;
done:
    for (i = 0; i < 3 + 2 * DENOISE_LAYERS; i++)
        mc_image_free(&im[i]);
    free(rgb);
    free(raw);
    if (error && error_size)
        snprintf(error, error_size, "%s", d.msg);
    return st;
}
