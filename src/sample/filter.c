/* filter.c: box, tent and truncated Gaussian pixel filters, sampled exactly (see filter.h).
 * Reference: Ernst et al. 2006, "Filter Importance Sampling"; pbrt-v4 §8.8. */
#include "sample/filter.h"

#include <math.h>

const char *const mc_filter_names[FILTER_COUNT + 1] = {MC_FILTERS(MC_NAMES_ENTRY)
                                                       [FILTER_COUNT] = NULL};

#define GAUSS_SIGMA 0.5f
#define GAUSS_RADIUS 1.5f

/* 1 − e^{−R²/2σ²}: the mass of the untruncated Gaussian inside the disk, R = 3σ. */
static float gauss_mass(void)
{
    return -expm1f(-0.5f * (GAUSS_RADIUS * GAUSS_RADIUS) / (GAUSS_SIGMA * GAUSS_SIGMA));
}

/* Inverse CDF of the tent 1 − |x| on [-1, 1] (pbrt-v4 SampleTent, in one piece per half):
 * F(x) = (1 + x)²/2 for x ≤ 0 and 1 − (1 − x)²/2 above. */
static float tent_inverse(float u)
{
    return u < 0.5f ? sqrtf(2.0f * u) - 1.0f : 1.0f - sqrtf(2.0f - 2.0f * u);
}

vec2 mc_filter_sample(enum filter_kind k, vec2 u)
{
    float r, phi;
    switch (k) {
    case FILTER_TENT:
        return v2(tent_inverse(u.x), tent_inverse(u.y));
    case FILTER_GAUSSIAN:
        /* The radius has CDF F(r) = (1 − e^{−r²/2σ²}) / (1 − e^{−R²/2σ²}) on [0, R]; its inverse
         * r = σ·√(−2 ln(1 − u·(1 − e^{−R²/2σ²}))) is written with log1p to keep small radii
         * accurate. Polar coordinates take strata of u to annular sectors: the map is smooth
         * and its only seam, u.y = 0 against 1, joins the same angle. */
        r = GAUSS_SIGMA * sqrtf(-2.0f * log1pf(-u.x * gauss_mass()));
        phi = 2.0f * MC_PI * u.y;
        return v2(r * cosf(phi), r * sinf(phi));
    case FILTER_BOX:
        break;
    }
    /* u − ½ is exact for u on pcg32's 2^-24 grid, and (x + ½) + (u − ½) then rounds like x + u. */
    return v2(u.x - 0.5f, u.y - 0.5f);
}

float mc_filter_pdf(enum filter_kind k, vec2 o)
{
    float r2;
    switch (k) {
    case FILTER_TENT:
        return fmaxf(0.0f, 1.0f - fabsf(o.x)) * fmaxf(0.0f, 1.0f - fabsf(o.y));
    case FILTER_GAUSSIAN:
        r2 = o.x * o.x + o.y * o.y;
        if (!(r2 < GAUSS_RADIUS * GAUSS_RADIUS))
            return 0.0f;
        return expf(-0.5f * r2 / (GAUSS_SIGMA * GAUSS_SIGMA))
               / (2.0f * MC_PI * GAUSS_SIGMA * GAUSS_SIGMA * gauss_mass());
    case FILTER_BOX:
        break;
    }
    return fabsf(o.x) <= 0.5f && fabsf(o.y) <= 0.5f ? 1.0f : 0.0f;
}

float mc_filter_radius(enum filter_kind k)
{
    switch (k) {
    case FILTER_TENT:
        return 1.0f;
    case FILTER_GAUSSIAN:
        return GAUSS_RADIUS;
    case FILTER_BOX:
        break;
    }
    return 0.5f;
}
