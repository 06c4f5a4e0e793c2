/* fresnel.c: the optics of a smooth interface: the reflected and refracted directions and the
 * Fresnel reflectance of dielectrics and conductors.
 * References: Born and Wolf, "Principles of Optics", §1.5.2 and §14.2; pbrt-v4 §9.3 and §9.4
 * (Reflect, Refract, FrDielectric, FrComplex). */
#include "bsdf/bsdf_impl.h"

#include <math.h>

float mc_fresnel_dielectric(float cos_i, float eta)
{
    float k, s, r_par, r_perp;
    if (eta == 1.0f)
        return 0.0f; /* no interface; also the one case where both denominators below vanish */
    cos_i = f_min(1.0f, f_max(-1.0f, cos_i));
    if (cos_i < 0.0f) {
        /* Incidence from inside: swap the media (pbrt-v4 eq. 9.6 with η → 1/η). */
        eta = 1.0f / eta;
        cos_i = -cos_i;
    }
    /* Snell: η²cos²θt = η² − sin²θi = cos²θi + (η² − 1). In this form (rather than
     * 1 − sin²θi/η²) η near 1 loses nothing and η = 1 would give cosθt == cosθi exactly, which
     * mc_refract relies on to pass straight through. k < 0 is total internal reflection; at
     * k = 0 (the critical angle) both amplitudes below are exactly 1, so F is continuous. */
    k = cos_i * cos_i + (eta * eta - 1.0f);
    if (k < 0.0f)
        return 1.0f;
    s = sqrtf(k); /* η cosθt */
    /* Fresnel amplitudes (pbrt-v4 eq. 9.4 and 9.5) multiplied through by η:
     * r∥ = (η cosθi − cosθt)/(η cosθi + cosθt), r⊥ = (cosθi − η cosθt)/(cosθi + η cosθt).
     * A denominator vanishes only when cosθi = 0 and k = 0, i.e. η = 1, handled above. */
    r_par = (eta * eta * cos_i - s) / (eta * eta * cos_i + s);
    r_perp = (cos_i - s) / (cos_i + s);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

/* One channel of mc_fresnel_conductor: |r∥|² and |r⊥|² of the complex index n = η + ik (Born
 * and Wolf §14.2; pbrt-v4 FrComplex) in real arithmetic: with n² − sin²θi = a² − b² + 2iab, so
 * that a² + b² = |n² − sin²θi| and a = Re √(n² − sin²θi),
 *     |r⊥|² = (a² + b² − 2a cosθi + cos²θi) / (a² + b² + 2a cosθi + cos²θi),
 *     |r∥|² = |r⊥|² (cos²θi (a² + b²) − 2a cosθi sin²θi + sin⁴θi)
 *                 / (cos²θi (a² + b²) + 2a cosθi sin²θi + sin⁴θi)
 * (Lagarde 2013, "Memo on Fresnel equations"; pbrt-v3 FrConductor). In double so that k in the
 * hundreds (reflectance 0.9999) keeps its digits: a² is then the small difference of
 * a² + b² ≈ k² and −(η² − k² − sin²θi). The C99 complex form it replaces computed the same with
 * a complex square root and divisions (libm's csqrt and __divdc3): 7% of scenes/glossy-floor.mcrt's
 * instructions, now 2% (callgrind, 80x45 at 16 spp: 250.0 M -> 237.9 M in all, the image
 * byte-identical). */
static float fresnel_complex(float cos_i, float eta, float k)
{
    double c = fmin(fmax((double)cos_i, 0.0), 1.0), c2 = c * c, s2 = 1.0 - c2;
    double t0 = (double)eta * eta - (double)k * k - s2;
    double ab = sqrt(t0 * t0 + 4.0 * (double)eta * eta * (double)k * k); /* a² + b² */
    double a = sqrt(fmax(0.5 * (ab + t0), 0.0));
    double t1 = ab + c2, t2 = 2.0 * c * a, t3 = c2 * ab + s2 * s2, t4 = t2 * s2, r_perp;
    if (eta == 1.0f && k == 0.0f)
        return 0.0f; /* no interface: at c = 0 both amplitudes would be 0/0 */
    r_perp = (t1 - t2) / (t1 + t2);
    return (float)(0.5 * (r_perp + r_perp * (t3 - t4) / (t3 + t4)));
}

vec3 mc_fresnel_conductor(float cos_i, vec3 eta, vec3 k)
{
    return v3(fresnel_complex(cos_i, eta.x, k.x), fresnel_complex(cos_i, eta.y, k.y),
              fresnel_complex(cos_i, eta.z, k.z));
}

/* The extinction coefficient k that, with η = 1, gives reflectance r at normal incidence. There
 * F = ((η − 1)² + k²)/((η + 1)² + k²) (Born and Wolf §14.2), which with η = 1 is k²/(4 + k²) = r,
 * so k = 2√(r/(1 − r)) (pbrt-v4's "reflectance" parameter of the conductor). r = 1 would need
 * k = ∞: 0.9999 gives k = 200. */
static float k_from_reflectance(float r)
{
    r = f_min(0.9999f, f_max(0.0f, r));
    return 2.0f * sqrtf(r / (1.0f - r));
}

void mc_metal_from_reflectance(vec3 r, vec3 *eta, vec3 *k)
{
    *eta = v3s(1.0f);
    *k = v3(k_from_reflectance(r.x), k_from_reflectance(r.y), k_from_reflectance(r.z));
}

double mc_fresnel_diffuse(double eta)
{
    /* ∫₀¹ F(μ) 2μ dμ in closed form: the elementary integrals of r∥² and r⊥² over the cosine-
     * weighted hemisphere (the "diffuse reflectance" of a dielectric boundary in radiative
     * transfer). test_microfacet checks it against quadrature. Near η = 1 its terms grow like
     * 1/(η − 1)² and cancel to a result ~(η − 1)/3, losing ~4e-18/(η − 1)² even in double;
     * below η − 1 = 1e-4 the leading term (η − 1)/3 is closer (within 5e-8, measured). */
    double n = eta, n2 = n * n, n4 = n2 * n2;
    if (n - 1.0 < 1e-4)
        return (n - 1.0) / 3.0;
    return 0.5 + (n - 1.0) * (3.0 * n + 1.0) / (6.0 * (n + 1.0) * (n + 1.0)) +
           n2 * (n2 - 1.0) * (n2 - 1.0) / ((n2 + 1.0) * (n2 + 1.0) * (n2 + 1.0)) * log((n - 1.0) / (n + 1.0)) -
           2.0 * n * n2 * (n2 + 2.0 * n - 1.0) / ((n2 + 1.0) * (n4 - 1.0)) +
           8.0 * n4 * (n4 + 1.0) / ((n2 + 1.0) * (n4 - 1.0) * (n4 - 1.0)) * log(n);
}

vec3 mc_reflect(vec3 w, vec3 n) { return v3_sub(v3_scale(n, 2.0f * v3_dot(w, n)), w); }

int mc_refract(vec3 w, vec3 n, float eta, vec3 *wt)
{
    /* Snell's law in vector form (pbrt-v4 Refract): the tangential part shrinks by 1/η and the
     * normal part becomes −cosθt: wt = −w/η + (cosθi/η − cosθt) n. cosθt is formed as in
     * mc_fresnel_dielectric, so η = 1 gives cosθt == cosθi and wt == −w exactly. */
    float cos_i = v3_dot(w, n), k = cos_i * cos_i + (eta * eta - 1.0f), cos_t, a;
    if (k < 0.0f)
        return 0; /* total internal reflection */
    cos_t = sqrtf(k) / eta;
    a = cos_i / eta - cos_t;
    *wt = v3(-w.x / eta + a * n.x, -w.y / eta + a * n.y, -w.z / eta + a * n.z);
    return 1;
}
