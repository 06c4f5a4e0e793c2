/* diffuse.c: the Lambertian BSDF, f = albedo/π, sampled by Malley's cosine-weighted method
 * (pbrt-v4 §9.2, DiffuseBxDF). */
#include "bsdf/bsdf_impl.h"

#include "sample/warp.h"

/* Opaque: light only scatters back into the hemisphere wo came from, whichever face that is.
 * A direction in the tangent plane (z = 0) has zero cosine and gets no density. */
static int same_side(vec3 wo, vec3 wi) { return wo.z * wi.z > 0.0f; }

static vec3 diffuse_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    (void)mode; /* reflection only: the same f either way */
    return same_side(wo, wi) ? v3_scale(b->color, MC_INV_PI) : v3s(0.0f);
}

static float diffuse_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    (void)b;
    return same_side(wo, wi) ? mc_warp_cosine_hemisphere_pdf(fabsf(wi.z)) : 0.0f;
}

static int diffuse_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                          struct bsdf_sample *out)
{
    vec3 wi;
    (void)uc;
    (void)mode;
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

/* A coloured albedo, and white (the furnace: every weight is exactly 1). */
static const struct mc_material_example examples[] = {
    {{0.8f, 0.5f, 0.2f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{1.0f, 1.0f, 1.0f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 1e-6},
};

const struct mc_material_ops mc_material_ops_diffuse = {
    "diffuse reflector", MC_DELTA_NEVER, 0, NULL, NULL, NULL, diffuse_eval, diffuse_pdf, diffuse_sample,
    examples, (int)(sizeof examples / sizeof examples[0])};
