/* test_samplers_render.c: the samplers in whole renders, through the public API: at equal spp,
 * stratified and sobol give a lower relative MSE than random on a soft-shadow scene and on a
 * depth-of-field scene, measured against a long render.
 *
 * relMSE = mean over pixels and channels of (x − ref)² / (ref² + 0.01). Pixels are rendered
 * independently, so the per-pixel terms of one render are independent given the reference, and
 * the standard error of a relMSE is the spread of its terms over √pixels. A sampler must beat
 * random by more than 3 standard errors of the difference (one-sided p ≈ 1.3e-3). The
 * reference's own error adds the same amount to every relMSE, so it can only hide a difference,
 * never create one; it is a sobol render at 32× the spp, with another seed. Each render's mean
 * must also match the reference's: no sampler may bias the image. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"
#include "render_util.h"
#include "t.h"

enum { SPP = 16, REF_SPP = 512 };

/* A disk light above and behind a plane with a sphere and a floating square casting penumbrae;
 * direct lighting only, so the light-sample dimensions carry the noise. The light is outside
 * the view. */
static const char soft_shadows[] =
    "camera { eye 0 4 5 look 0 0 0 fov 40 }\n"
    "integrator { method direct }\n"
    "quad { corner -6 0 6 edge1 12 0 0 edge2 0 0 -12 }\n"
    "sphere { center -0.6 0.7 0.3 radius 0.5 }\n"
    "quad { corner 0.3 0.9 -0.8 edge1 1.2 0 0 edge2 0 0 1.2 }\n"
    "disk { center 0 4.5 -2 normal 0 -1 0.3 radius 1.5 emit 5 }\n";

/* Emitting spheres before, at and behind the plane in focus (z = 0) over an emitting floor, seen
 * through a thin lens: only emitters seen directly (max_depth 0), so the film and lens
 * dimensions carry all the noise. */
static const char dof[] =
    "camera { eye 0 0 6 look 0 0 0 fov 40 lens_radius 0.2 }\n"
    "integrator { max_depth 0 }\n"
    "sphere { center -1.2 0 -2 radius 0.8 emit 1 0.3 0.2 }\n"
    "sphere { center 0 0 0 radius 0.5 emit 0.2 1 0.3 }\n"
    "sphere { center 1 0.3 2.5 radius 0.35 emit 0.3 0.4 1 }\n"
    "quad { corner -6 -1 6 edge1 12 0 0 edge2 0 0 -12 emit 0.3 }\n";

/* Render the scene on a 96×96 film with this sampler; the pixels (owned by the caller) or NULL. */
static float *render(const char *scene, const char *sampler, int spp, uint64_t seed, int *npix)
{
    struct t_render_opts o = {0, 0, 0, 0, NULL, NULL};
    char text[1024];
    int w = 0, h = 0;
    float *px;
    snprintf(text, sizeof text, "film { width 96 height 96 sampler %s }\n%s", sampler, scene);
    o.spp = spp;
    o.seed = seed;
    px = t_render(text, &o, &w, &h, NULL);
    *npix = w * h;
    return px;
}

struct rel_mse { double mean, se; };

/* Mean over pixels and channels of x − ref, in units of its standard error (from the spread of
 * the per-pixel differences, which are independent). */
static double bias_z(const float *x, const float *ref, int npix)
{
    double sum = 0.0, sum2 = 0.0, mean;
    int p;
    for (p = 0; p < npix; p++) {
        double d = ((double)x[3 * p] - ref[3 * p] + x[3 * p + 1] - ref[3 * p + 1] + x[3 * p + 2]
                    - ref[3 * p + 2]) / 3.0;
        sum += d;
        sum2 += d * d;
    }
    mean = sum / npix;
    return mean / sqrt(fmax(sum2 / npix - mean * mean, 1e-300) / (npix - 1));
}

static struct rel_mse rel_mse(const float *x, const float *ref, int npix)
{
    double sum = 0.0, sum2 = 0.0;
    struct rel_mse m;
    int p, c;
    for (p = 0; p < npix; p++) {
        double t = 0.0;
        for (c = 0; c < 3; c++) {
            double d = (double)x[3 * p + c] - ref[3 * p + c];
            t += d * d / ((double)ref[3 * p + c] * ref[3 * p + c] + 0.01);
        }
        t /= 3.0;
        sum += t;
        sum2 += t * t;
    }
    m.mean = sum / npix;
    m.se = sqrt(fmax(sum2 / npix - m.mean * m.mean, 0.0) / (npix - 1));
    return m;
}

static void compare(const char *name, const char *scene)
{
    static const char *const kinds[3] = {"random", "stratified", "sobol"};
    struct rel_mse m[3];
    double z[3];
    float *ref, *img;
    int npix = 0, k, n;
    ref = render(scene, "sobol", REF_SPP, 1001, &npix);
    T_CHECK(ref != NULL, "%s: reference render failed", name);
    if (!ref)
        return;
    for (k = 0; k < 3; k++) {
        img = render(scene, kinds[k], SPP, 7, &n);
        T_CHECK(img != NULL && n == npix, "%s: %s render failed", name, kinds[k]);
        if (!img) {
            free(ref);
            return;
        }
        m[k] = rel_mse(img, ref, npix);
        z[k] = bias_z(img, ref, npix);
        free(img);
    }
    T_NOTE("%s, %d spp (reference sobol %d spp): relMSE random %.3e ± %.1e, stratified %.3e ± %.1e "
           "(%.2fx lower), sobol %.3e ± %.1e (%.2fx lower)",
           name, SPP, REF_SPP, m[0].mean, m[0].se, m[1].mean, m[1].se, m[0].mean / m[1].mean, m[2].mean,
           m[2].se, m[0].mean / m[2].mean);
    T_NOTE("%s: image mean minus the reference's, in standard errors: random %+.2f, stratified %+.2f, "
           "sobol %+.2f", name, z[0], z[1], z[2]);
    /* No sampler may shift the image: each mean within 4 standard errors (two-sided p ≈ 6e-5). */
    for (k = 0; k < 3; k++)
        T_CHECK(fabs(z[k]) <= 4.0, "%s: %s image mean is off by %.1f standard errors", name, kinds[k], z[k]);
    for (k = 1; k < 3; k++)
        T_CHECK(m[0].mean - m[k].mean > 3.0 * hypot(m[0].se, m[k].se),
                "%s: %s relMSE %.3e not significantly below random's %.3e", name, kinds[k], m[k].mean,
                m[0].mean);
    free(ref);
}

int main(void)
{
    compare("soft shadows", soft_shadows);
    compare("depth of field", dof);
    return t_done();
}
