/* bsdf_util.h: a BSDF seen from a fixed wo as the chi-square harness (chi2.h) wants it, shared by
 * the BSDF tests. */
#ifndef MCRT_TEST_BSDF_UTIL_H
#define MCRT_TEST_BSDF_UTIL_H

#include "bsdf/bsdf.h"
#include "chi2.h"

static inline vec2 rand2(pcg32 *r)
{
    float a = pcg32_float(r);
    return v2(a, pcg32_float(r));
}

struct bsdf_case { struct bsdf b; vec3 wo; };

/* A sampled direction; delta samples are not in the pdf, so they count as missing, like failed
 * draws. */
static inline int bsdf_case_sample(void *ctx, pcg32 *rng, vec3 *w)
{
    const struct bsdf_case *c = (const struct bsdf_case *)ctx;
    struct bsdf_sample s;
    float uc = pcg32_float(rng);
    if (!mc_bsdf_sample(&c->b, c->wo, uc, rand2(rng), MC_RADIANCE, &s) || s.delta)
        return 0;
    *w = s.wi;
    return 1;
}
static inline double bsdf_case_pdf(void *ctx, vec3 wi)
{
    const struct bsdf_case *c = (const struct bsdf_case *)ctx;
    return mc_bsdf_pdf(&c->b, c->wo, wi);
}

#endif
