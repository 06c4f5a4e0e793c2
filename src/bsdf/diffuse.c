/* diffuse.c: the Lambertian BSDF, f = albedo/π, sampled by Malley's cosine-weighted method
 * (pbrt-v4 §9.2, DiffuseBxDF). */
#include "bsdf/bsdf_impl.h"

#include "sample/warp.h"

/* Opaque: light only scatters back into the hemisphere wo came from, whichever face that is.
 * A direction in the tangent plane (z = 0) has zero cosine and gets no density. */
static int same_side(vec3 wo, vec3 wi) { return wo.z * wi.z > 0.0f; }

vec3 mc_diffuse_eval(const struct bsdf *b, vec3 wo, vec3 wi)
{
    return same_side(wo, wi) ? v3_scale(b->color, MC_INV_PI) : v3s(0.0f);
}

float mc_diffuse_pdf(vec3 wo, vec3 wi)
{
    return same_side(wo, wi) ? mc_warp_cosine_hemisphere_pdf(fabsf(wi.z)) : 0.0f;
}

int mc_diffuse_sample(const struct bsdf *b, vec3 wo, vec2 u, struct bsdf_sample *out)
{
    vec3 wi;
    if (wo.z == 0.0f)
        return 0; /* grazing: no side to scatter into */
    wi = mc_warp_cosine_hemisphere(u);
    if (wo.z < 0.0f)
        wi.z = -wi.z; /* back face: mirror the lobe */
    /* The disk's rim lifts to wi.z = 0, where the pdf is 0 and f·cos/pdf would be 0/0
     * (the NaN of mmp/pbrt-v4#313). */
    if (wi.z == 0.0f)
        return 0;
    out->wi = wi;
    out->pdf = mc_warp_cosine_hemisphere_pdf(fabsf(wi.z));
    out->weight = b->color; /* (albedo/π)·cosθ / (cosθ/π) */
    out->delta = 0;
    out->eta = 1.0f;
    return 1;
}
