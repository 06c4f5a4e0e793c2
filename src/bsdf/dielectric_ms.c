/* dielectric_ms.c: energy compensation of rough glass for the light that single-scattering GGX
 * loses between microfacets: an added diffuse-like lobe built from tabulated directional albedos.
 * Reference: Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks" (SIGGRAPH
 * course), sections on energy compensation and its dielectric extension.
 *
 * Notation: side 0 is the outside (ior n_0 = 1), side 1 the inside (n_1 = ior); wo on side a,
 * wi on side b. The radiance BSDF of the single-scattering model, f_ss, and of this lobe obey
 * f(wo, wi)/n_a² = f(wi, wo)/n_b² (Veach 1997 §5.2), and the energy albedo seen from wo is
 * E_a(μo) = ∫ f(wo, wi) (n_b/n_a)² |μi| dωi (the flux leaving for both sides; the (n_b/n_a)²
 * undoes radiance's 1/η² on crossing); a non-absorbing interface must have E_a ≡ 1.
 *
 * The added lobe is f_ms(wo, wi) = n_a² C_ab (1 − Ê_a(μo)) (1 − Ê_b(μi)) with C symmetric, so it
 * is reciprocal. With m_b = ∫ (1 − Ê_b(μ)) |μ| dω = π (1 − Ê_avg,b), its energy albedo is
 * (1 − Ê_a(μo)) Σ_b n_b² C_ab m_b, which must be 1 − Ê_a(μo) for both a:
 *     n_0² C_00 m_0 + n_1² C_01 m_1 = 1,   n_0² C_10 m_0 + n_1² C_11 m_1 = 1.
 * Three unknowns, two equations: the share t_a = n_b² C_ab m_b (b ≠ a) of side a's compensated
 * energy that crosses is free on one side, and reciprocity fixes the other: t_1 n_1² m_1 =
 * t_0 n_0² m_0. As Kulla and Conty we split by the smooth interface's hemispherical Fresnel
 * transmittance seen from the rarer side, t = 1 − F̄ (the share a random, cosine-distributed
 * walk among the facets would end up crossing), and derive the denser side's share from the
 * relation above (clamped to 1, reducing both, should that side lose too little). */
#include "bsdf/bsdf_impl.h"

#include "sample/warp.h"

enum { N = MC_MS_NODES, QUAD = 64 };

/* The single-scattering energy albedo from a wo at cosine mu on the side where the relative ior
 * of the far side is eta: the expectation over the visible normals wm of wo (density D_wo) of
 * the weight of mc_dielectric_sample with radiance's 1/η² undone, averaged over its lobe choice:
 * F·G2/G1 for the reflection and (1 − F)·G2/G1 for the refraction, each 0 when it leaves on the
 * wrong side. Midpoint rule in (v, φm) with tanθm = α tan v, where D cosθm dω = d(sin²v) dφ/2π
 * (GGX's cumulative distribution), so the lobe's long tail, where the loss happens, gets its
 * share of nodes at any α; wo lies in the xz plane, so φm ∈ [0, π] covers the integral twice.
 * Deterministic; within ~1e-3 of 1e6-sample estimates (test_microfacet). */
static double single_scattering_albedo(float alpha, float eta, double mu)
{
    vec3 wo = v3((float)sqrt(1.0 - mu * mu), 0.0f, (float)mu);
    double sum = 0.0;
    int i, j;
    for (i = 0; i < QUAD; i++) {
        double v = (i + 0.5) / QUAD * MC_PI / 2, tm = alpha * tan(v), cm = 1.0 / sqrt(1.0 + tm * tm);
        double dv = 2.0 * sin(v) * cos(v) * (MC_PI / 2 / QUAD); /* d(sin²v) */
        for (j = 0; j < QUAD; j++) {
            double phi = (j + 0.5) / QUAD * MC_PI, sm = tm * cm;
            vec3 wm = v3((float)(sm * cos(phi)), (float)(sm * sin(phi)), (float)cm), wr, wt;
            double c = v3_dot(wo, wm), f, w = 0.0;
            if (c <= 0.0)
                continue;
            f = mc_fresnel_dielectric((float)c, eta);
            wr = mc_reflect(wo, wm);
            if (wr.z > 0.0f)
                w += f * mc_ggx_g2(alpha, wo, wr);
            if (f < 1.0 && mc_refract(wo, wm, eta, &wt) && wt.z < 0.0f)
                w += (1.0 - f) * mc_ggx_g2(alpha, wo, wt);
            /* The weight w/G1 times D_wo dωm = G1 (wo·wm) D dωm / μ = G1 (wo·wm)/(μ cosθm) ·
             * d(sin²v) dφ/2π: the G1 cancel. */
            sum += w * c / (cm * mu) * dv / QUAD;
        }
    }
    return sum;
}

static double node(int k) { return (double)k / (N - 1); }

/* ∫ 4x³ g(x) dx over [x_k, x_k+1] for g linear from g0 to g1: 2∫ g μ dμ with μ = x². */
static double segment_moment(int k, double g0, double g1)
{
    double x0 = node(k), x1 = node(k + 1), b = (g1 - g0) / (x1 - x0), a = g0 - b * x0;
    return a * (x1 * x1 * x1 * x1 - x0 * x0 * x0 * x0) + 0.8 * b * (pow(x1, 5.0) - pow(x0, 5.0));
}

void mc_dielectric_ms_build(struct mc_dielectric_ms *ms, float alpha, float ior)
{
    double n2[2] = {1.0, (double)ior * ior}, m[2], w[2], cross, t[2];
    int s, k, rare = ior >= 1.0f ? 0 : 1;
    for (s = 0; s < 2; s++) {
        float eta = s == 0 ? ior : 1.0f / ior;
        double seg[N - 1], loss = 0.0, acc = 0.0;
        w[s] = 0.0;
        for (k = 0; k < N; k++) {
            /* μ = 0 itself has no microfacet response; 1e-5 is its limit to ~1e-5. */
            double mu = fmax(node(k) * node(k), 1e-5);
            ms->e[s][k] = (float)fmin(fmax(single_scattering_albedo(alpha, eta, mu), 0.0), 1.0);
        }
        /* m_s/π = 2∫(1 − Ê)μ dμ exactly for the interpolated Ê, so that the lobe's energy is
         * exactly 1 − Ê_a(μo) of the table. Sampling uses, per segment, the larger end value of
         * 1 − Ê times |μ| (weights stay within a segment's variation of 1). */
        for (k = 0; k < N - 1; k++) {
            double l0 = 1.0 - ms->e[s][k], l1 = 1.0 - ms->e[s][k + 1];
            loss += segment_moment(k, l0, l1);
            seg[k] = fmax(l0, l1) * (pow(node(k + 1), 4.0) - pow(node(k), 4.0));
            w[s] += seg[k];
        }
        m[s] = MC_PI * loss;
        for (k = 0; k < N - 1; k++) {
            ms->cdf[s][k] = w[s] > 0.0 ? (float)(acc / w[s]) : 0.0f;
            acc += seg[k];
        }
        ms->cdf[s][N - 1] = 1.0f;
        ms->norm[s] = w[s] > 0.0 ? (float)(1.0 / (MC_PI * w[s])) : 0.0f;
    }
    /* C_01 = t_rare / (n_dense² m_dense); the dense side's share t_rare n_rare² m_rare/(n_dense²
     * m_dense). A side without loss takes and gives nothing. */
    t[0] = t[1] = 0.0;
    cross = 0.0;
    if (m[0] > 0.0 && m[1] > 0.0) {
        int dense = 1 - rare;
        t[rare] = 1.0 - mc_fresnel_diffuse(rare == 0 ? (double)ior : 1.0 / ior);
        t[dense] = t[rare] * n2[rare] * m[rare] / (n2[dense] * m[dense]);
        if (t[dense] > 1.0) {
            t[rare] /= t[dense];
            t[dense] = 1.0;
        }
        cross = t[0] / (n2[1] * m[1]);
    }
    for (s = 0; s < 2; s++) {
        ms->t[s] = (float)t[s];
        ms->c[s][s] = m[s] > 0.0 ? (float)((1.0 - t[s]) / m[s]) : 0.0f; /* n_s² C_ss */
        ms->c[s][1 - s] = (float)(n2[s] * cross);
    }
    ms->ready = 1;
}

/* The segment of the table holding cosine mu. */
static int segment(float mu)
{
    int k = (int)(sqrtf(fminf(fabsf(mu), 1.0f)) * (N - 1));
    return k > N - 2 ? N - 2 : k;
}

float mc_dielectric_ms_albedo(const struct mc_dielectric_ms *ms, int side, float mu)
{
    int k = segment(mu);
    float f = sqrtf(fminf(fabsf(mu), 1.0f)) * (N - 1) - (float)k;
    return ms->e[side][k] + f * (ms->e[side][k + 1] - ms->e[side][k]);
}

float mc_dielectric_ms_eval(const struct mc_dielectric_ms *ms, vec3 wo, vec3 wi)
{
    int a = wo.z < 0.0f, b = wi.z < 0.0f;
    /* The product first: it is the same float either way round, so reflection stays exactly
     * reciprocal. */
    return ms->c[a][b] * ((1.0f - mc_dielectric_ms_albedo(ms, a, wo.z)) * (1.0f - mc_dielectric_ms_albedo(ms, b, wi.z)));
}

float mc_dielectric_ms_pdf(const struct mc_dielectric_ms *ms, vec3 wo, vec3 wi)
{
    int a = wo.z < 0.0f, b = wi.z < 0.0f, k = segment(wi.z);
    float side = a == b ? 1.0f - ms->t[a] : ms->t[a];
    float l = fmaxf(1.0f - ms->e[b][k], 1.0f - ms->e[b][k + 1]);
    return side * l * fabsf(wi.z) * ms->norm[b];
}

int mc_dielectric_ms_sample(const struct mc_dielectric_ms *ms, vec3 wo, float uc, vec2 u, vec3 *wi)
{
    int a = wo.z < 0.0f, cross = uc < ms->t[a], b = cross ? 1 - a : a, lo = 0, hi = N - 1;
    const float *cdf = ms->cdf[b];
    double x0, x1, mu, r, phi;
    /* The segment k with cdf[k] <= u.x < cdf[k + 1], then μ² uniform in it (density ∝ |μ|). */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (u.x < cdf[mid])
            hi = mid;
        else
            lo = mid;
    }
    if (!(cdf[lo + 1] > cdf[lo]))
        return 0; /* an empty segment: only reached when no loss is tabulated at all */
    x0 = node(lo);
    x1 = node(lo + 1);
    x0 *= x0 * x0 * x0;
    x1 *= x1 * x1 * x1;
    mu = sqrt(x0 + (u.x - cdf[lo]) / (cdf[lo + 1] - cdf[lo]) * (x1 - x0));
    mu = fmin(fmax(mu, 1e-7), 1.0);
    r = sqrt(fmax(0.0, 1.0 - mu * mu));
    phi = 2.0 * MC_PI * u.y;
    /* wo's side is +z on the outside; crossing flips the sign of wo's side. */
    *wi = v3((float)(r * cos(phi)), (float)(r * sin(phi)), (float)((b == 0) ? mu : -mu));
    return 1;
}
