/* warp.c: maps from the unit square to disks, triangles and directions, with their pdfs.
 * Reference: Pharr, Jakob and Humphreys, "Physically Based Rendering", 4th ed. (pbrt-v4), §A.5. */
#include "sample/warp.h"

/* Every map below is finite for u in [0, 1): pcg32_float tops out at 1 − 2^-24, and the only
 * square roots are of quantities clamped to be non-negative. */

vec2 mc_warp_concentric_disk(vec2 u)
{
    /* Shirley and Chiu 1997, "A Low Distortion Map Between Disk and Square", JGT 2(3), in the
     * single-branch form of pbrt-v4 SampleUniformDiskConcentric: each concentric square of the
     * offset point maps to a circle of the same radius, so area ratios are preserved (pdf 1/π). */
    float x = 2.0f * u.x - 1.0f, y = 2.0f * u.y - 1.0f;
    float r, phi;
    if (x == 0.0f && y == 0.0f)
        return v2(0.0f, 0.0f); /* the centre; the angle formulas below would divide 0 by 0 */
    if (fabsf(x) > fabsf(y)) {
        r = x;
        phi = (MC_PI / 4.0f) * (y / x);
    } else {
        r = y;
        phi = MC_PI / 2.0f - (MC_PI / 4.0f) * (x / y);
    }
    return v2(r * cosf(phi), r * sinf(phi));
}

vec2 mc_warp_rejection_disk(pcg32 *rng)
{
    /* von Neumann 1951, "Various techniques used in connection with random digits": points
     * uniform on the square that fall inside the circle are uniform on the disk. The
     * coordinates are the centres of pcg32_float's 2^24 cells mapped to [-1, 1], so they are
     * exact in float and symmetric about 0; the test is in double, where the squares are
     * exact, so every accepted point lies strictly inside the circle. */
    for (;;) {
        float x = 2.0f * pcg32_float(rng) - 1.0f + 0x1p-24f;
        float y = 2.0f * pcg32_float(rng) - 1.0f + 0x1p-24f;
        if ((double)x * x + (double)y * y < 1.0)
            return v2(x, y);
    }
}

vec3 mc_warp_cosine_hemisphere(vec2 u)
{
    /* Malley's method: a uniform disk point lifted to the hemisphere has density cosθ/π
     * (pbrt-v4 SampleCosineHemisphere). */
    vec2 d = mc_warp_concentric_disk(u);
    float z = sqrtf(f_max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return v3(d.x, d.y, z);
}

float mc_warp_cosine_hemisphere_pdf(float cos_theta)
{
    return cos_theta > 0.0f ? cos_theta * MC_INV_PI : 0.0f;
}

/* The unit vector at polar cosine z (with sinθ given) and azimuth 2π·u. */
static vec3 spherical(float sin_theta, float z, float u)
{
    float phi = 2.0f * MC_PI * u;
    return v3(sin_theta * cosf(phi), sin_theta * sinf(phi), z);
}

vec3 mc_warp_uniform_hemisphere(vec2 u)
{
    /* Archimedes: z is uniform on [0, 1] for a uniform hemisphere (pbrt-v4 SampleUniformHemisphere). */
    float z = u.x;
    return spherical(sqrtf(f_max(0.0f, 1.0f - z * z)), z, u.y);
}

float mc_warp_uniform_hemisphere_pdf(void) { return 0.5f * MC_INV_PI; }

vec3 mc_warp_uniform_sphere(vec2 u)
{
    float z = 1.0f - 2.0f * u.x;
    return spherical(sqrtf(f_max(0.0f, 1.0f - z * z)), z, u.y);
}

float mc_warp_uniform_sphere_pdf(void) { return 0.25f * MC_INV_PI; }

/* 1 − cosθmax without cancellation: for cosθmax near 1 the difference loses every digit in
 * float (θmax < 2.4e-4 rad gives cosθmax == 1), while sin²θ/(1 + cosθ) keeps full precision.
 * For cones wider than a hemisphere 1 + cosθmax may vanish, but there 1 − cosθmax is exact. */
static float one_minus_cos_max(float cos_max, float sin2_max)
{
    return cos_max > 0.0f ? sin2_max / (1.0f + cos_max) : 1.0f - cos_max;
}

vec3 mc_warp_uniform_cone(vec2 u, float cos_max, float sin2_max)
{
    /* z = cosθ is uniform on [cosθmax, 1] (as in pbrt-v4 SampleUniformCone), here expressed
     * through t = 1 − cosθ = u·(1 − cosθmax) so that sin²θ = t(2 − t) is computed without the
     * cancellation of 1 − cos²θ; pbrt-v4 SampleSphere resorts to a Taylor expansion for the
     * same reason. cos²θ + sin²θ = (1 − t)² + t(2 − t) = 1 exactly, so the result is unit. */
    float t = u.x * one_minus_cos_max(cos_max, sin2_max);
    return spherical(sqrtf(f_max(0.0f, t * (2.0f - t))), 1.0f - t, u.y);
}

float mc_warp_uniform_cone_pdf(float cos_max, float sin2_max)
{
    /* The cone's solid angle is 2π(1 − cosθmax); a degenerate cone (sin2_max = 0) has no
     * density and reports 0 so that callers discard it rather than divide by 0. */
    float omc = one_minus_cos_max(cos_max, sin2_max);
    return omc > 0.0f ? 1.0f / (2.0f * MC_PI * omc) : 0.0f;
}

vec2 mc_warp_triangle(vec2 u)
{
    /* Heitz 2019, "A Low-Distortion Map Between Triangle and Square" (Listing 1; pbrt-v4
     * SampleUniformTriangle): the square's lower and upper halves shear onto the triangle
     * with constant Jacobian, so uniform u gives uniform barycentrics. */
    float b1, b2;
    if (u.x < u.y) {
        b1 = u.x * 0.5f;
        b2 = u.y - b1;
    } else {
        b2 = u.y * 0.5f;
        b1 = u.x - b2;
    }
    return v2(b1, b2);
}
