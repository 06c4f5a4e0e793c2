/* plastic.c: a Lambertian base under a clear dielectric coat (plastic, varnish, glazed paint):
 * the coat reflects as a smooth (delta) or GGX dielectric interface, the base diffusely, and the
 * light between them bounces any number of times before it leaves.
 * Reference: Jakob, Mitsuba 0.6 "plastic" (with nonlinear = true), whose diffuse term this is;
 * the coat made rough as in Mitsuba's "roughplastic"; layering in the manner of Weidlich and
 * Wilkie 2007, "Arbitrarily Layered Micro-Facet Surfaces". */
#include "bsdf/bsdf_impl.h"

#include <stdio.h>

#include "sample/warp.h"

/* The model, for a coat of relative ior η over a base of albedo ρ (Fresnel F(μ) from outside,
 * its cosine-weighted average F̄ = mc_fresnel_diffuse(η)):
 *
 *   f = f_coat + A (1 − F(cosθo)) (1 − F(cosθi)) / (π (1 − F̄)),   A = ρ (1 − F̄ᵢ) / (1 − ρ F̄ᵢ).
 *
 * Light entering through the coat, 1 − F(cosθo), is scattered by the base; a diffuse field
 * inside leaves with total probability 1 − F̄ᵢ and is otherwise reflected back down, so the
 * bounces sum to the geometric series A. It leaves with radiance ∝ (1 − F(cosθi)), normalised
 * by ∫(1 − F) cos/π dω = 1 − F̄. By reciprocity of the interface (a diffuse field's
 * transmittance is η² times smaller from the dense side), F̄ᵢ = 1 − (1 − F̄)/η². f is reciprocal
 * and its directional albedo is F(cosθo) + (1 − F(cosθo))·A for the smooth coat: exactly 1 at
 * ρ = 1 (white furnace), less otherwise.
 *
 * Rough coat: f_coat = F(wo·wm) D G2 / (4 cosθo cosθi) keeps the smooth coat's (1 − F) for the
 * light it lets through. Fresnel's convexity makes the rough coat reflect slightly more than
 * F(cosθo) where GGX's shadowing loses little: measured (quadrature, η in [1.05, 4], α in
 * [0.03, 1]), the excess peaks at 7e-4·(1 − F(cosθo)) near α = 0.1, θo = 47°. ρ is therefore
 * capped at 0.999, which lowers A below 1 by 1e-3 (η → 1) to 1e-2 (η = 3) and keeps every
 * directional albedo below 1 (MC_PLASTIC_MAX_ALBEDO, material.h). */

/* A for base albedo rho: the geometric series of bounces between base and coat (above). */
static float bounce_albedo(float rho, double fdr_in)
{
    return (float)(rho * (1.0 - fdr_in) / (1.0 - rho * fdr_in));
}

static void plastic_init(struct bsdf *b, const struct material *m)
{
    double fdr, fdr_in;
    (void)m;
    /* The model needs a coat denser than the outside; ior < 1 acts as 1 (no coat). */
    b->ior = fmaxf(b->ior, 1.0f);
    b->color = v3_min(v3_max(b->color, v3s(0.0f)), v3s(MC_PLASTIC_MAX_ALBEDO));
    fdr = mc_fresnel_diffuse(b->ior);
    fdr_in = 1.0 - (1.0 - fdr) / ((double)b->ior * b->ior);
    b->fdr = (float)fdr;
    b->albedo = v3(bounce_albedo(b->color.x, fdr_in), bounce_albedo(b->color.y, fdr_in),
                   bounce_albedo(b->color.z, fdr_in));
}

/* The diffuse term of f for wo, wi on the front (z > 0). */
static vec3 diffuse(const struct bsdf *b, vec3 wo, vec3 wi)
{
    float t = (1.0f - mc_fresnel_dielectric(wo.z, b->ior)) * (1.0f - mc_fresnel_dielectric(wi.z, b->ior));
    return v3_scale(b->albedo, t * MC_INV_PI / (1.0f - b->fdr));
}

/* The probability of sampling the coat: its reflectance F(cosθo) against the diffuse albedo
 * (1 − F(cosθo))·A, averaged over the channels. Exact lobe albedos for the smooth coat; F is a
 * proxy for the rough coat's. */
static float coat_probability(const struct bsdf *b, float cos_o)
{
    float f = mc_fresnel_dielectric(cos_o, b->ior), s = f + (1.0f - f) * v3_avg(b->albedo);
    return s > 0.0f ? f / s : 0.0f;
}

static vec3 plastic_eval(const struct bsdf *b, vec3 wo, vec3 wi, enum mc_transport mode)
{
    vec3 f;
    (void)mode; /* reflection only: the same f either way */
    if (!(wo.z * wi.z > 0.0f))
        return v3s(0.0f);
    wo = mc_front(wo);
    wi = mc_front(wi);
    f = diffuse(b, wo, wi);
    if (b->alpha > 0.0f) { /* the smooth coat is a delta lobe: not part of eval (bsdf.h) */
        float c, coat = mc_ggx_reflection(b->alpha, wo, wi, &c);
        f = v3_add(f, v3s(mc_fresnel_dielectric(c, b->ior) * coat));
    }
    return f;
}

static float plastic_pdf(const struct bsdf *b, vec3 wo, vec3 wi)
{
    float pc, pdf;
    if (!(wo.z * wi.z > 0.0f))
        return 0.0f;
    wo = mc_front(wo);
    wi = mc_front(wi);
    pc = coat_probability(b, wo.z);
    pdf = (1.0f - pc) * mc_warp_cosine_hemisphere_pdf(wi.z);
    return b->alpha > 0.0f ? pdf + pc * mc_ggx_reflection_pdf(b->alpha, wo, wi) : pdf;
}

static int plastic_sample(const struct bsdf *b, vec3 wo, float uc, vec2 u, enum mc_transport mode,
                          struct bsdf_sample *out)
{
    vec3 w = mc_front(wo), wi;
    float pc, pdf;
    if (wo.z == 0.0f)
        return 0;
    pc = coat_probability(b, w.z);
    if (uc < pc) {
        if (b->alpha == 0.0f) /* the smooth coat's delta reflection, chosen with probability pc */
            return mc_specular_reflection(wo, v3s(mc_fresnel_dielectric(w.z, b->ior) / pc), pc, out);
        wi = mc_reflect(w, mc_ggx_sample_visible(b->alpha, w, u));
        if (wi.z <= 0.0f)
            return 0;
    } else {
        wi = mc_warp_cosine_hemisphere(u);
        if (wi.z == 0.0f)
            return 0; /* the disk's rim: zero density (diffuse.c) */
    }
    /* Either way wi could have come from both non-delta lobes: the weight is the whole f over
     * the mixture density (one-sample MIS with the balance heuristic, Veach 1997 §9.2.4). */
    pdf = plastic_pdf(b, w, wi);
    if (!(pdf > 0.0f))
        return 0;
    out->wi = wo.z > 0.0f ? wi : mc_mirror_z(wi);
    out->pdf = pdf;
    out->weight = v3_scale(plastic_eval(b, w, wi, mode), wi.z / pdf);
    out->delta = 0;
    out->eta = 1.0f;
    return 1;
}

static int plastic_complete(struct material *m, unsigned given, struct mc_material_problem *p)
{
    (void)given;
    if (m->ior >= 1.0f)
        return 1;
    p->key = MC_KEY_IOR;
    p->at_number = 1;
    snprintf(p->what, sizeof p->what, "'ior' of a plastic's coat must be at least 1");
    return 0;
}

/* Smooth and rough coats over a coloured base, and a white base (whose albedo stays below 1:
 * plastic.c's cap). */
static const struct mc_material_example examples[] = {
    {{0.8f, 0.4f, 0.1f}, 1.5f, 0.0f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{0.8f, 0.4f, 0.1f}, 1.5f, 0.1f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{0.8f, 0.4f, 0.1f}, 1.5f, 1.0f, {0, 0, 0}, {0, 0, 0}, 0.0},
    {{1.0f, 1.0f, 1.0f}, 1.5f, 0.3f, {0, 0, 0}, {0, 0, 0}, 0.0},
};

const struct mc_material_ops mc_material_ops_plastic = {
    "glossy plastic", MC_DELTA_NEVER, 1, plastic_complete, NULL, plastic_init, plastic_eval, plastic_pdf,
    plastic_sample, examples, (int)(sizeof examples / sizeof examples[0])};
