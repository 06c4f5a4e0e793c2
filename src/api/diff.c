/* diff.c: the public image comparison, mcrt_diff (mcrt.h): reads the images, checks the options
 * and hands the pixels to src/diff; writes the false-colour z image when the z-test fails. */
#include "mcrt.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "api/sized.h"
#include "core/alloc.h"
#include "diff/diff.h"
#include "io/image.h"

/* Defaults of the z-test (issue 4, after Mitsuba 3's render tests): a 1% chance that a correct
 * renderer fails the family of tests, and a pass when 99.75% of pixels agree. */
#define DEFAULT_ALPHA 0.01
#define DEFAULT_MIN_AGREE 0.9975

void mcrt_diff_options_init(mcrt_diff_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->size = sizeof *o;
}

static void copy_stats(const struct diff_stats *s, mcrt_diff_stats *out)
{
    out->pixels = s->pixels;
    out->mse = s->mse;
    out->relmse = s->relmse;
    out->psnr = s->psnr;
    out->max_abs = s->max_abs;
    out->bias = s->bias;
    out->bias_r = s->bias_rgb[0];
    out->bias_g = s->bias_rgb[1];
    out->bias_b = s->bias_rgb[2];
}


/* Read the variance of TEST's means: the "variance" layer when the file has one, else the image.
 * Out of memory reading the layer is not its absence. */
static mcrt_status read_variance(const char *path, struct image *var, mc_diag *d)
{
    mcrt_status st = mc_image_read_layer(path, "variance", var, d);
    if (st == MCRT_OK || st == MCRT_ERR_NOMEM)
        return st;
    return mc_image_read(path, var, d);
}

/* The z-test over rect; writes the z image on failure when asked. */
static mcrt_status ztest(const struct image *t, const struct image *r, const mcrt_diff_options *o,
                         struct diff_rect rect, mcrt_diff_result *out, mc_diag *d)
{
    struct image var = {0, 0, NULL};
    struct diff_ztest z;
    size_t n = (size_t)(rect.x1 - rect.x0) * (size_t)(rect.y1 - rect.y0);
    float *zimg = NULL, *rgb = NULL;
    mcrt_status st = read_variance(o->variance, &var, d);
    if (st != MCRT_OK) {
        out->width = out->height = 0;
        return st;
    }
    if (var.width != t->width || var.height != t->height) {
        st = mc_fail(d, MCRT_ERR_INVALID, "'%s' is %dx%d but the test image is %dx%d",
                     o->variance, var.width, var.height, t->width, t->height);
        goto done;
    }
    if (o->z_image && !(zimg = mc_malloc(n * sizeof *zimg))) {
        st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
        goto done;
    }
    z.floor = o->floor;
    z.alpha = o->alpha > 0.0 ? o->alpha : DEFAULT_ALPHA;
    mc_diff_ztest(t, r, &var, rect, &z, zimg);
    out->ztest = 1;
    out->ztest_pass = z.agree >= (o->min_agree > 0.0 ? o->min_agree : DEFAULT_MIN_AGREE);
    out->alpha_test = z.alpha_test;
    out->z_crit = z.z_crit;
    out->agree = z.agree;
    out->max_z = z.max_z;
    out->rejected = z.rejected;
    if (zimg && !out->ztest_pass) {
        if (!(rgb = mc_malloc(3 * n * sizeof *rgb))) {
            st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory");
            goto done;
        }
        mc_diff_zcolour(zimg, n, z.z_crit, rgb);
        st = mc_image_write(o->z_image, rgb, rect.x1 - rect.x0, rect.y1 - rect.y0, d);
        out->z_image_written = st == MCRT_OK;
    }
done:
    free(zimg);
    free(rgb);
    mc_image_free(&var);
    return st;
}

/* The comparison into the library's own result struct; mcrt_diff copies it to the caller's. */
static mcrt_status compare(const char *test, const char *ref, const mcrt_diff_options *o,
                           mcrt_diff_result *out, mc_diag *d)
{
    struct image t = {0, 0, NULL}, r = {0, 0, NULL};
    struct diff_rect whole, rect;
    struct diff_stats s;
    mcrt_status st;
    if ((st = mc_image_read_layer(test, o->layer, &t, d)) != MCRT_OK ||
        (st = mc_image_read_layer(ref, o->layer, &r, d)) != MCRT_OK)
        goto done;
    if (t.width != r.width || t.height != r.height) {
        st = mc_fail(d, MCRT_ERR_INVALID, "'%s' is %dx%d but '%s' is %dx%d", test, t.width,
                     t.height, ref, r.width, r.height);
        goto done;
    }
    whole.x0 = whole.y0 = 0;
    whole.x1 = t.width;
    whole.y1 = t.height;
    rect = whole;
    if (o->crop_x0 || o->crop_y0 || o->crop_x1 || o->crop_y1) {
        rect.x0 = o->crop_x0;
        rect.y0 = o->crop_y0;
        rect.x1 = o->crop_x1;
        rect.y1 = o->crop_y1;
        if (rect.x0 < 0 || rect.y0 < 0 || rect.x1 > t.width || rect.y1 > t.height ||
            rect.x0 >= rect.x1 || rect.y0 >= rect.y1) {
            st = mc_fail(d, MCRT_ERR_INVALID,
                         "crop %d,%d,%d,%d is not a non-empty window inside the %dx%d image",
                         rect.x0, rect.y0, rect.x1, rect.y1, t.width, t.height);
            goto done;
        }
    }
    out->width = t.width;
    out->height = t.height;
    mc_diff_stats(&t, &r, whole, &s);
    copy_stats(&s, &out->whole);
    mc_diff_stats(&t, &r, rect, &s);
    copy_stats(&s, &out->crop);
    if (o->variance)
        st = ztest(&t, &r, o, rect, out, d);
done:
    mc_image_free(&t);
    mc_image_free(&r);
    return st;
}

mcrt_status mcrt_diff(const char *test, const char *ref, const mcrt_diff_options *o,
                      mcrt_diff_result *out, size_t out_size, char *error, size_t error_size)
{
    mcrt_diff_options opt;
    mcrt_diff_result res;
    mc_diag d;
    mcrt_status st;

    d.msg[0] = '\0';
    memset(&res, 0, sizeof res);
    mcrt_diff_options_init(&opt);
    if (!test || !ref || !o || !out)
        st = mc_fail(&d, MCRT_ERR_INVALID, "mcrt_diff: %s is NULL",
                     !test ? "test" : !ref ? "ref" : !o ? "options" : "out");
    else if (!mc_sized_read(&opt, sizeof opt, o, o->size))
        st = mc_fail(&d, MCRT_ERR_INVALID,
                     "mcrt_diff_options.size is %zu: not set by mcrt_diff_options_init, or options "
                     "of a newer mcrt.h that this library (%s, %zu bytes) does not know are set",
                     o->size, MCRT_VERSION, sizeof opt);
    else
        st = compare(test, ref, &opt, &res, &d);
    if (out)
        mc_sized_write(out, out_size, &res, sizeof res);
    if (error && error_size)
        snprintf(error, error_size, "%s", st != MCRT_OK ? d.msg : "");
    return st;
}
