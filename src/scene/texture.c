/* texture.c: evaluation of the textures of MC_TEXTURES (texture.h). */
#include "scene/texture.h"

#include <math.h>

const char *const mc_texture_names[TEXTURE_KIND_COUNT + 1] = {MC_TEXTURES(MC_NAMES_IDENT)[TEXTURE_KIND_COUNT] = NULL};

/* Texel i of a row or column of n, for i in [-1, n − 1], and the next, wrapping across the
 * edge (no division: this runs at every textured hit). */
static void wrap_pair(int i, int n, int *i0, int *i1)
{
    *i0 = i < 0 ? n - 1 : i;
    *i1 = *i0 + 1 == n ? 0 : *i0 + 1;
}

static vec3 texel(const float *rgb, int w, int x, int y)
{
    const float *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)x);
    return v3(p[0], p[1], p[2]);
}

vec3 mc_texture_bilinear(const float *rgb, int w, int h, float s, float t)
{
    /* Continuous texel coordinates with texel centres at integers + ½ (Heckbert 1989): x to the
     * right, y down from the top row. Reduced to one period first, so that huge s or t keep their
     * fraction within float rounding of the product: fs, ft in [0, 1) exactly (a float minus its
     * floor is exact in double), so x0 and y0 lie in [-1, w − 1] and [-1, h − 1]. */
    double fs = s - floor(s), ft = t - floor(t);
    double x = fs * w - 0.5, y = (1.0 - ft) * h - 0.5;
    double x0 = floor(x), y0 = floor(y);
    float ax = (float)(x - x0), ay = (float)(y - y0);
    int i0, i1, j0, j1;
    wrap_pair((int)x0, w, &i0, &i1);
    wrap_pair((int)y0, h, &j0, &j1);
    vec3 a = texel(rgb, w, i0, j0), b = texel(rgb, w, i1, j0);
    vec3 c = texel(rgb, w, i0, j1), e = texel(rgb, w, i1, j1);
    vec3 top = v3_madd(a, v3_sub(b, a), ax), bottom = v3_madd(c, v3_sub(e, c), ax);
    return v3_madd(top, v3_sub(bottom, top), ay);
}

vec3 mc_texture_eval(const struct texture *t, vec2 uv)
{
    float s = uv.x * t->scale.x + t->offset.x, tt = uv.y * t->scale.y + t->offset.y;
    switch (t->kind) {
    case TEXTURE_IMAGE:
        return mc_texture_bilinear(t->rgb, t->w, t->h, s, tt);
    case TEXTURE_CHECKER:
    default:
        return fmod(floor(s) + floor(tt), 2.0) == 0.0 ? t->even : t->odd;
    }
}

mcrt_status mc_texture_check(const struct texture *t, const char *origin, mc_diag *d)
{
    size_t i, n = (size_t)t->w * (size_t)t->h * 3;
    if (t->kind != TEXTURE_IMAGE)
        return MCRT_OK;
    for (i = 0; i < n; i++) {
        float v = t->rgb[i];
        const char *what = isnan(v) ? "a NaN value" : v < 0.0f ? "a negative value"
                           : !(v <= 1.0f)    ? "a value above 1"
                                             : NULL;
        if (what)
            return mc_fail(d, MCRT_ERR_PARSE,
                           "%s: texture '%s': pixel (%d, %d) has %s (a texture is a reflectance "
                           "or a roughness, in [0, 1])",
                           origin, t->name, (int)(i / 3 % (size_t)t->w), (int)(i / 3 / (size_t)t->w),
                           what);
    }
    return MCRT_OK;
}
