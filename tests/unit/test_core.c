/* test_core.c: the small shared pieces: vector math and frames, PCG32, robust ray offsets, the
 * per-pixel sampler, the film accumulator and the camera mapping. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "camera/camera.h"
#include "core/rng.h"
#include "core/vec.h"
#include "geom/ray.h"
#include "render/film.h"
#include "sample/sampler.h"
#include "t.h"

static void test_vec(void)
{
    vec3 a = v3(1, 2, 3), b = v3(-4, 5, 0.5f), c = v3_cross(a, b);
    pcg32 rng;
    int i;
    T_NEAR(v3_dot(a, b), 1 * -4 + 2 * 5 + 3 * 0.5, 0, "dot");
    /* a × b is orthogonal to both and follows the right-hand rule: x × y = z. */
    T_NEAR(v3_dot(c, a), 0, 1e-5, "cross ⟂ a");
    T_NEAR(v3_dot(c, b), 0, 1e-5, "cross ⟂ b");
    T_NEAR(v3_cross(v3(1, 0, 0), v3(0, 1, 0)).z, 1, 0, "x × y = z");
    T_NEAR(v3_length(v3_normalize(b)), 1, 1e-6, "normalize");
    T_CHECK(v3_is_zero(v3_normalize(v3s(0))), "normalising zero gives zero, not NaN");
    T_NEAR(v3_max_comp(b), 5, 0, "max component");
    T_CHECK(!v3_is_finite(v3(0, NAN, 0)) && !v3_is_finite(v3(INFINITY, 0, 0)), "finite test");
    /* Duff et al.'s basis is orthonormal and right-handed for every normal, including the poles
     * and the -z hemisphere where the naive 1/(1+z) form breaks down. */
    pcg32_seed(&rng, 1, 2);
    for (i = 0; i < 100000; i++) {
        vec3 n, w, back;
        frame f;
        double err;
        if (i == 0)
            n = v3(0, 0, -1);
        else if (i == 1)
            n = v3(0, 0, 1);
        else if (i == 2)
            n = v3(0, -1e-30f, -1);
        else
            n = v3_normalize(v3(pcg32_float(&rng) * 2 - 1, pcg32_float(&rng) * 2 - 1,
                                pcg32_float(&rng) * 2 - 1));
        f = frame_from_normal(v3_normalize(n));
        err = fabs(v3_dot(f.t, f.b)) + fabs(v3_dot(f.t, f.n)) + fabs(v3_dot(f.b, f.n))
              + fabs(v3_length(f.t) - 1) + fabs(v3_length(f.b) - 1)
              + v3_length(v3_sub(v3_cross(f.t, f.b), f.n));
        w = v3(0.3f, -0.5f, 0.8f);
        back = frame_to_world(&f, frame_to_local(&f, w));
        err += v3_length(v3_sub(back, w));
        if (!(err < 1e-5)) {
            T_CHECK(0, "frame for n = (%g, %g, %g): error %g", n.x, n.y, n.z, err);
            return;
        }
    }
    T_CHECK(1, "100000 frames orthonormal");
}

/* The reference outputs of pcg32_srandom_r(42, 54), from O'Neill's pcg32-demo. */
static void test_pcg32(void)
{
    pcg32 r;
    uint32_t first[3];
    int i, hist[10] = {0};
    float lo = 1, hi = 0;
    pcg32_seed(&r, 42, 54);
    first[0] = pcg32_next(&r);
    first[1] = pcg32_next(&r);
    first[2] = pcg32_next(&r);
    T_CHECK(first[0] == 0xa15c02b7u && first[1] == 0x7b47f409u && first[2] == 0xba1d3330u,
            "pcg32 outputs %08x %08x %08x", first[0], first[1], first[2]);
    for (i = 0; i < 1000000; i++) {
        float u = pcg32_float(&r);
        lo = fminf(lo, u);
        hi = fmaxf(hi, u);
        hist[(int)(u * 10)]++;
    }
    T_CHECK(lo >= 0 && hi < 1, "floats in [0,1): [%g, %g]", lo, hi);
    /* Each decile holds 1e5 ± 300 (σ = √(1e6·0.1·0.9)); 5σ = 1500. */
    for (i = 0; i < 10; i++)
        T_CHECK(abs(hist[i] - 100000) < 1500, "decile %d holds %d", i, hist[i]);
    T_CHECK(mc_hash3(1, 2, 3) != mc_hash3(1, 3, 2), "hash depends on order");
}

/* A point offset along n must land strictly on n's side of the plane through p with normal n,
 * at any magnitude, and stay close to p. */
static void test_ray_offset(void)
{
    pcg32 r;
    int i, bad = 0;
    double worst = 0;
    pcg32_seed(&r, 3, 4);
    for (i = 0; i < 200000; i++) {
        float scale = powf(10.0f, pcg32_float(&r) * 16 - 8); /* 1e-8 .. 1e8 */
        vec3 p = v3_scale(v3(pcg32_float(&r) * 2 - 1, pcg32_float(&r) * 2 - 1,
                             pcg32_float(&r) * 2 - 1), scale);
        vec3 n = v3_normalize(v3(pcg32_float(&r) * 2 - 1, pcg32_float(&r) * 2 - 1,
                                 pcg32_float(&r) * 2 - 1));
        vec3 q = ray_offset(p, n);
        double side = (double)(q.x - p.x) * n.x + (double)(q.y - p.y) * n.y + (double)(q.z - p.z) * n.z;
        double rel = v3_length(v3_sub(q, p)) / fmax(v3_length(p), 1.0 / 32);
        bad += !(side > 0);
        if (rel > worst)
            worst = rel;
    }
    T_NOTE("ray offset: largest move relative to |p| %.2e", worst);
    T_CHECK(bad == 0, "%d offsets did not leave the surface on the normal's side", bad);
    /* At most 256 ulps per component (|p| ≥ 1/32): |Δ| ≤ √3·256·2^-23·|p| ≈ 5.3e-5·|p|; nearer
     * the origin a fixed 2^-16 per component, ≤ √3·2^-16 / (1/32) ≈ 8.5e-4 relative to 1/32. */
    T_CHECK(worst < 8.5e-4, "offset too large: %g", worst);
}

/* Stratified film positions: with spp = n², each of the n×n cells of the pixel gets exactly one
 * sample; samples are reproducible one by one; and other spp counts stay inside the pixel. */
static void test_sampler(void)
{
    struct sampler s;
    int counts[64], i, spp;
    vec2 u0, again;
    mc_sampler_pixel(&s, SAMPLER_STRATIFIED, 9, 5, 7, 64);
    memset(counts, 0, sizeof counts);
    for (i = 0; i < 64; i++) {
        vec2 u;
        mc_sampler_start(&s, (uint32_t)i);
        u = mc_sampler_2d(&s);
        counts[(int)(u.y * 8) * 8 + (int)(u.x * 8)]++;
    }
    for (i = 0; i < 64 && counts[i] == 1; i++)
        ;
    T_CHECK(i == 64, "cell %d has %d samples", i, i < 64 ? counts[i] : 0);
    mc_sampler_start(&s, 17);
    u0 = mc_sampler_2d(&s);
    (void)mc_sampler_1d(&s);
    mc_sampler_pixel(&s, SAMPLER_STRATIFIED, 9, 5, 7, 64);
    mc_sampler_start(&s, 17);
    again = mc_sampler_2d(&s);
    T_CHECK(u0.x == again.x && u0.y == again.y, "sample 17 regenerated differently");
    for (spp = 1; spp <= 40; spp++) {
        int out = 0;
        mc_sampler_pixel(&s, SAMPLER_STRATIFIED, 1, 0, 0, spp);
        for (i = 0; i < spp; i++) {
            vec2 u;
            mc_sampler_start(&s, (uint32_t)i);
            u = mc_sampler_2d(&s);
            out += !(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1);
        }
        if (out) {
            T_CHECK(0, "spp %d: %d samples outside the pixel", spp, out);
            return;
        }
    }
    /* Kensler's permute is a bijection of [0, n) for every n. */
    for (spp = 1; spp <= 300; spp++) {
        unsigned char seen[300];
        memset(seen, 0, sizeof seen);
        for (i = 0; i < spp; i++)
            seen[mc_permute((uint32_t)i, (uint32_t)spp, 12345u)]++;
        for (i = 0; i < spp && seen[i] == 1; i++)
            ;
        if (i < spp) {
            T_CHECK(0, "permute is not a bijection for n = %d", spp);
            return;
        }
    }
    T_CHECK(1, "samples inside the pixel; permute bijective");
}

/* Welford in double: 10⁶ samples of 1e-3 accumulate to 1e-3 without drift, next to a pixel of
 * 1e4, and the variance of alternating values is exact, with the samples spread over both halves
 * and the halves combined (Chan et al.). */
static void test_film(void)
{
    struct film f;
    struct film_sums a, b;
    int i;
    T_CHECK(mc_film_init(&f, 2, 1) == 0, "film");
    for (i = 0; i < 1000000; i++) {
        mc_film_add(&f.pixels[0].half[(i >> 1) & 1], v3s(1e-3f));
        mc_film_add(&f.pixels[1].half[(i >> 1) & 1], v3(1e4f, (i & 1) ? 1.0f : 3.0f, 0));
    }
    a = mc_film_pixel_sums(&f.pixels[0]);
    b = mc_film_pixel_sums(&f.pixels[1]);
    T_CHECK(a.count == 1000000 && b.count == 1000000, "counts");
    T_NEAR(a.mean[0], (double)1e-3f, 1e-15, "small pixel drifted");
    T_NEAR(b.mean[0], 1e4, 1e-9, "large pixel");
    T_NEAR(b.mean[1], 2.0, 1e-12, "alternating mean");
    T_NEAR(b.m2[1] / (1e6 - 1), 1e6 / (1e6 - 1), 1e-9, "alternating sample variance");
    mc_film_free(&f);
}

/* The camera follows the scene language's mapping: the film centre looks along forward, the top
 * left corner along f − tan(fov/2)·(W/H)·r + tan(fov/2)·u. */
static void test_camera(void)
{
    struct camera_desc d;
    struct camera c;
    struct ray r;
    float t = tanf(20.0f * MC_PI / 180.0f);
    vec3 want;
    memset(&d, 0, sizeof d); /* a still pinhole: no lens, no motion */
    d.shutter[1] = 1.0f;
    d.eye = v3(1, 2, 3);
    d.look = v3(1, 2, -7);
    d.up = v3(0, 1, 0);
    d.fov = 40;
    mc_camera_init(&c, &d, 200, 100);
    r = mc_camera_ray(&c, 100, 50);
    T_NEAR(v3_length(v3_sub(r.d, v3(0, 0, -1))), 0, 1e-6, "centre ray");
    T_CHECK(r.o.x == 1 && r.o.y == 2 && r.o.z == 3, "ray starts at the eye");
    r = mc_camera_ray(&c, 0, 0);
    want = v3_normalize(v3(-t * 2, t, -1)); /* right = f × up = (1,0,0) for f = -z */
    T_NEAR(v3_length(v3_sub(r.d, want)), 0, 1e-6, "top-left corner ray");
    T_NEAR(v3_length(r.d), 1, 1e-6, "unit direction");
}

int main(void)
{
    test_vec();
    test_pcg32();
    test_ray_offset();
    test_sampler();
    test_film();
    test_camera();
    return t_done();
}
