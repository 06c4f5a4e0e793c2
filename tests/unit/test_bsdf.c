/* test_bsdf.c: what is particular to each of the simpler BSDFs of src/bsdf (test_materials.c
 * has what holds for all): diffuse edge cases and energy; the mirror's exact reflection;
 * glass's Snell and reflection laws, Fresnel-proportional lobe choice, energy and total internal
 * reflection; Fresnel against closed forms. */
#include <string.h>

#include "bsdf/material.h"
#include "bsdf_util.h"
#include "sample/warp.h"
#include "t.h"

static const double PI = 3.14159265358979323846;

static struct bsdf make_bsdf(const struct mc_material_kind *kind, vec3 color, float ior)
{
    struct material m;
    struct bsdf b;
    memset(&m, 0, sizeof m);
    m.kind = kind;
    m.color = color;
    m.ior = ior;
    mc_bsdf_init(&b, &m);
    return b;
}

/* The direction at polar angle theta (degrees) and azimuth phi (radians). */
static vec3 dir(double theta_deg, double phi)
{
    double t = theta_deg * PI / 180.0;
    return v3((float)(sin(t) * cos(phi)), (float)(sin(t) * sin(phi)), (float)cos(t));
}

static int same_vec(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* ---- Fresnel ---- */

/* Textbook Fresnel in double from the angles (Born and Wolf §1.5.2; Hecht, Optics, eq. 4.42–4.43):
 * rs = −sin(θi − θt)/sin(θi + θt), rp = tan(θi − θt)/tan(θi + θt), an independent form of
 * what fresnel.c computes from cosines. Valid away from normal incidence (0/0 there). */
static double fresnel_ref(double theta_i, double n_i, double n_t)
{
    double s = n_i / n_t * sin(theta_i), tt, rs, rp;
    if (s >= 1.0)
        return 1.0;
    tt = asin(s);
    rs = -sin(theta_i - tt) / sin(theta_i + tt);
    rp = tan(theta_i - tt) / tan(theta_i + tt);
    return 0.5 * (rs * rs + rp * rp);
}

static void test_fresnel(void)
{
    const double n = 1.5;
    static const float etas[] = {1.5f, 1.333f, 2.42f, 1.0f / 1.5f};
    double cos_b = 1.0 / sqrt(1.0 + n * n), rs_b = (1.0 - n * n) / (1.0 + n * n);
    double max_ref = 0.0, max_recip = 0.0;
    size_t e;
    int k, bad_tir = 0;

    /* Normal incidence: ((n − 1)/(n + 1))², from either side. Float evaluation: ~1e-7. */
    T_NEAR(mc_fresnel_dielectric(1.0f, 1.5f), 0.04, 1e-6, "normal incidence");
    T_NEAR(mc_fresnel_dielectric(-1.0f, 1.5f), 0.04, 1e-6, "normal incidence from inside");
    /* Brewster's angle tanθB = n: rp = 0 and, with cosθt = sinθB,
     * rs = (cosθB − n sinθB)/(cosθB + n sinθB) = (1 − n²)/(1 + n²), so F = rs²/2. From inside
     * (tanθ = 1/n) rs changes sign only, so F is the same. */
    T_NEAR(mc_fresnel_dielectric((float)cos_b, 1.5f), 0.5 * rs_b * rs_b, 1e-6, "Brewster from outside");
    T_NEAR(mc_fresnel_dielectric(-(float)(n * cos_b), 1.5f), 0.5 * rs_b * rs_b, 1e-6, "Brewster from inside");
    /* Grazing: everything reflects; 1 − F grows like cosθ near grazing. */
    T_CHECK(mc_fresnel_dielectric(0.0f, 1.5f) == 1.0f, "grazing: %g", mc_fresnel_dielectric(0.0f, 1.5f));
    T_CHECK(mc_fresnel_dielectric(1e-4f, 1.5f) > 0.999f, "near grazing: %g",
            mc_fresnel_dielectric(1e-4f, 1.5f));
    /* No interface at eta = 1, at any angle and from either side. */
    T_CHECK(mc_fresnel_dielectric(1.0f, 1.0f) == 0.0f && mc_fresnel_dielectric(0.5f, 1.0f) == 0.0f &&
                mc_fresnel_dielectric(1e-3f, 1.0f) == 0.0f && mc_fresnel_dielectric(0.0f, 1.0f) == 0.0f &&
                mc_fresnel_dielectric(-0.5f, 1.0f) == 0.0f,
            "eta = 1 must give F = 0");
    /* Total internal reflection from inside beyond θc = asin(1/n) = 41.81°. */
    T_CHECK(mc_fresnel_dielectric(-0.5f, 1.5f) == 1.0f, "TIR at 60 deg inside");
    T_CHECK(mc_fresnel_dielectric(-(float)cos(asin(1.0 / n) + 1e-3), 1.5f) == 1.0f, "TIR just past critical");
    {
        float f = mc_fresnel_dielectric(-(float)cos(asin(1.0 / n) - 1e-3), 1.5f);
        T_CHECK(f > 0.5f && f < 1.0f, "just inside the critical angle F = %g", f);
    }

    /* Against the angle form over θi in [1°, 89.9°], both sides, several η; and reciprocity
     * F(cosθi, η) = F(cosθt, 1/η) = F(−cosθt, η). Tolerance per point: float inputs and
     * arithmetic leave ~2.4e-7 absolute in k = η²cos²θt (fresnel.c), which reaches F through
     * s = √k as δs = δk/(2s), with |∂F/∂s| ≤ ~4; so 2e-6 + 1e-6/s for each evaluation, where
     * s = η cosθt for F(cosθi, η) and s = cosθi/η for both reciprocal forms. F is steep only
     * near the critical angle (s → 0), e.g. from inside when the outside ray is grazing. */
    for (e = 0; e < sizeof etas / sizeof etas[0]; e++)
        for (k = 10; k <= 899; k++) {
            double ti = k * 0.1 * PI / 180.0, eta = etas[e], st = sin(ti) / eta, ct, s1, s2, tol, err;
            float ci = (float)cos(ti), f = mc_fresnel_dielectric(ci, (float)eta);
            if (st >= 1.0) {
                bad_tir += f != 1.0f;
                continue;
            }
            ct = sqrt(1.0 - st * st);
            s1 = eta * ct;
            s2 = cos(ti) / eta;
            err = fabs(f - fresnel_ref(ti, 1.0, eta)) / (2e-6 + 1e-6 / s1);
            if (err > max_ref)
                max_ref = err;
            {
                float f1 = mc_fresnel_dielectric((float)ct, (float)(1.0 / eta));
                float f2 = mc_fresnel_dielectric(-(float)ct, (float)eta);
                tol = 2e-6 + 1e-6 / s1 + 1e-6 / s2;
                err = fmax(fabs(f1 - f), fabs(f2 - f)) / tol;
                if (err > max_recip)
                    max_recip = err;
            }
        }
    T_NOTE("Fresnel: max |F - angle form| / tol %.3f, max reciprocity error / tol %.3f", max_ref, max_recip);
    T_CHECK(max_ref <= 1.0, "Fresnel vs angle form: %g of the tolerance", max_ref);
    T_CHECK(max_recip <= 1.0, "Fresnel reciprocity: %g of the tolerance", max_recip);
    T_CHECK(bad_tir == 0, "%d angles beyond the critical angle with F != 1", bad_tir);
}

/* ---- diffuse ---- */

/* The diffuse lobe's edge cases (sampling, reciprocity and energy hold for every material:
 * test_materials.c). */
static void test_diffuse_limits(void)
{
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(diffuse), v3(0.8f, 0.5f, 0.2f), 1.5f);
    struct bsdf_sample s;
    T_CHECK(!mc_bsdf_is_delta(&b), "diffuse is not delta");
    T_CHECK(!mc_bsdf_sample(&b, v3(1.0f, 0.0f, 0.0f), 0.5f, v2(0.3f, 0.6f), MC_RADIANCE, &s),
            "grazing wo gives no sample");
    /* u = (0, 1/2) maps to the disk's rim, which lifts to wi.z = 0: no sample rather than a 0/0
     * weight */
    T_CHECK(!mc_bsdf_sample(&b, v3(0.0f, 0.0f, 1.0f), 0.5f, v2(0.0f, 0.5f), MC_RADIANCE, &s),
            "rim sample is rejected");
}

/* Directional albedo ∫ f |cosθi| dωi. Estimated two ways at several wo: with the BSDF's own
 * sampling (every weight is exactly the albedo, so the mean must equal it to float rounding)
 * and with uniform hemisphere sampling, X = 2π f cosθ = 2ρ cosθ with cosθ ~ U(0, 1), whose
 * mean is ρ with standard error ρ/√(3N); the tolerance is 4 standard errors (measured). */
static void test_diffuse_energy(void)
{
    static const double thetas[] = {0.0, 45.0, 89.0, 100.0, 180.0};
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(diffuse), v3(1.0f, 0.6f, 0.25f), 1.5f);
    const int n = 200000;
    size_t k;
    pcg32 rng;
    pcg32_seed(&rng, 40, 0);
    for (k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
        vec3 wo = dir(thetas[k], 2.0);
        double sum[3] = {0, 0, 0}, sum2 = 0.0, imp_max = 0.0, imp_sum = 0.0;
        int i, c;
        for (i = 0; i < n; i++) {
            vec3 wi = mc_warp_uniform_hemisphere(rand2(&rng)), f;
            struct bsdf_sample s;
            if (wo.z < 0.0f)
                wi.z = -wi.z;
            f = mc_bsdf_eval(&b, wo, wi, MC_RADIANCE);
            for (c = 0; c < 3; c++)
                sum[c] += v3_get(f, c) * fabsf(wi.z) * 2.0 * PI;
            sum2 += pow(f.x * fabsf(wi.z) * 2.0 * PI, 2.0);
            if (mc_bsdf_sample(&b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s)) {
                imp_sum += s.weight.x;
                if (s.weight.x > imp_max)
                    imp_max = s.weight.x;
            }
        }
        {
            double mean = sum[0] / n, se = sqrt((sum2 / n - mean * mean) / n);
            T_NOTE("diffuse albedo at %g deg: uniform estimate (%.5f, %.5f, %.5f) +- %.5f, sampled mean %.7f",
                   thetas[k], mean, sum[1] / n, sum[2] / n, se, imp_sum / n);
            T_CHECK(fabs(mean - 1.0) <= 4.0 * se, "white channel albedo %.5f, se %.5f", mean, se);
            T_CHECK(fabs(sum[1] / n - 0.6) <= 4.0 * 0.6 * se && fabs(sum[2] / n - 0.25) <= 4.0 * 0.25 * se,
                    "coloured channels (%.5f, %.5f)", sum[1] / n, sum[2] / n);
            T_CHECK(imp_max <= 1.0 && fabs(imp_sum / n - 1.0) <= 1e-6, "sampled weights: max %.9g mean %.9g",
                    imp_max, imp_sum / n);
        }
    }
}

/* ---- mirror ---- */

static void test_mirror(void)
{
    vec3 col = v3(0.9f, 0.7f, 0.3f);
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(mirror), col, 1.5f);
    pcg32 rng;
    int i, bad = 0;
    struct bsdf_sample s;
    pcg32_seed(&rng, 50, 0);
    T_CHECK(mc_bsdf_is_delta(&b), "mirror is delta");
    for (i = 0; i < 10000; i++) {
        vec3 wo = mc_warp_uniform_sphere(rand2(&rng)), wi = mc_warp_uniform_sphere(rand2(&rng));
        bad += !v3_is_zero(mc_bsdf_eval(&b, wo, wi, MC_RADIANCE)) || mc_bsdf_pdf(&b, wo, wi) != 0.0f;
        if (!mc_bsdf_sample(&b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s)) {
            bad++;
            continue;
        }
        bad += !same_vec(s.wi, v3(-wo.x, -wo.y, wo.z)) || !same_vec(s.weight, col) || s.pdf != 1.0f ||
               !s.delta || s.eta != 1.0f;
    }
    T_CHECK(bad == 0, "%d mirror samples not exact (wi, weight, pdf, delta, eta) or nonzero eval/pdf", bad);
    T_CHECK(!mc_bsdf_sample(&b, v3(0.6f, 0.8f, 0.0f), 0.5f, v2(0.5f, 0.5f), MC_RADIANCE, &s), "grazing mirror: no sample");
}

/* ---- glass ---- */

static void test_glass_laws(void)
{
    vec3 tint = v3(1.0f, 0.8f, 0.5f);
    const float ior = 1.5f;
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(glass), tint, ior);
    pcg32 rng;
    int i, nrefl = 0, ntrans = 0, bad_refl = 0, bad_trans = 0;
    double max_snell = 0.0, max_az = 0.0, max_energy = 0.0;
    pcg32_seed(&rng, 60, 0);
    T_CHECK(mc_bsdf_is_delta(&b), "glass is delta");
    for (i = 0; i < 100000; i++) {
        vec3 wo = mc_warp_uniform_sphere(rand2(&rng));
        struct bsdf_sample s;
        float f = mc_fresnel_dielectric(wo.z, ior);
        if (!v3_is_zero(mc_bsdf_eval(&b, wo, wo, MC_RADIANCE)) || mc_bsdf_pdf(&b, wo, v3_neg(wo)) != 0.0f)
            bad_refl++;
        if (!mc_bsdf_sample(&b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s)) {
            bad_trans++;
            continue;
        }
        if (s.wi.z * wo.z > 0.0f) {
            /* Reflection law, exactly; weight F/F = 1. */
            nrefl++;
            bad_refl += !same_vec(s.wi, v3(-wo.x, -wo.y, wo.z)) || !same_vec(s.weight, v3s(1.0f)) ||
                        s.pdf != f || !s.delta || s.eta != 1.0f;
        } else {
            /* Snell: n_i sinθi = n_t sinθt; the plane of incidence is kept (wi's tangential part
             * is antiparallel to wo's); etap = n_t/n_i. */
            double etap = wo.z > 0.0f ? ior : 1.0 / ior;
            double si = hypot(wo.x, wo.y), st = hypot(s.wi.x, s.wi.y);
            double snell = fabs(si - etap * st), az = fabs((double)wo.x * s.wi.y - (double)wo.y * s.wi.x);
            double energy = v3_max_comp(s.weight) * s.eta * s.eta; /* tint after undoing 1/η² */
            ntrans++;
            if (snell > max_snell)
                max_snell = snell;
            if (az > max_az)
                max_az = az;
            if (energy > max_energy)
                max_energy = energy;
            bad_trans += s.wi.z * wo.z >= 0.0f || (double)wo.x * s.wi.x + (double)wo.y * s.wi.y > 0.0 ||
                         fabs(s.eta - etap) > 1e-7 * etap || fabsf(s.pdf - (1.0f - f)) > 0.0f || !s.delta ||
                         fabsf(v3_length(s.wi) - 1.0f) > 1e-6f ||
                         fabs(s.weight.y * s.eta * s.eta - tint.y) > 1e-6 || !v3_is_finite(s.weight);
        }
    }
    T_NOTE("glass: %d reflections, %d transmissions; max |sin_i - eta sin_t| %.2g, max |wo x wi|_z %.2g, "
           "max weight*eta^2 %.7f",
           nrefl, ntrans, max_snell, max_az, max_energy);
    T_CHECK(bad_refl == 0, "%d reflections violating the reflection law or its weight/pdf", bad_refl);
    T_CHECK(bad_trans == 0, "%d transmissions with a wrong side, eta, pdf, length or weight", bad_trans);
    /* float directions: sines good to ~1e-7, so 1e-6 */
    T_CHECK(max_snell <= 1e-6, "Snell's law off by %g", max_snell);
    T_CHECK(max_az <= 1e-6, "refraction left the plane of incidence by %g", max_az);
    /* Energy: reflection carries 1; transmission carries tint/η², i.e. at most 1 once the
     * radiance-compression factor is undone. */
    T_CHECK(max_energy <= 1.0 + 1e-6, "transmission weight * eta^2 = %.9g > 1", max_energy);
}

/* The lobe is chosen with probability F: the reflected fraction of N samples is binomial with
 * standard deviation √(F(1 − F)/N); 4 standard deviations (plus uc's 2^-24 quantisation). */
static void test_glass_fresnel_frequency(void)
{
    static const double thetas[] = {0.0, 45.0, 80.0, 160.0, 140.0};
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(glass), v3s(1.0f), 1.5f);
    const int n = 200000;
    size_t k;
    pcg32 rng;
    pcg32_seed(&rng, 70, 0);
    for (k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
        vec3 wo = dir(thetas[k], 0.3);
        double f = mc_fresnel_dielectric(wo.z, 1.5f), frac, sd = sqrt(f * (1.0 - f) / n);
        double energy = 0.0;
        int i, refl = 0;
        for (i = 0; i < n; i++) {
            struct bsdf_sample s;
            if (!mc_bsdf_sample(&b, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s))
                continue;
            refl += s.wi.z * wo.z > 0.0f;
            energy += v3_avg(s.weight) * s.eta * s.eta;
        }
        frac = (double)refl / n;
        T_NOTE("glass at %g deg: reflected fraction %.5f vs F %.5f (sd %.5f); mean weight*eta^2 %.7f",
               thetas[k], frac, f, sd, energy / n);
        T_CHECK(fabs(frac - f) <= 4.0 * sd + 1e-7, "reflected fraction %.6f vs F %.6f", frac, f);
        /* A clear interface loses nothing: reflected plus transmitted power is 1. */
        T_CHECK(fabs(energy / n - 1.0) <= 1e-6, "mean weight*eta^2 %.9f", energy / n);
    }
}

static void test_glass_tir_and_limits(void)
{
    struct bsdf b = make_bsdf(MC_MATERIAL_KIND(glass), v3(0.9f, 0.9f, 0.9f), 1.5f);
    struct bsdf clear = make_bsdf(MC_MATERIAL_KIND(glass), v3(0.7f, 0.8f, 0.9f), 1.0f);
    static const float ucs[] = {0.0f, 0.25f, 0.5f, 0.999f, 0x1.fffffep-1f};
    double theta_c = asin(1.0 / 1.5);
    struct bsdf_sample s;
    pcg32 rng;
    int i, bad_tir = 0, bad_sweep = 0, bad_clear = 0;
    size_t k;
    /* Beyond θc = 41.81° from inside, every uc reflects with weight 1 and probability 1. */
    for (i = 0; i <= 100; i++) {
        double theta = theta_c + 1e-4 + (PI / 2 - 1e-4 - theta_c - 1e-4) * i / 100.0;
        vec3 wo = v3((float)sin(theta), 0.0f, -(float)cos(theta));
        for (k = 0; k < sizeof ucs / sizeof ucs[0]; k++)
            bad_tir += !mc_bsdf_sample(&b, wo, ucs[k], v2(0.5f, 0.5f), MC_RADIANCE, &s) ||
                       !same_vec(s.wi, v3(-wo.x, -wo.y, wo.z)) || s.pdf != 1.0f ||
                       !same_vec(s.weight, v3s(1.0f));
    }
    T_CHECK(bad_tir == 0, "%d samples beyond the critical angle were not total reflections", bad_tir);
    /* Across θc ± 1e-4 rad (float cosθ resolves ~1e-7 there): finite unit directions, finite weights. */
    for (i = -1000; i <= 1000; i++) {
        double theta = theta_c + 1e-7 * i;
        vec3 wo = v3((float)sin(theta), 0.0f, -(float)cos(theta));
        for (k = 0; k < sizeof ucs / sizeof ucs[0]; k++)
            if (mc_bsdf_sample(&b, wo, ucs[k], v2(0.5f, 0.5f), MC_RADIANCE, &s))
                bad_sweep += !v3_is_finite(s.wi) || !v3_is_finite(s.weight) || !(s.pdf > 0.0f) ||
                             fabsf(v3_length(s.wi) - 1.0f) > 1e-6f;
            else
                bad_sweep++;
    }
    T_CHECK(bad_sweep == 0, "%d bad samples near the critical angle", bad_sweep);
    /* ior = 1: no interface; straight through with the tint, F = 0. */
    pcg32_seed(&rng, 80, 0);
    for (i = 0; i < 10000; i++) {
        vec3 wo = mc_warp_uniform_sphere(rand2(&rng));
        bad_clear += !mc_bsdf_sample(&clear, wo, pcg32_float(&rng), rand2(&rng), MC_RADIANCE, &s) ||
                     !same_vec(s.wi, v3_neg(wo)) || !same_vec(s.weight, clear.color) || s.pdf != 1.0f ||
                     s.eta != 1.0f;
    }
    T_CHECK(bad_clear == 0, "%d ior-1 samples not straight through", bad_clear);
    /* Grazing wo: no sample, rather than a NaN. */
    T_CHECK(!mc_bsdf_sample(&b, v3(1.0f, 0.0f, 0.0f), 0.5f, v2(0.5f, 0.5f), MC_RADIANCE, &s), "grazing glass: no sample");
    T_CHECK(!mc_bsdf_sample(&clear, v3(0.0f, 1.0f, 0.0f), 0.5f, v2(0.5f, 0.5f), MC_RADIANCE, &s),
            "grazing clear: no sample");
}

int main(void)
{
    test_fresnel();
    test_diffuse_limits();
    test_diffuse_energy();
    test_mirror();
    test_glass_laws();
    test_glass_fresnel_frequency();
    test_glass_tir_and_limits();
    return t_done();
}
