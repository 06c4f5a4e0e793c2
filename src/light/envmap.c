/* envmap.c: latitude-longitude environment maps and their importance sampling (see envmap.h). */
#include "light/envmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

/* Rec. 709 luminance: what the eye weighs, the quantity the distribution follows. */
static float luminance(const float *c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

mcrt_status mc_envmap_build(struct envmap *m, const float *rgb, int w, int h, const char *name,
                            mc_diag *d)
{
    size_t n, i;
    float *f;
    mcrt_status st;
    int x, y;
    memset(m, 0, sizeof *m);
    if (w < 1 || h < 1)
        return mc_fail(d, MCRT_ERR_PARSE, "%s: an environment map needs at least one pixel", name);
    n = (size_t)w * (size_t)h;
    for (i = 0; i < 3 * n; i++)
        if (!(rgb[i] >= 0.0f) || isinf(rgb[i])) {
            x = (int)(i / 3 % (size_t)w);
            y = (int)(i / 3 / (size_t)w);
            return mc_fail(d, MCRT_ERR_PARSE, "%s: pixel (%d, %d) has a %s value: an environment map "
                           "holds radiance, finite and not negative", name, x, y,
                           isnan(rgb[i]) ? "NaN" : isinf(rgb[i]) ? "infinite" : "negative");
        }
    m->rgb = mc_malloc(3 * n * sizeof *m->rgb);
    f = mc_malloc(n * sizeof *f);
    if (!m->rgb || !f) {
        free(f);
        mc_envmap_free(m);
        return mc_fail(d, MCRT_ERR_NOMEM, "%s: out of memory", name);
    }
    memcpy(m->rgb, rgb, 3 * n * sizeof *m->rgb);
    m->w = w;
    m->h = h;
    for (y = 0; y < h; y++) {
        /* The row's solid angle per pixel, exact: (2π/w)·(cos θ0 − cos θ1); the sampling weight
         * uses sin θ at the row's centre (pbrt-v3), the power the exact solid angle. */
        double t0 = MC_PI * y / h, t1 = MC_PI * (y + 1) / h;
        double s = sin(MC_PI * (y + 0.5) / h), dw = 2.0 * MC_PI / w * (cos(t0) - cos(t1));
        for (x = 0; x < w; x++) {
            const float *c = &m->rgb[3 * ((size_t)y * (size_t)w + (size_t)x)];
            f[(size_t)y * (size_t)w + (size_t)x] = luminance(c) * (float)s;
            double mean = (c[0] + c[1] + c[2]) / 3.0;
            m->power_integral += dw * mean;
            m->square_integral += dw * mean * mean;
        }
    }
    st = mc_distrib2d_build(&m->dist, f, (size_t)w, (size_t)h, d);
    free(f);
    if (st != MCRT_OK)
        mc_envmap_free(m);
    return st;
}

void mc_envmap_free(struct envmap *m)
{
    free(m->rgb);
    mc_distrib2d_free(&m->dist);
    memset(m, 0, sizeof *m);
}

size_t mc_envmap_bytes(const struct envmap *m)
{
    size_t w = (size_t)m->w, h = (size_t)m->h;
    return w * h * (3 + 1) * sizeof(float) + h * (w + 1) * sizeof(double)
           + h * (sizeof(float) + sizeof(double) + sizeof(struct mc_distrib1d)) + sizeof(double);
}

vec3 mc_envmap_direction(float u, float v)
{
    float theta = MC_PI * v, phi = 2.0f * MC_PI * (u - 0.5f), st = sinf(theta);
    return v3(st * sinf(phi), cosf(theta), -st * cosf(phi));
}

vec2 mc_envmap_uv(vec3 dir)
{
    vec2 uv;
    uv.x = atan2f(dir.x, -dir.z) * (0.5f / MC_PI) + 0.5f;
    /* θ by atan2 rather than acos(y): a float y near ±1 says little about small θ. */
    uv.y = atan2f(sqrtf(dir.x * dir.x + dir.z * dir.z), dir.y) * (1.0f / MC_PI);
    return uv;
}

/* The pixel holding (u, v), clamped into the image (u = 1 and v = 1 are edges, not outside). */
static size_t pixel(const struct envmap *m, vec2 uv)
{
    int x = (int)(uv.x * (float)m->w), y = (int)(uv.y * (float)m->h);
    x = x < 0 ? 0 : x >= m->w ? m->w - 1 : x;
    y = y < 0 ? 0 : y >= m->h ? m->h - 1 : y;
    return (size_t)y * (size_t)m->w + (size_t)x;
}

vec3 mc_envmap_eval(const struct envmap *m, vec3 dir)
{
    const float *c = &m->rgb[3 * pixel(m, mc_envmap_uv(dir))];
    return v3(c[0], c[1], c[2]);
}

/* Jacobian of (u, v) → direction: dω = 2π² sin θ du dv. */
static float jacobian_pdf(float pdf_uv, float sin_theta)
{
    return sin_theta > 0.0f ? pdf_uv / (2.0f * MC_PI * MC_PI * sin_theta) : 0.0f;
}

vec3 mc_envmap_sample(const struct envmap *m, vec2 u, float *pdf, vec3 *L)
{
    float pdf_uv;
    vec2 uv = mc_distrib2d_sample(&m->dist, u.x, u.y, &pdf_uv);
    const float *c = &m->rgb[3 * pixel(m, uv)];
    *pdf = jacobian_pdf(pdf_uv, sinf(MC_PI * uv.y));
    *L = v3(c[0], c[1], c[2]);
    return mc_envmap_direction(uv.x, uv.y);
}

float mc_envmap_pdf(const struct envmap *m, vec3 dir)
{
    vec2 uv = mc_envmap_uv(dir);
    float sin_theta = sqrtf(dir.x * dir.x + dir.z * dir.z);
    /* u = 1 and v = 1 lie on the image's edges: the distribution's own bins end below 1. */
    size_t i = pixel(m, uv);
    float x = ((float)(i % (size_t)m->w) + 0.5f) / (float)m->w;
    float y = ((float)(i / (size_t)m->w) + 0.5f) / (float)m->h;
    return jacobian_pdf(mc_distrib2d_pdf(&m->dist, x, y), sin_theta);
}
