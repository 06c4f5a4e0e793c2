/* test_materials.c: what holds for every material, over every kind of the material table
 * (src/bsdf/materials.def) and each representative parameter set its ops supply, so that a new
 * kind is tested without new test code: sampling against the pdf (chi-square); agreement of
 * sample, eval and pdf in both transport modes; reciprocity in the form of the adjoint,
 * f_radiance(wo, wi) = f_importance(wi, wo) (Veach 1997 §5.2 and eq. 5.14; pbrt-v4 §9.5.2),
 * and equal modes for reflection; directional albedo at most 1, 1 in a white furnace for the
 * parameter sets that claim it; a kind that says it reads no choice number (ops->chooses 0,
 * material.h) samples the same for every uc, and one that says it reads it does not. Kind-specific laws are in test_bsdf.c and test_microfacet.c. */
#include <string.h>

#include "bsdf/material.h"
#include "bsdf_util.h"
#include "chi2.h"
#include "sample/warp.h"
#include "t.h"

static const double PI = 3.14159265358979323846;

/* The directions wo of the checks: normal, oblique, near grazing, and on the back (opaque kinds:
 * the mirrored lobe; glass: from inside). */
static const double thetas[] = {0.0, 45.0, 80.0, 89.0, 135.0, 180.0};
/* Those of the chi-square tests (each 10^6 samples). */
static const double chi2_thetas[] = {30.0, 150.0};

struct example {
    const struct mc_material_kind *kind;
    const struct mc_material_example *ex;
    struct material m;
    struct bsdf b;
    char name[96];
};

/* Every (kind, parameter set) pair; the BSDFs refer to their materials (rough glass's table),
 * which live here for the whole run. */
static struct example examples[64];
static int example_count;

static void make_examples(void)
{
    int k, e;
    for (k = 0; k < MC_MATERIAL_COUNT; k++) {
        const struct mc_material_kind *kind = &mc_material_kinds[k];
        T_CHECK(kind->ops->example_count > 0, "%s: no representative parameter sets", kind->name);
        for (e = 0; e < kind->ops->example_count && example_count < 64; e++) {
            struct example *x = &examples[example_count++];
            const struct mc_material_example *ex = &kind->ops->examples[e];
            memset(&x->m, 0, sizeof x->m);
            x->kind = kind;
            x->ex = ex;
            x->m.kind = kind;
            x->m.color = ex->color;
            x->m.ior = ex->ior;
            x->m.alpha = ex->alpha;
            x->m.eta = ex->eta;
            x->m.k = ex->k;
            mc_bsdf_prepare(&x->m);
            mc_bsdf_init(&x->b, &x->m);
            snprintf(x->name, sizeof x->name, "%s (%g %g %g) ior %g alpha %g", kind->name, ex->color.x, ex->color.y,
                     ex->color.z, ex->ior, ex->alpha);
        }
    }
    T_CHECK(example_count < 64, "more than 64 parameter sets: enlarge examples[]");
}

/* The direction at polar angle theta (degrees) and azimuth phi (radians). */
static vec3 dir(double theta_deg, double phi)
{
    double t = theta_deg * PI / 180.0;
    return v3((float)(sin(t) * cos(phi)), (float)(sin(t) * sin(phi)), (float)cos(t));
}

static double rel_err(double a, double b) { return a == b ? 0.0 : fabs(a - b) / fmax(fabs(a), fabs(b)); }

static int same_vec(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* ---- chi-square ---- */

/* Over the whole sphere in 1° cells of θ (glass refracts; opaque kinds leave the far hemisphere
 * empty), for every parameter set that is not all delta. The pdf's integral must equal the
 * probability of a non-delta sample, 1 − missing/N: 4 binomial standard deviations plus 2e-4 for
 * the harness's quadrature (test_microfacet.c). */
static void test_chi2(void)
{
    int i, pass, tests = 0, run = 0;
    size_t t;
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < example_count; i++) {
            if (mc_bsdf_is_delta(&examples[i].b))
                continue;
            for (t = 0; t < sizeof chi2_thetas / sizeof chi2_thetas[0]; t++) {
                struct bsdf_case c;
                struct chi2_dir_spec s;
                struct chi2_result r;
                char name[160];
                double p, tol;
                if (pass == 0) {
                    tests++;
                    continue;
                }
                c.b = examples[i].b;
                c.wo = dir(chi2_thetas[t], 0.7);
                snprintf(name, sizeof name, "%s, wo at %g deg", examples[i].name, chi2_thetas[t]);
                s = chi2_dir_spec_of(name, bsdf_case_sample, bsdf_case_pdf, &c, 0.0);
                s.ntheta = 180;
                s.seed = 3000 + (uint64_t)run++;
                s.tests = tests;
                r = chi2_run_directions(&s);
                p = 1.0 - (double)r.missing / 1e6;
                tol = 4.0 * sqrt(p * (1.0 - p) / 1e6) + 2e-4;
                T_NOTE("chi2 %s: chi2 %.1f, dof %d, p %.3f; pdf integral %.6f vs sampled fraction %.6f", name,
                       r.chi2, r.dof, r.p, r.integral, p);
                T_CHECK(r.pass, "%s: %s", name, r.why);
                T_CHECK(fabs(r.integral - p) <= tol, "%s: pdf integral %.6f, sampled fraction %.6f", name,
                        r.integral, p);
            }
        }
}

/* ---- sample, eval and pdf; the two modes ---- */

/* Over random wo on the sphere, in each mode: a sample's fields are finite and unit; a non-delta
 * sample's pdf is exactly mc_bsdf_pdf's and its weight f·|cos|/pdf to 1e-5 (microfacet factors
 * cancel only up to rounding); the same (uc, u) gives the same direction, pdf and lobe in both
 * modes, and the same weight for a reflection. Every eval and pdf is finite and at least 0. */
static void test_consistency(void)
{
    int i, j;
    for (i = 0; i < example_count; i++) {
        const struct bsdf *b = &examples[i].b;
        int bad = 0, bad_modes = 0, n = 0;
        double max_w = 0.0;
        pcg32 rng;
        pcg32_seed(&rng, 100 + (uint64_t)i, 0);
        for (j = 0; j < 20000; j++) {
            vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), wr = mc_warp_uniform_sphere(rand2(&rng));
            float uc = pcg32_float(&rng);
            vec2 u = rand2(&rng);
            struct bsdf_sample s[2];
            int ok[2], m, c;
            for (m = 0; m < 2; m++) {
                enum mc_transport mode = m == 0 ? MC_RADIANCE : MC_IMPORTANCE;
                vec3 f = mc_bsdf_eval(b, wo, wr, mode);
                float pdf = mc_bsdf_pdf(b, wo, wr);
                bad += !v3_is_finite(f) || !(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f) || !(pdf >= 0.0f) ||
                       !isfinite(pdf);
                ok[m] = mc_bsdf_sample(b, wo, uc, u, mode, &s[m]);
                if (!ok[m])
                    continue;
                bad += !v3_is_finite(s[m].wi) || fabsf(v3_length(s[m].wi) - 1.0f) > 1e-5f ||
                       !v3_is_finite(s[m].weight) || !(s[m].pdf > 0.0f) || !isfinite(s[m].pdf);
                if (s[m].delta)
                    continue;
                n++;
                f = mc_bsdf_eval(b, wo, s[m].wi, mode);
                pdf = mc_bsdf_pdf(b, wo, s[m].wi);
                bad += s[m].pdf != pdf;
                for (c = 0; c < 3; c++) {
                    double expect = v3_get(f, c) * fabsf(s[m].wi.z) / pdf;
                    if (v3_get(s[m].weight, c) > 0.0f || expect > 0.0)
                        max_w = fmax(max_w, rel_err(v3_get(s[m].weight, c), expect));
                }
            }
            if (ok[0] != ok[1])
                bad_modes++;
            else if (ok[0])
                bad_modes += !same_vec(s[0].wi, s[1].wi) || s[0].pdf != s[1].pdf || s[0].delta != s[1].delta ||
                             s[0].eta != s[1].eta ||
                             (s[0].wi.z * wo.z > 0.0f && !same_vec(s[0].weight, s[1].weight));
        }
        T_NOTE("%s: %d non-delta samples, max relative |weight - f cos/pdf| %.2g", examples[i].name, n, max_w);
        T_CHECK(bad == 0, "%s: %d non-finite results or samples with pdf != mc_bsdf_pdf", examples[i].name, bad);
        T_CHECK(max_w <= 1e-5, "%s: weight off f cos/pdf by %.3g", examples[i].name, max_w);
        T_CHECK(bad_modes == 0, "%s: %d samples differing between the modes beyond the weight of a crossing",
                examples[i].name, bad_modes);
    }
}

/* ---- the choice number ---- */

/* The integrators draw uc only for a kind whose ops say it reads it (mc_bsdf_chooses): one that
 * says it does not must sample the same for uc 0.05 and 0.95 (else its lobe choice would be
 * stuck at 0.5), over random wo and u in both modes; one that says it does must differ for some,
 * or the draw is spent on nothing. */
static void test_chooses(void)
{
    int i, j;
    for (i = 0; i < example_count; i++) {
        const struct bsdf *b = &examples[i].b;
        int differ = 0, m;
        pcg32 rng;
        pcg32_seed(&rng, 500 + (uint64_t)i, 0);
        for (j = 0; j < 2000; j++) {
            vec3 wo = mc_warp_uniform_sphere(rand2(&rng));
            vec2 u = rand2(&rng);
            for (m = 0; m < 2; m++) {
                enum mc_transport mode = m == 0 ? MC_RADIANCE : MC_IMPORTANCE;
                struct bsdf_sample s0, s1;
                int ok0 = mc_bsdf_sample(b, wo, 0.05f, u, mode, &s0);
                int ok1 = mc_bsdf_sample(b, wo, 0.95f, u, mode, &s1);
                differ += ok0 != ok1 || (ok0 && (!same_vec(s0.wi, s1.wi) || s0.pdf != s1.pdf));
            }
        }
        if (mc_bsdf_chooses(b))
            T_CHECK(differ > 0, "%s: says it reads uc, but samples alike for every uc", examples[i].name);
        else
            T_CHECK(differ == 0, "%s: says it reads no uc, but %d samples of 4000 change with it",
                    examples[i].name, differ);
    }
}

/* ---- reciprocity ---- */

/* f_radiance(wo, wi) = f_importance(wi, wo), and f_radiance = f_importance for wo, wi on the same
 * side, both exactly: reflection is formed symmetrically (mc_ggx_half, dielectric_ms.c). Across
 * an interface (relative ior b.ior; opaque kinds must give f = 0 there) each side recomputes the
 * microfacet normal wm from the generalised half vector h = wo + η wi (η = n_wi/n_wo) in its own
 * scaling. Rounding wo and wi (2^-24 per component) turns wm by δ <~ 4·2^-24/|h|; ln D changes by
 * at most 2/α per radian of it (|d ln D/dθm| = 4 tanθm/(α² + tan²θm) peaks at tanθm = α). The
 * Fresnel transmittance is ∝ the outside cosine c at wm near grazing, a small dot product of unit
 * vectors that each side computes with an absolute error of a few ulps of 1 from its own wm (up
 * to 8·2^-24 apart), so it changes by 8·2^-24/c relative. Tolerance: 1e-4 + 8·2^-24/(α|h|) +
 * 8·2^-24/c relative. */
static void test_reciprocity(void)
{
    int i, j;
    for (i = 0; i < example_count; i++) {
        const struct bsdf *b = &examples[i].b;
        int bad = 0, nonzero = 0, crossing = 0;
        double worst = 0.0;
        pcg32 rng;
        if (mc_bsdf_is_delta(b))
            continue;
        pcg32_seed(&rng, 200 + (uint64_t)i, 0);
        for (j = 0; j < 50000; j++) {
            vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), wi = mc_warp_uniform_sphere(rand2(&rng));
            vec3 f = mc_bsdf_eval(b, wo, wi, MC_RADIANCE), g = mc_bsdf_eval(b, wi, wo, MC_IMPORTANCE);
            nonzero += !v3_is_zero(f);
            if (wo.z * wi.z > 0.0f) {
                bad += !same_vec(f, g) || !same_vec(f, mc_bsdf_eval(b, wo, wi, MC_IMPORTANCE));
            } else if (!v3_is_zero(f) || !v3_is_zero(g)) {
                float n_o = wo.z > 0.0f ? 1.0f : b->ior, n_i = wi.z > 0.0f ? 1.0f : b->ior;
                vec3 h = v3_madd(wo, wi, n_i / n_o), wm = v3_normalize(h);
                double c_out = fabs(v3_dot(wo.z > 0.0f ? wo : wi, wm));
                double tol = 1e-4 + 8.0 * 0x1p-24 / (b->alpha * v3_length(h)) + 8.0 * 0x1p-24 / c_out;
                int c;
                crossing++;
                for (c = 0; c < 3; c++)
                    worst = fmax(worst, rel_err(v3_get(f, c), v3_get(g, c)) / tol);
            }
        }
        T_NOTE("%s: %d nonzero pairs, %d across; worst crossing error / tolerance %.3f", examples[i].name, nonzero,
               crossing, worst);
        T_CHECK(bad == 0, "%s: %d same-side pairs with f_rad(wo, wi) != f_imp(wi, wo) or != f_imp(wo, wi)",
                examples[i].name, bad);
        T_CHECK(worst <= 1.0, "%s: f_rad(wo, wi) vs f_imp(wi, wo) across: %.3g of the tolerance", examples[i].name,
                worst);
    }
}

/* ---- energy ---- */

/* Directional albedo ∫ f_importance(wo, wi) |cos θi| dωi, the fraction of the flux arriving from
 * wo that leaves (importance weights carry flux; radiance weights across an interface carry the
 * (n_wo/n_wi)² of radiance's compression besides). Estimated by the mean sample weight, which
 * must be at most 1 + 4 standard errors, and 1 within the set's furnace tolerance plus 4 standard
 * errors when it claims to conserve energy; and its non-delta part by uniform sampling of the
 * sphere, 4π f |cos|, which must agree with the non-delta samples' mean within 4 combined
 * standard errors. */
static void test_energy(void)
{
    const int n = 50000;
    int i;
    size_t t;
    for (i = 0; i < example_count; i++) {
        const struct bsdf *b = &examples[i].b;
        double furnace = examples[i].ex->furnace;
        for (t = 0; t < sizeof thetas / sizeof thetas[0]; t++) {
            vec3 wo = dir(thetas[t], 0.2);
            double s1 = 0.0, s2 = 0.0, d1 = 0.0, d2 = 0.0, u1 = 0.0, u2 = 0.0, mean, se, dmean, dse, umean, use;
            int j;
            pcg32 rng;
            pcg32_seed(&rng, 400 + 16 * (uint64_t)i + t, 0);
            for (j = 0; j < n; j++) {
                struct bsdf_sample s;
                vec3 wi = mc_warp_uniform_sphere(rand2(&rng));
                double x = 0.0, y = v3_avg(mc_bsdf_eval(b, wo, wi, MC_IMPORTANCE)) * fabsf(wi.z) * 4.0 * PI;
                if (mc_bsdf_sample(b, wo, pcg32_float(&rng), rand2(&rng), MC_IMPORTANCE, &s)) {
                    x = v3_avg(s.weight);
                    if (!s.delta) {
                        d1 += x;
                        d2 += x * x;
                    }
                }
                s1 += x;
                s2 += x * x;
                u1 += y;
                u2 += y * y;
            }
            mean = s1 / n;
            se = sqrt(fmax(s2 / n - mean * mean, 0.0) / n);
            dmean = d1 / n;
            dse = sqrt(fmax(d2 / n - dmean * dmean, 0.0) / n);
            umean = u1 / n;
            use = sqrt(fmax(u2 / n - umean * umean, 0.0) / n);
            T_NOTE("%s at %g deg: albedo %.5f +- %.5f; non-delta part %.5f +- %.5f sampled, %.5f +- %.5f uniform",
                   examples[i].name, thetas[t], mean, se, dmean, dse, umean, use);
            T_CHECK(mean <= 1.0 + 4.0 * se + 1e-6, "%s at %g deg: albedo %.6f > 1", examples[i].name, thetas[t], mean);
            if (furnace > 0.0)
                T_CHECK(fabs(mean - 1.0) <= 4.0 * se + furnace, "%s at %g deg: white furnace albedo %.6f, not 1",
                        examples[i].name, thetas[t], mean);
            T_CHECK(fabs(dmean - umean) <= 4.0 * sqrt(dse * dse + use * use) + 1e-6,
                    "%s at %g deg: sampled %.5f vs uniform %.5f", examples[i].name, thetas[t], dmean, umean);
        }
    }
}

int main(void)
{
    make_examples();
    test_chi2();
    test_consistency();
    test_chooses();
    test_reciprocity();
    test_energy();
    return t_done();
}
