/* test_microfacet.c: the GGX microfacet BSDFs of src/bsdf (metal, rough glass, plastic) and
 * their optics: conductor Fresnel against closed forms; the GGX distribution's normalisations;
 * sampling against the pdf (chi-square) at grazing angles and refraction's jumps, with the
 * missing mass accounted for; agreement of sample, eval and pdf down to the smoothest rough α;
 * the transport modes across glass; directional albedo (energy) bounds and closed forms; the
 * smooth limits; and finite results at grazing angles and extreme roughness. What holds for
 * every material at its representative parameters is in test_materials.c. */
#include <complex.h>
#include <string.h>

#include "bsdf/bsdf_impl.h"
#include "bsdf_util.h"
#include "chi2.h"
#include "sample/warp.h"
#include "t.h"

/* Chi-square tests this binary expects to accept (Šidák correction): see test_chi2. */
#define CHI2_TESTS 30

static const double PI = 3.14159265358979323846;

/* A prepared material as the scene makes them, and its BSDF. The BSDF refers to its material (rough
 * glass's compensation table), so materials live in a pool for the whole run. */
static struct bsdf make(const struct mc_material_kind *kind, vec3 color, float ior, float alpha)
{
    static struct material pool[1024];
    static size_t used;
    struct material *m = &pool[used < 1024 ? used++ : 1023];
    struct bsdf b;
    memset(m, 0, sizeof *m);
    m->kind = kind;
    m->color = color;
    m->ior = ior;
    m->alpha = alpha;
    mc_metal_from_reflectance(color, &m->eta, &m->k); /* used by metal only */
    mc_bsdf_prepare(m);
    mc_bsdf_init(&b, m);
    T_CHECK(used < 1024, "material pool exhausted");
    return b;
}

/* Gold at about 650, 550, 450 nm (Johnson and Christy 1972, as tabulated by pbrt). */
static struct bsdf make_gold(float alpha)
{
    struct bsdf b = make(MC_MATERIAL_KIND(metal), v3s(0.0f), 1.0f, alpha);
    b.eta = v3(0.166f, 0.428f, 1.38f);
    b.k = v3(3.15f, 2.35f, 1.87f);
    return b;
}

/* The direction at polar angle theta (degrees) and azimuth phi (radians). */
static vec3 dir(double theta_deg, double phi)
{
    double t = theta_deg * PI / 180.0;
    return v3((float)(sin(t) * cos(phi)), (float)(sin(t) * sin(phi)), (float)cos(t));
}

static int finite_sample(const struct bsdf_sample *s)
{
    return v3_is_finite(s->wi) && v3_is_finite(s->weight) && isfinite(s->pdf) && s->pdf > 0.0f &&
           fabsf(v3_length(s->wi) - 1.0f) <= 1e-5f && s->weight.x >= 0.0f && s->weight.y >= 0.0f &&
           s->weight.z >= 0.0f;
}

static double rel_err(double a, double b) { return fabs(a - b) / fmax(fabs(a), fabs(b)); }

/* ---- conductor Fresnel ---- */

/* The conductor Fresnel equations as complex amplitudes (Born and Wolf §14.2; pbrt-v4
 * FrComplex): cosθt = √(1 − sin²θi/n²), n = η + ik, and r∥, r⊥ as for a dielectric; an
 * independent derivation from the real a² + b² form of fresnel.c. */
static double fr_conductor_ref(double c, double eta, double k)
{
    double complex n = eta + k * I, cos_t = csqrt(1.0 - (1.0 - c * c) / (n * n));
    double complex r_par = (n * c - cos_t) / (n * c + cos_t);
    double complex r_perp = (c - n * cos_t) / (c + n * cos_t);
    return 0.5 * (creal(r_par) * creal(r_par) + cimag(r_par) * cimag(r_par) +
                  creal(r_perp) * creal(r_perp) + cimag(r_perp) * cimag(r_perp));
}

static void test_fresnel_conductor(void)
{
    static const float etas[] = {0.166f, 0.2f, 1.0f, 1.5f, 2.9f, 0.05f};
    static const float ks[] = {3.15f, 3.9f, 0.5f, 0.0f, 3.0f, 200.0f};
    static const float rs[] = {0.0f, 0.04f, 0.5f, 0.9f, 0.95f, 0.9999f};
    double max_ref = 0.0, max_n = 0.0, max_r = 0.0, max_d = 0.0;
    size_t e;
    int i;
    for (e = 0; e < sizeof etas / sizeof etas[0]; e++) {
        double eta = etas[e], k = ks[e];
        double n0 = ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
        vec3 f0 = mc_fresnel_conductor(1.0f, v3s(etas[e]), v3s(ks[e]));
        max_n = fmax(max_n, fabs(f0.x - n0));
        for (i = 0; i <= 1000; i++) {
            float c = (float)(i / 1000.0);
            vec3 f = mc_fresnel_conductor(c, v3s(etas[e]), v3s(ks[e]));
            max_ref = fmax(max_ref, fabs(f.y - fr_conductor_ref(c, eta, k)));
            /* k = 0 is a dielectric of ior eta (outside-in incidence). */
            if (k == 0.0)
                max_d = fmax(max_d, fabs(f.z - mc_fresnel_dielectric(c, etas[e])));
        }
    }
    for (e = 0; e < sizeof rs / sizeof rs[0]; e++) {
        vec3 eta, k;
        mc_metal_from_reflectance(v3(rs[e], 0.5f, 0.5f), &eta, &k);
        max_r = fmax(max_r, fabs(mc_fresnel_conductor(1.0f, eta, k).x - rs[e]));
    }
    /* Float results of double arithmetic: a few ulps of 1. */
    T_NOTE("conductor Fresnel: max |F(1) - closed form| %.2g, max |F - complex form| %.2g, "
           "max |F(k=0) - dielectric| %.2g, max |F(1) - R| from reflectance %.2g",
           max_n, max_ref, max_d, max_r);
    T_CHECK(max_n <= 1e-6, "normal incidence off by %g", max_n);
    T_CHECK(max_ref <= 1e-6, "real vs complex form off by %g", max_ref);
    T_CHECK(max_d <= 1e-6, "k = 0 vs dielectric off by %g", max_d);
    T_CHECK(max_r <= 1e-6, "metal from reflectance: F(1) off R by %g", max_r);
    {
        vec3 eta, k, f;
        mc_metal_from_reflectance(v3(1.0f, 2.0f, -1.0f), &eta, &k);
        f = mc_fresnel_conductor(1.0f, eta, k);
        T_CHECK(eta.x == 1.0f && isfinite(k.x) && isfinite(k.y) && k.z == 0.0f,
                "reflectance 1 / 2 / -1 gives k = (%g, %g, %g)", k.x, k.y, k.z);
        T_NEAR(f.x, 0.9999, 1e-6, "reflectance 1 clamps to 0.9999");
        T_CHECK(f.z == 0.0f && mc_fresnel_conductor(0.0f, eta, k).z == 0.0f, "reflectance 0: no interface");
        T_CHECK(mc_fresnel_conductor(0.0f, v3s(0.2f), v3s(3.9f)).x == 1.0f, "grazing conductor reflects all");
    }
}

/* The hemispherical average of dielectric Fresnel against composite Simpson quadrature in
 * double: 2e5 intervals resolve even the near-singular point μ ~ √(2(η − 1)) of η = 1 + 2^-23
 * (the results do not move at 16 times as many). Tolerance 1e-9 for the closed form; 5e-8 for
 * the (η − 1)/3 used below η − 1 = 1e-4. */
static void test_fresnel_diffuse(void)
{
    static const double etas[] = {1.0 + 0x1p-23, 1.00001, 1.00009, 1.0001, 1.001, 1.05, 1.33, 1.5, 2.4, 10.0};
    double max_err = 0.0, max_small = 0.0;
    size_t e;
    for (e = 0; e < sizeof etas / sizeof etas[0]; e++) {
        const int n = 200000;
        double sum = 0.0, h = 1.0 / n, err;
        int i;
        for (i = 0; i <= n; i++) {
            double mu = i * h, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            /* the dielectric Fresnel in double, as fresnel.c computes it in float */
            double k = mu * mu + etas[e] * etas[e] - 1.0, s = sqrt(k), n2 = etas[e] * etas[e];
            double rp = (n2 * mu - s) / (n2 * mu + s), rs = (mu - s) / (mu + s);
            sum += w * 0.5 * (rp * rp + rs * rs) * 2.0 * mu;
        }
        err = fabs(sum * h / 3.0 - mc_fresnel_diffuse(etas[e]));
        if (etas[e] - 1.0 < 1e-4)
            max_small = fmax(max_small, err);
        else
            max_err = fmax(max_err, err);
    }
    T_NOTE("hemispherical Fresnel average: max |closed form - quadrature| %.2g, |(eta - 1)/3 - quadrature| %.2g",
           max_err, max_small);
    T_CHECK(max_err <= 1e-9, "closed form off by %g", max_err);
    T_CHECK(max_small <= 5e-8, "(eta - 1)/3 off by %g", max_small);
    T_CHECK(mc_fresnel_diffuse(1.0) == 0.0, "no interface at eta 1");
}

/* ---- the GGX distribution ---- */

/* Heitz 2014: the projected microfacet area is the macro area, ∫ D(m) cosθm dωm = 1,
 * and the visible projected area is wo's projected area, ∫ G1(wo) max(0, wo·m) D(m) dωm =
 * cosθo, i.e. D_wo integrates to 1. Quadrature over m with θm = atan(α tan v), which spreads
 * the nodes over the lobe whatever its width; midpoint rule, 4000 × 400 nodes (measured
 * errors ~1e-6). */
static void test_ggx_normalisation(void)
{
    static const float alphas[] = {1e-3f, 0.1f, 0.5f, 1.0f};
    static const double thetas[] = {0.0, 45.0, 80.0, 89.9};
    double max_d = 0.0, max_v = 0.0;
    size_t a, t;
    for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++)
        for (t = 0; t < sizeof thetas / sizeof thetas[0]; t++) {
            const int nv = 4000, nphi = 400;
            vec3 wo = dir(thetas[t], 0.4);
            double al = alphas[a], sd = 0.0, sv = 0.0;
            int i, j;
            for (i = 0; i < nv; i++) {
                double v = (i + 0.5) / nv * PI / 2, tv = tan(v);
                double th = atan(al * tv), dth = al / (cos(v) * cos(v)) / (1.0 + al * al * tv * tv);
                for (j = 0; j < nphi; j++) {
                    double phi = (j + 0.5) / nphi * 2.0 * PI, w = sin(th) * dth * (PI / 2 / nv) * (2 * PI / nphi);
                    vec3 m = v3((float)(sin(th) * cos(phi)), (float)(sin(th) * sin(phi)), (float)cos(th));
                    if (t == 0)
                        sd += mc_ggx_d(alphas[a], m) * m.z * w;
                    sv += mc_ggx_visible_pdf(alphas[a], wo, m) * w;
                }
            }
            if (t == 0)
                max_d = fmax(max_d, fabs(sd - 1.0));
            max_v = fmax(max_v, fabs(sv - 1.0));
        }
    T_NOTE("GGX: max |∫D cos - 1| %.2g, max |∫D_wo - 1| %.2g", max_d, max_v);
    T_CHECK(max_d <= 1e-4, "projected microfacet area off by %g", max_d);
    T_CHECK(max_v <= 1e-4, "visible normal density integrates to 1 +- %g", max_v);
}

/* Smith masking for GGX against Heitz 2014's Λ = (−1 + √(1 + α² tan²θ))/2, in double:
 * G1 = 1/(1 + Λ) and the height-correlated G2 = 1/(1 + Λ(wo) + Λ(wi)), which is not the
 * separable G1(wo)G1(wi) (e.g. α = 1, θ = 60° both ways: Λ = 1/2, G2 = 1/2, G1² = 4/9). Float
 * evaluation: 1e-6. And G2 lies between the uncorrelated product and the smaller G1 (Heitz
 * 2014): G1(wo) G1(wi) <= G2 <= min(G1(wo), G1(wi)). */
static double smith_lambda(double alpha, vec3 w)
{
    double t2 = ((double)w.x * w.x + (double)w.y * w.y) / ((double)w.z * w.z);
    return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * t2));
}

static void test_ggx_smith(void)
{
    pcg32 rng;
    int i, bad = 0;
    double max_err = 0.0;
    pcg32_seed(&rng, 7, 0);
    T_NEAR(mc_ggx_g2(1.0f, dir(60.0, 0.0), dir(60.0, 2.0)), 0.5, 1e-6, "G2 at alpha 1, 60 deg both ways");
    for (i = 0; i < 100000; i++) {
        float alpha = 0.001f + pcg32_float(&rng);
        vec3 wo = mc_warp_uniform_hemisphere(rand2(&rng)), wi = mc_warp_uniform_hemisphere(rand2(&rng));
        float g1o, g1i, g2;
        double lo, li;
        if (wo.z == 0.0f || wi.z == 0.0f)
            continue;
        g1o = mc_ggx_g1(alpha, wo);
        g1i = mc_ggx_g1(alpha, wi);
        g2 = mc_ggx_g2(alpha, wo, wi);
        lo = smith_lambda(alpha, wo);
        li = smith_lambda(alpha, wi);
        max_err = fmax(max_err, fmax(fabs(g1o - 1.0 / (1.0 + lo)), fabs(g2 - 1.0 / (1.0 + lo + li))));
        bad += !(g2 >= g1o * g1i * (1.0f - 1e-6f) && g2 <= fminf(g1o, g1i) * (1.0f + 1e-6f));
    }
    T_NOTE("Smith: max |G - Heitz 2014| %.2g", max_err);
    T_CHECK(max_err <= 1e-6, "G1/G2 off the closed form by %g", max_err);
    T_CHECK(bad == 0, "%d cases with G2 outside [G1 G1, min G1]", bad);
}

/* ---- chi-square of sampling against pdf ---- */

static int chi2_count;

/* Run the chi-square test s (numbered by chi2_count for its seed) and check, besides the
 * histogram, that the pdf integrates to the fraction of samples returned (tolerance: see
 * run_chi2). */
static void run_dir_spec(struct chi2_dir_spec *s, const char *name)
{
    struct chi2_result r;
    double p, tol;
    s->seed = 1000 + (uint64_t)chi2_count;
    s->tests = CHI2_TESTS;
    chi2_count++;
    r = chi2_run_directions(s);
    p = 1.0 - (double)r.missing / 1e6;
    tol = 4.0 * sqrt(p * (1.0 - p) / 1e6) + 2e-4;
    T_NOTE("chi2 %s: chi2 %.1f, dof %d, p %.3f; pdf integral %.6f vs sampled fraction %.6f", name, r.chi2,
           r.dof, r.p, r.integral, p);
    T_CHECK(r.pass, "%s: %s", name, r.why);
    T_CHECK(fabs(r.integral - p) <= tol, "%s: pdf integral %.6f, sampled fraction %.6f (tol %.2g)", name,
            r.integral, p, tol);
}

/* One chi-square test over wo's hemisphere (opaque materials), whose rim is where the
 * reflection pdf drops to 0. Near grazing the reflected lobe is narrow in φ: a sideways tilt δ
 * of the microfacet turns wi by 2(wo·wm)δ, so the lobe is ~2α cosθo wide (0.0035 rad at
 * α = 0.1, 89°), which 160 cells of φ do not resolve; there 640 do. The pdf's integral must
 * also equal the probability of a (non-delta) sample, 1 − missing/N: the mass the sampler
 * loses (reflections below the horizon, the delta lobe) is exactly what the pdf leaves out.
 * Tolerance: 4 binomial standard deviations √(p(1 − p)/N) plus 2e-4 for the harness's
 * Gauss–Legendre integral (against a 6000 × 4000 midpoint rule: <= 1e-5 for α = 0.1 at 30°
 * and 89°). */
static void run_chi2(const char *what, struct bsdf b, double theta)
{
    struct bsdf_case c;
    struct chi2_dir_spec s;
    char name[96];
    c.b = b;
    c.wo = dir(theta, 0.7);
    snprintf(name, sizeof name, "%s, alpha %g, wo at %g deg", what, b.alpha, theta);
    s = chi2_dir_spec_of(name, bsdf_case_sample, bsdf_case_pdf, &c, PI / 2);
    s.nphi = theta >= 85.0 ? 640 : 160;
    run_dir_spec(&s, name);
}

/* Glass over the whole sphere, in 1° cells of θ. Its refraction pdf jumps from 0 where the
 * generalised half vector reaches the horizon (microfacets cannot tilt past 90°): at
 * wi.z = −wo.z/η for wo outside, at wi.z = −η wo.z for wo inside. Gauss–Legendre's interior
 * nodes integrate a cell with a jump well only if the jump lies on the cell's edge, so near
 * grazing and inside (where the jump is large) wo is placed to put it on a whole degree; the
 * reflection's jump at 90° is on an edge anyway. */
static double theta_for_jump(double jump_deg)
{
    double c = cos(jump_deg * PI / 180.0);
    return acos(jump_deg > 90.0 ? -1.5 * c : -c / 1.5) * 180.0 / PI;
}

static void run_chi2_glass(float alpha, double theta)
{
    struct bsdf_case c;
    struct chi2_dir_spec s;
    char name[96];
    c.b = make(MC_MATERIAL_KIND(glass), v3(1.0f, 0.9f, 0.8f), 1.5f, alpha);
    c.wo = dir(theta, 0.7);
    snprintf(name, sizeof name, "glass ior 1.5, alpha %g, wo at %.2f deg", alpha, theta);
    s = chi2_dir_spec_of(name, bsdf_case_sample, bsdf_case_pdf, &c, 0.0);
    s.ntheta = 180;
    run_dir_spec(&s, name);
}

static void test_chi2(void)
{
    static const struct { float alpha; double theta; } metal[] = {
        {0.1f, 30.0}, {0.1f, 89.0}, {0.2f, 0.0}, {0.2f, 60.0},
        {0.5f, 30.0}, {0.5f, 89.0}, {1.0f, 45.0}, {1.0f, 89.0}};
    /* Glass: θ < 0 means theta_for_jump(−θ): 88.50° (jump at 91°) and, from inside, 92.67° and
     * 120.20° (jumps at 86° and 41°). Beyond 131.8° the macro surface would reflect totally;
     * rough microfacets still let light out. At 0°, 45° and beyond 131.8° the jump is 0 or small. */
    static const struct { float alpha; double theta; } glass[] = {
        {0.1f, 45.0}, {0.1f, 150.0}, {0.2f, 0.0}, {0.2f, -91.0}, {0.2f, -41.0}, {0.5f, 45.0},
        {0.5f, 160.0}, {0.5f, -86.0}, {1.0f, -91.0}, {1.0f, -41.0}, {1.0f, 180.0}, {0.3f, 60.0}, {0.3f, 130.0}};
    /* The smooth coat at 80°, not 89°: there it takes 98% of the samples, too few for the base. */
    static const struct { float alpha; double theta; } plastic[] = {
        {0.0f, 30.0}, {0.0f, 80.0}, {0.1f, 30.0}, {0.1f, 89.0}, {0.2f, 50.0}, {0.5f, 30.0}, {1.0f, 0.0},
        {1.0f, 89.0}, {1.0f, 60.0}};
    size_t i;
    for (i = 0; i < sizeof metal / sizeof metal[0]; i++)
        run_chi2("metal (gold)", make_gold(metal[i].alpha), metal[i].theta);
    for (i = 0; i < sizeof glass / sizeof glass[0]; i++)
        run_chi2_glass(glass[i].alpha, glass[i].theta < 0.0 ? theta_for_jump(-glass[i].theta) : glass[i].theta);
    for (i = 0; i < sizeof plastic / sizeof plastic[0]; i++)
        run_chi2("plastic ior 1.5", make(MC_MATERIAL_KIND(plastic), v3(0.8f, 0.4f, 0.1f), 1.5f, plastic[i].alpha),
                 plastic[i].theta);
    T_CHECK(chi2_count == CHI2_TESTS, "CHI2_TESTS is %d but %d tests ran", CHI2_TESTS, chi2_count);
}

/* ---- sample / eval / pdf agreement, reciprocity, back faces ---- */

/* Over random wo on the sphere: every non-delta sample's pdf is exactly mc_bsdf_pdf's (sample
 * takes it from there), and its weight, formed in closed form (F G2/G1 and the like), equals
 * eval·|cos|/pdf, where the microfacet factors cancel only up to rounding: a few dozen float
 * operations, so 1e-5 relative. */
static void test_consistency(void)
{
    static const float alphas[] = {1e-3f, 0.05f, 0.3f, 1.0f};
    const char *names[] = {"metal", "glass", "plastic"};
    int m;
    size_t a;
    for (m = 0; m < 3; m++) {
        double max_w = 0.0;
        int bad = 0, n = 0;
        pcg32 rng;
        pcg32_seed(&rng, 100 + (uint64_t)m, 0);
        for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
            struct bsdf b = m == 0 ? make_gold(alphas[a])
                                   : make(m == 1 ? MC_MATERIAL_KIND(glass) : MC_MATERIAL_KIND(plastic), v3(0.9f, 0.6f, 0.3f), 1.5f,
                                          alphas[a]);
            int i;
            for (i = 0; i < 50000; i++) {
                vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), f, expect;
                struct bsdf_sample s;
                float pdf, etap = 1.0f;
                int c;
                if (!mc_bsdf_sample(&b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s) || s.delta)
                    continue;
                n++;
                f = mc_bsdf_eval(&b, wo, s.wi, MC_RADIANCE);
                pdf = mc_bsdf_pdf(&b, wo, s.wi);
                if (!finite_sample(&s) || s.pdf != pdf) {
                    bad++;
                    continue;
                }
                expect = v3_scale(f, fabsf(s.wi.z) / pdf);
                /* Opaque materials reflect to wo's side; glass refracts with eta = etap. */
                if (s.wi.z * wo.z < 0.0f)
                    etap = wo.z > 0.0f ? 1.5f : 1.0f / 1.5f;
                bad += (m != 1 && s.wi.z * wo.z <= 0.0f) || s.eta != etap;
                for (c = 0; c < 3; c++)
                    if (v3_get(s.weight, c) > 0.0f || v3_get(expect, c) > 0.0f)
                        max_w = fmax(max_w, rel_err(v3_get(s.weight, c), v3_get(expect, c)));
            }
        }
        T_NOTE("%s: %d samples; max relative |weight - f cos/pdf| %.2g", names[m], n, max_w);
        T_CHECK(bad == 0, "%s: %d samples non-finite, with pdf != mc_bsdf_pdf, or of wrong side/eta", names[m],
                bad);
        T_CHECK(max_w <= 1e-5, "%s: weight off f cos/pdf by %.3g", names[m], max_w);
    }
}

/* Transport modes (bsdf.h): across glass, radiance's f(wo, wi) carries (n_wo/n_wi)² that
 * importance's lacks, so f_rad(wo, wi)/n_wo² = f_imp(wo, wi)/n_wi², which with the adjoint
 * f_imp(wo, wi) = f_rad(wi, wo) (test_materials.c) is Veach 1997 eq. 5.14, f(wo, wi)/n_wo² =
 * f(wi, wo)/n_wi² (pbrt-v4 §9.5.2). Checked for rough glass's eval (both lobes) and smooth
 * glass's sample weight (the same (uc, u) in both modes: the same wi and pdf, the weight of a
 * transmission η² larger in importance, η = s.eta = n_wi/n_wo), to float rounding (1e-6
 * relative: the radiance factor is one multiplication, the compensation lobe's constants
 * c[a][b] and c[b][a] are rounded apart); reflection is the same bits in both modes. */
static void test_transport_mode(void)
{
    static const float alphas[] = {0.0f, 0.1f, 0.5f, 1.0f};
    double worst = 0.0;
    int bad = 0, crossings = 0;
    size_t a;
    pcg32 rng;
    pcg32_seed(&rng, 250, 0);
    for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
        struct bsdf b = make(MC_MATERIAL_KIND(glass), v3(1.0f, 0.9f, 0.8f), 1.5f, alphas[a]);
        int i, c;
        for (i = 0; i < 50000; i++) {
            vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), wi = mc_warp_uniform_sphere(rand2(&rng)), fr, fi;
            float uc = pcg32_float(&rng), n_o = wo.z > 0.0f ? 1.0f : 1.5f, n_i = wi.z > 0.0f ? 1.0f : 1.5f;
            vec2 u = rand2(&rng);
            struct bsdf_sample sr, si;
            int okr = mc_bsdf_sample(&b, wo, uc, u, MC_RADIANCE, &sr);
            int oki = mc_bsdf_sample(&b, wo, uc, u, MC_IMPORTANCE, &si);
            bad += okr != oki;
            if (okr && oki) {
                bad += memcmp(&sr.wi, &si.wi, sizeof sr.wi) || sr.pdf != si.pdf || sr.eta != si.eta;
                for (c = 0; c < 3; c++) {
                    double r = v3_get(sr.weight, c) * sr.eta * sr.eta, m = v3_get(si.weight, c);
                    if (sr.wi.z * wo.z > 0.0f)
                        bad += v3_get(sr.weight, c) != v3_get(si.weight, c);
                    else if (r > 0.0 || m > 0.0)
                        worst = fmax(worst, rel_err(r, m));
                }
            }
            fr = mc_bsdf_eval(&b, wo, wi, MC_RADIANCE);
            fi = mc_bsdf_eval(&b, wo, wi, MC_IMPORTANCE);
            if (wo.z * wi.z > 0.0f) {
                bad += memcmp(&fr, &fi, sizeof fr) != 0;
                continue;
            }
            crossings += !v3_is_zero(fr);
            for (c = 0; c < 3; c++) {
                double x = v3_get(fr, c) / (n_o * n_o), y = v3_get(fi, c) / (n_i * n_i);
                if (x > 0.0 || y > 0.0)
                    worst = fmax(worst, rel_err(x, y));
            }
        }
    }
    T_NOTE("transport modes: %d nonzero crossing pairs; max relative |f_rad/n_wo^2 - f_imp/n_wi^2| and "
           "|weight_rad eta^2 - weight_imp| %.2g", crossings, worst);
    T_CHECK(bad == 0, "%d samples or reflections differing between the modes", bad);
    T_CHECK(crossings > 0 && worst <= 1e-6, "modes across glass off the eta^2 relation by %.3g", worst);
}

/* Opaque materials on the back face are the front face mirrored: the same (uc, u) gives the
 * mirrored sample, and eval/pdf agree exactly. */
static void test_back_face(void)
{
    static const float alphas[] = {0.0f, 0.2f, 1.0f};
    int bad = 0, m;
    size_t a;
    pcg32 rng;
    pcg32_seed(&rng, 300, 0);
    for (m = 0; m < 2; m++)
        for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
            struct bsdf b =
                m == 0 ? make_gold(alphas[a]) : make(MC_MATERIAL_KIND(plastic), v3(0.5f, 0.5f, 0.5f), 1.5f, alphas[a]);
            int i;
            for (i = 0; i < 20000; i++) {
                vec3 wo = mc_warp_uniform_hemisphere(rand2(&rng)), wi = mc_warp_uniform_hemisphere(rand2(&rng));
                vec3 wob = v3(wo.x, wo.y, -wo.z), wib = v3(wi.x, wi.y, -wi.z);
                float uc = pcg32_float(&rng);
                vec2 u = rand2(&rng);
                struct bsdf_sample s, t;
                int ok = mc_bsdf_sample(&b, wo, uc, u, MC_RADIANCE, &s), okb = mc_bsdf_sample(&b, wob, uc, u, MC_RADIANCE, &t);
                vec3 f = mc_bsdf_eval(&b, wo, wi, MC_RADIANCE), fb = mc_bsdf_eval(&b, wob, wib, MC_RADIANCE);
                bad += f.x != fb.x || f.y != fb.y || f.z != fb.z ||
                       mc_bsdf_pdf(&b, wo, wi) != mc_bsdf_pdf(&b, wob, wib) || ok != okb;
                if (ok && okb)
                    bad += s.wi.x != t.wi.x || s.wi.y != t.wi.y || s.wi.z != -t.wi.z || s.pdf != t.pdf ||
                           s.weight.x != t.weight.x || s.delta != t.delta;
            }
        }
    T_CHECK(bad == 0, "%d back-face configurations differ from the mirrored front", bad);
}

/* ---- energy ---- */

/* Directional albedo ∫ f |cosθi| dωi at wo, two ways: the mean sample weight (with the η² of
 * radiance transport undone for refraction), and uniform sampling of the sphere (4π f |cos|,
 * η² likewise). Both means come with their standard errors. */
struct albedo { double sampled, se_sampled, uniform, se_uniform, max_weight; };

static struct albedo directional_albedo(const struct bsdf *b, vec3 wo, int n, uint64_t seed)
{
    struct albedo r;
    double s1 = 0.0, s2 = 0.0, u1 = 0.0, u2 = 0.0;
    int i;
    pcg32 rng;
    pcg32_seed(&rng, seed, 0);
    r.max_weight = 0.0;
    for (i = 0; i < n; i++) {
        struct bsdf_sample s;
        vec3 wi = mc_warp_uniform_sphere(rand2(&rng));
        double x = 0.0, y;
        if (mc_bsdf_sample(b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s)) {
            x = v3_avg(s.weight) * s.eta * s.eta;
            r.max_weight = fmax(r.max_weight, x);
        }
        s1 += x;
        s2 += x * x;
        y = v3_avg(mc_bsdf_eval(b, wo, wi, MC_RADIANCE)) * fabsf(wi.z) * 4.0 * PI;
        if (wo.z * wi.z < 0.0f && b->ops == MC_MATERIAL_KIND(glass)->ops)
            y *= (wo.z > 0.0f ? b->ior * b->ior : 1.0 / (b->ior * b->ior));
        u1 += y;
        u2 += y * y;
    }
    r.sampled = s1 / n;
    r.se_sampled = sqrt(fmax(s2 / n - r.sampled * r.sampled, 0.0) / n);
    r.uniform = u1 / n;
    r.se_uniform = sqrt(fmax(u2 / n - r.uniform * r.uniform, 0.0) / n);
    return r;
}

/* The two estimates agree within 4 combined standard errors, and the sampled one (the sharper)
 * stays at or below 1 + 4 standard errors. */
static void check_albedo(const char *what, const struct bsdf *b, double theta, struct albedo r, int unit_weights)
{
    double se = sqrt(r.se_sampled * r.se_sampled + r.se_uniform * r.se_uniform);
    T_NOTE("%s alpha %g at %g deg: albedo %.5f +- %.5f (sampled), %.5f +- %.5f (uniform), max weight %.6f", what,
           b->alpha, theta, r.sampled, r.se_sampled, r.uniform, r.se_uniform, r.max_weight);
    T_CHECK(fabs(r.sampled - r.uniform) <= 4.0 * se, "%s alpha %g at %g deg: sampled %.5f vs uniform %.5f", what,
            b->alpha, theta, r.sampled, r.uniform);
    T_CHECK(r.sampled <= 1.0 + 4.0 * r.se_sampled, "%s alpha %g at %g deg: albedo %.6f > 1", what, b->alpha, theta,
            r.sampled);
    /* Metal weights are F·G2/G1: never above 1 (float: 1e-6). (Rough glass's are not: they mix
     * its compensation lobe's pdf in; test_glass_energy.) */
    if (unit_weights)
        T_CHECK(r.max_weight <= 1.0 + 1e-6, "%s alpha %g at %g deg: weight %.9f > 1", what, b->alpha, theta,
                r.max_weight);
}

static void test_energy(void)
{
    static const float alphas[] = {0.1f, 0.5f, 1.0f};
    static const double thetas[] = {0.0, 60.0, 89.0};
    static const double glass_thetas[] = {0.0, 70.0, 89.0, 150.0, 100.0};
    const int n = 200000;
    size_t a, t;
    uint64_t seed = 400;
    for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
        struct bsdf metal = make(MC_MATERIAL_KIND(metal), v3s(1.0f), 1.0f, alphas[a]); /* R = 0.9999 */
        struct bsdf glass = make(MC_MATERIAL_KIND(glass), v3s(1.0f), 1.5f, alphas[a]);
        struct bsdf plastic = make(MC_MATERIAL_KIND(plastic), v3s(1.0f), 1.5f, alphas[a]);
        for (t = 0; t < sizeof thetas / sizeof thetas[0]; t++) {
            struct albedo r = directional_albedo(&metal, dir(thetas[t], 0.2), n, seed++);
            check_albedo("white metal", &metal, thetas[t], r, 1);
            /* The single-scattering loss of GGX (energy that real microsurfaces return after
             * several bounces; Heitz et al. 2016, Kulla and Conty 2017). */
            T_NOTE("white metal alpha %g at %g deg: energy loss %.4f", metal.alpha, thetas[t], 1.0 - r.sampled);
            /* Closed form at α = 1, normal incidence: the visible normals are cosine-distributed
             * (D = 1/π), wi = 2θm is lost beyond θm = 45°, and G2/G1 = 2cosθi/(1 + cosθi), so
             * E = ∫₀^{π/4} G2 2cosθm sinθm dθm = ∫_{1/2}^1 (2t − 1)/t dt (t = cos²θm) = 1 − ln 2,
             * times F ∈ [0.9999, 1] (1e-4). */
            if (alphas[a] == 1.0f && thetas[t] == 0.0)
                T_CHECK(fabs(r.sampled - (1.0 - log(2.0))) <= 4.0 * r.se_sampled + 1e-4,
                        "white metal alpha 1 at normal incidence: albedo %.5f, expected 1 - ln 2 = %.5f", r.sampled,
                        1.0 - log(2.0));
            r = directional_albedo(&plastic, dir(thetas[t], 0.2), n, seed++);
            check_albedo("white plastic", &plastic, thetas[t], r, 0);
        }
        for (t = 0; t < sizeof glass_thetas / sizeof glass_thetas[0]; t++)
            check_albedo("clear rough glass", &glass, glass_thetas[t],
                         directional_albedo(&glass, dir(glass_thetas[t], 0.2), n, seed++), 0);
    }
}

/* Clear rough glass with its multiple-scattering compensation conserves energy: the mean sample
 * weight (the 1/η² of crossing undone) is 1 from outside and from inside, at normal to grazing
 * incidence, for α up to 1 and η of water, glass and diamond. Tolerance: 4 standard errors plus
 * 3e-3 for the tables (the energy is 1 + E_ss(μo) − Ê(μo): the quadrature of dielectric_ms.c
 * measured within 2e-3 of 1e6-sample estimates of E_ss at every node for α 0.01, 0.1, 1, and
 * linear interpolation between nodes adds less). */
static void test_glass_energy(void)
{
    static const float iors[] = {1.33f, 1.5f, 2.4f}, alphas[] = {0.01f, 0.09f, 0.3f, 1.0f};
    static const double thetas[] = {0.0, 45.0, 80.0, 89.5, 180.0, 130.0, 100.0, 90.5};
    const int n = 15000;
    double worst = 0.0, max_weight = 0.0;
    size_t i, a, t;
    uint64_t seed = 800;
    for (i = 0; i < sizeof iors / sizeof iors[0]; i++)
        for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
            struct bsdf b = make(MC_MATERIAL_KIND(glass), v3s(1.0f), iors[i], alphas[a]);
            for (t = 0; t < sizeof thetas / sizeof thetas[0]; t++) {
                struct albedo r = directional_albedo(&b, dir(thetas[t], 0.2), n, seed++);
                double z = fabs(r.sampled - 1.0) / (4.0 * r.se_sampled + 3e-3);
                worst = fmax(worst, z);
                max_weight = fmax(max_weight, r.max_weight);
                T_CHECK(z <= 1.0, "glass ior %g alpha %g at %g deg: albedo %.5f +- %.5f, not 1", iors[i], alphas[a],
                        thetas[t], r.sampled, r.se_sampled);
            }
        }
    T_NOTE("compensated rough glass: worst |albedo - 1| / (4 se + 3e-3) %.3f over 96 cases, max weight %.3f", worst,
           max_weight);
}

/* Plastic with a white base, sharply: the coat's albedo as the mean weight of 10^6 samples of
 * the black-base plastic (all from the coat: weight F G2/G1, at most F; or the smooth coat's
 * delta reflection of weight F exactly), with its standard error; plus the base's albedo
 * 2π∫ f_base μ dμ by Simpson's rule in μ = cosθi (f_base, the white-base f minus the black-base
 * f, depends on μ only; 2·10^4 intervals: error ~1e-9). For the smooth coat the sum must be the
 * closed form F(cosθo) + (1 − F(cosθo))·A, A = ρ(1 − F̄ᵢ)/(1 − ρF̄ᵢ) at the capped ρ = 0.999,
 * to 1e-6; for the rough coat at most 1 + 4 standard errors, where the coat's reflectance
 * exceeds F(cosθo) most (plastic.c). */
static double plastic_albedo(float ior, float alpha, double theta, double *se)
{
    struct bsdf white = make(MC_MATERIAL_KIND(plastic), v3s(1.0f), ior, alpha);
    struct bsdf black = make(MC_MATERIAL_KIND(plastic), v3s(0.0f), ior, alpha);
    vec3 wo = dir(theta, 0.0);
    const int n = 1000000, nmu = 20000;
    double coat = 0.0, coat2 = 0.0, base = 0.0;
    int i;
    pcg32 rng;
    pcg32_seed(&rng, 700, 0);
    for (i = 0; i < n; i++) {
        struct bsdf_sample s;
        if (mc_bsdf_sample(&black, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s)) {
            coat += s.weight.x;
            coat2 += (double)s.weight.x * s.weight.x;
        }
    }
    for (i = 1; i <= nmu; i++) {
        double mu = (double)i / nmu, w = i == nmu ? 1.0 : (i % 2 ? 4.0 : 2.0);
        vec3 wi = v3((float)sqrt(1.0 - mu * mu), 0.0f, (float)mu);
        base += w * 2.0 * PI * mu * (mc_bsdf_eval(&white, wo, wi, MC_RADIANCE).x - mc_bsdf_eval(&black, wo, wi, MC_RADIANCE).x);
    }
    coat /= n;
    *se = sqrt(fmax(coat2 / n - coat * coat, 0.0) / n);
    return coat + base / (3.0 * nmu);
}

static void test_plastic_white(void)
{
    static const struct { float ior, alpha; double theta; } worst[] = {
        {1.2f, 0.12f, 48.0}, {1.5f, 0.08f, 47.0}, {1.5f, 0.1f, 44.0}, {1.7f, 0.03f, 53.0}, {1.05f, 0.06f, 65.0}};
    static const double thetas[] = {0.0, 45.0, 80.0, 89.0};
    double max_smooth = 0.0, se;
    size_t k;
    for (k = 0; k < sizeof worst / sizeof worst[0]; k++) {
        double a = plastic_albedo(worst[k].ior, worst[k].alpha, worst[k].theta, &se);
        T_NOTE("white plastic ior %g alpha %g at %g deg: albedo %.6f +- %.6f", worst[k].ior, worst[k].alpha,
               worst[k].theta, a, se);
        T_CHECK(a <= 1.0 + 4.0 * se, "white plastic ior %g alpha %g at %g deg: albedo %.6f > 1", worst[k].ior,
                worst[k].alpha, worst[k].theta, a);
    }
    for (k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
        const double eta = 1.5, rho = 0.999;
        double fbar = mc_fresnel_diffuse(eta), fin = 1.0 - (1.0 - fbar) / (eta * eta);
        double f = mc_fresnel_dielectric((float)cos(thetas[k] * PI / 180.0), 1.5f);
        double expect = f + (1.0 - f) * rho * (1.0 - fin) / (1.0 - rho * fin);
        max_smooth = fmax(max_smooth, fabs(plastic_albedo(1.5f, 0.0f, thetas[k], &se) - expect));
    }
    T_NOTE("white plastic, smooth coat: max |albedo - closed form| %.2g", max_smooth);
    T_CHECK(max_smooth <= 1e-6, "smooth coat albedo off the closed form by %g", max_smooth);
}

/* ---- smooth limits ---- */

static void test_limits(void)
{
    pcg32 rng;
    int i, bad_metal = 0, bad_glass = 0, bad_plastic = 0;
    struct bsdf metal = make_gold(1e-4f), glass = make(MC_MATERIAL_KIND(glass), v3(1.0f, 0.9f, 0.8f), 1.5f, 1e-4f);
    struct bsdf smooth_glass = make(MC_MATERIAL_KIND(glass), v3(1.0f, 0.9f, 0.8f), 1.5f, 0.0f);
    struct bsdf plastic = make(MC_MATERIAL_KIND(plastic), v3(0.5f, 0.5f, 0.5f), 1.5f, 1e-4f);
    struct bsdf rough_plastic = make(MC_MATERIAL_KIND(plastic), v3(0.5f, 0.5f, 0.5f), 1.5f, 1e-3f);
    struct bsdf rough_metal = make_gold(1e-3f);
    pcg32_seed(&rng, 500, 0);
    T_CHECK(mc_bsdf_is_delta(&metal) && mc_bsdf_is_delta(&glass) && !mc_bsdf_is_delta(&plastic) &&
                !mc_bsdf_is_delta(&rough_plastic) && !mc_bsdf_is_delta(&rough_metal),
            "delta: metal/glass at alpha 1e-4 yes; plastic never; alpha 1e-3 is rough");
    {
        struct bsdf clear = make(MC_MATERIAL_KIND(glass), v3s(1.0f), 1.0f, 0.5f);
        T_CHECK(mc_bsdf_is_delta(&clear), "rough glass of ior 1 is no interface: delta");
    }
    for (i = 0; i < 20000; i++) {
        vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), wi = mc_warp_uniform_sphere(rand2(&rng));
        float uc = pcg32_float(&rng);
        vec2 u = rand2(&rng);
        struct bsdf_sample s, t;
        vec3 f;
        /* Metal at α = 1e-4: the mirror direction with weight F(cosθo), exactly. */
        if (!mc_bsdf_sample(&metal, wo, uc, u, MC_RADIANCE, &s))
            bad_metal++;
        else {
            f = mc_fresnel_conductor(fabsf(wo.z), metal.eta, metal.k);
            bad_metal += s.wi.x != -wo.x || s.wi.y != -wo.y || s.wi.z != wo.z || !s.delta || s.pdf != 1.0f ||
                         s.weight.x != f.x || s.weight.y != f.y || s.weight.z != f.z;
        }
        bad_metal += !v3_is_zero(mc_bsdf_eval(&metal, wo, wi, MC_RADIANCE)) || mc_bsdf_pdf(&metal, wo, wi) != 0.0f;
        /* Glass at α = 1e-4: smooth glass, sample for sample. */
        if (mc_bsdf_sample(&glass, wo, uc, u, MC_RADIANCE, &s) != mc_bsdf_sample(&smooth_glass, wo, uc, u, MC_RADIANCE, &t) ||
            memcmp(&s.wi, &t.wi, sizeof s.wi) || memcmp(&s.weight, &t.weight, sizeof s.weight) || s.pdf != t.pdf ||
            !s.delta)
            bad_glass++;
        /* Plastic at α = 1e-4: the smooth coat's delta lobe plus the base. */
        if (mc_bsdf_sample(&plastic, wo, uc, u, MC_RADIANCE, &s) && s.delta) {
            float fc = mc_fresnel_dielectric(fabsf(wo.z), 1.5f);
            bad_plastic += s.wi.x != -wo.x || s.wi.y != -wo.y || s.wi.z != wo.z ||
                           fabsf(s.weight.x * s.pdf - fc) > 1e-6f;
        }
    }
    T_CHECK(bad_metal == 0, "%d metal samples at alpha 1e-4 not the exact mirror with weight F", bad_metal);
    T_CHECK(bad_glass == 0, "%d glass samples at alpha 1e-4 differ from smooth glass", bad_glass);
    T_CHECK(bad_plastic == 0, "%d smooth plastic coat samples not mirror with weight F/pdf", bad_plastic);

    /* Rough glass at α = 1e-3 (the smoothest α that is still a microfacet lobe): the reflected
     * fraction is F(cosθo) within 4 binomial standard deviations plus 1e-4 (the microfacets'
     * tilt ~α changes F by ~F'·α², and ~α·tanθo of the samples are lost). The reflections lie
     * near the mirror direction, but GGX's tails are long: at normal incidence a visible normal
     * is tilted beyond tanθm = t with probability α²/(α² + t²), 1% for t = 10α, whose
     * reflection is 2t = 0.02 rad off; so at least 98% within 0.02 rad. */
    {
        static const double thetas[] = {0.0, 60.0, 150.0};
        struct bsdf g = make(MC_MATERIAL_KIND(glass), v3s(1.0f), 1.5f, 1e-3f);
        size_t k;
        for (k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
            vec3 wo = dir(thetas[k], 1.1);
            double f = mc_fresnel_dielectric(wo.z, 1.5f), sd = sqrt(f * (1.0 - f) / 200000), frac;
            int j, refl = 0, near = 0;
            for (j = 0; j < 200000; j++) {
                struct bsdf_sample s;
                if (!mc_bsdf_sample(&g, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s))
                    continue;
                if (s.wi.z * wo.z > 0.0f) {
                    refl++;
                    near += v3_dot(s.wi, v3(-wo.x, -wo.y, wo.z)) > cosf(0.02f);
                }
            }
            frac = refl / 200000.0;
            T_NOTE("rough glass alpha 1e-3 at %g deg: reflected %.5f vs F %.5f (sd %.5f), %d of %d within 0.02 rad "
                   "of the mirror direction",
                   thetas[k], frac, f, sd, near, refl);
            T_CHECK(fabs(frac - f) <= 4.0 * sd + 1e-4, "reflected fraction %.5f vs F %.5f", frac, f);
            T_CHECK(near >= 0.98 * refl, "%d of %d reflections far from the mirror direction", refl - near, refl);
        }
    }
}

/* ---- numerical safety ---- */

/* Grazing wo (z = ±1e-4, ±0), normal wo, α from 1e-4 (delta) through 1e-3 to 1, u at the ends
 * of [0, 1): every sample finite with positive pdf, every eval and pdf finite and >= 0. */
static void test_finite(void)
{
    static const float alphas[] = {1e-4f, 1e-3f, 0.5f, 1.0f};
    static const float us[] = {0.0f, 0.5f, 0x1.fffffep-1f};
    const float zs[] = {1e-4f, -1e-4f, 0.0f, -0.0f, 1.0f, -1.0f, 0.9999999f};
    int bad = 0, samples = 0, mat, ui, uj;
    size_t a, z;
    pcg32 rng;
    pcg32_seed(&rng, 600, 0);
    for (mat = 0; mat < 3; mat++)
        for (a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
            struct bsdf b = mat == 0 ? make(MC_MATERIAL_KIND(metal), v3s(1.0f), 1.0f, alphas[a])
                                     : make(mat == 1 ? MC_MATERIAL_KIND(glass) : MC_MATERIAL_KIND(plastic), v3s(1.0f), 1.5f,
                                            alphas[a]);
            for (z = 0; z < sizeof zs / sizeof zs[0]; z++) {
                float st = sqrtf(fmaxf(0.0f, 1.0f - zs[z] * zs[z]));
                vec3 wo = v3(st * 0.6f, st * 0.8f, zs[z]);
                int i;
                for (i = 0; i < 2000 + 27; i++) {
                    struct bsdf_sample s;
                    float uc;
                    vec2 u;
                    vec3 wi = mc_warp_uniform_sphere(rand2(&rng)), f;
                    float p;
                    if (i < 27) { /* the corners and middle of the sample cube */
                        ui = i % 3;
                        uj = (i / 3) % 3;
                        uc = us[i / 9];
                        u = v2(us[ui], us[uj]);
                    } else {
                        uc = pcg32_float(&rng);
                        u = rand2(&rng);
                    }
                    if (mc_bsdf_sample(&b, wo, uc, u, MC_RADIANCE, &s)) {
                        samples++;
                        bad += !finite_sample(&s);
                        wi = s.wi;
                    }
                    f = mc_bsdf_eval(&b, wo, wi, MC_RADIANCE);
                    p = mc_bsdf_pdf(&b, wo, wi);
                    bad += !v3_is_finite(f) || !(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f) || !isfinite(p) ||
                           !(p >= 0.0f);
                }
            }
        }
    T_NOTE("finite: %d samples at grazing/normal wo, alpha 1e-4 to 1", samples);
    T_CHECK(bad == 0, "%d non-finite or negative results", bad);
    {
        /* The GGX functions themselves at the smallest rough α and a grazing direction. */
        vec3 w = v3(0.99999999f, 0.0f, 1e-4f), m = mc_ggx_sample_visible(1e-3f, w, v2(0.3f, 0.7f));
        float vals[] = {mc_ggx_d(1e-3f, v3(0.0f, 0.0f, 1.0f)), mc_ggx_g1(1e-3f, w), mc_ggx_g2(1e-3f, w, w),
                        mc_ggx_visible_pdf(1e-3f, w, m)};
        size_t k;
        int ok = v3_is_finite(m) && m.z > 0.0f;
        for (k = 0; k < sizeof vals / sizeof vals[0]; k++)
            ok &= isfinite(vals[k]) && vals[k] >= 0.0f;
        T_CHECK(ok, "GGX at alpha 1e-3, grazing: D %g G1 %g G2 %g D_wo %g", vals[0], vals[1], vals[2], vals[3]);
    }
}

int main(void)
{
    test_fresnel_conductor();
    test_fresnel_diffuse();
    test_ggx_normalisation();
    test_ggx_smith();
    test_chi2();
    test_consistency();
    test_transport_mode();
    test_back_face();
    test_energy();
    test_glass_energy();
    test_plastic_white();
    test_limits();
    test_finite();
    return t_done();
}
