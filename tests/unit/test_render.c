/* test_render.c: whole renders through the public API against closed-form answers:
 * a Lambertian plane under a point light, the white furnace, the emitting-sphere furnace
 * Le/(1−ρ), path vs direct where only direct light exists, thread-count determinism, and each
 * integrator named by the scene or by the options alike.
 * Tolerances come from the noise: the standard error of a region's mean is estimated from the
 * spread of its pixel means (pixels are independent), and a region passes within 4 standard
 * errors (two-sided p ≈ 6e-5 per check). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"
#include "render_util.h"
#include "t.h"

static const double PI = 3.14159265358979323846;

struct img {
    int w, h;
    float *rgb;
    mcrt_stats stats;
};

/* Render scene text with the given options; returns 0 on success. */
static int render(const char *text, int spp, int threads, const char *integrator, struct img *out)
{
    struct t_render_opts o = {0, 0, 0, 7, NULL, NULL};
    memset(out, 0, sizeof *out);
    o.spp = spp;
    o.threads = threads;
    o.integrator = integrator;
    out->rgb = t_render(text, &o, &out->w, &out->h, &out->stats);
    return out->rgb ? 0 : -1;
}

/* Mean and standard error of the green channel over pixels whose centre lies within radius rad
 * (in pixels) of the image centre. */
static void disk_mean(const struct img *im, double rad, double *mean, double *se)
{
    double sum = 0.0, sum2 = 0.0;
    int x, y, n = 0;
    for (y = 0; y < im->h; y++)
        for (x = 0; x < im->w; x++) {
            double dx = x + 0.5 - im->w / 2.0, dy = y + 0.5 - im->h / 2.0;
            double v = im->rgb[3 * (y * im->w + x) + 1];
            if (dx * dx + dy * dy > rad * rad)
                continue;
            sum += v;
            sum2 += v * v;
            n++;
        }
    *mean = sum / n;
    *se = sqrt(fmax(0.0, sum2 / n - *mean * *mean) / (n - 1));
}

/* A Lambertian plane y = 0 (albedo 0.5) under a point light of intensity I at height 2, seen
 * from straight above: the radiance at x is albedo/π · I · cosθ / r² (no noise: the light is a
 * delta, nothing else is visible). Each pixel is compared with that function averaged over the
 * pixel's footprint by 8×8 quadrature, to 0.5%. What separates the two is the jittered 8×8
 * estimate of the pixel integral: for a function varying by a fraction v across a pixel its error
 * is about v/(8·√12·8) ≈ v/220, and v < 10% here, so 0.5% leaves a wide margin. */
static void test_point_light_plane(void)
{
    const char *scene = "film { width 64 height 48 spp 64 }\n"
                        "camera { eye 0 6 0 look 0 0 0 up 0 0 -1 fov 50 }\n"
                        "material m { diffuse 0.5 }\n"
                        "quad { corner -100 0 100 edge1 200 0 0 edge2 0 0 -200 material m }\n"
                        "point_light { position 0.5 2 -0.5 intensity 10 }\n";
    const double albedo = 0.5, I = 10.0, lx = 0.5, ly = 2.0, lz = -0.5;
    /* The camera basis, as the scene language defines it: f = (0,-1,0), up (0,0,-1),
     * r = f × up = (1,0,0), u = r × f = (0,0,-1). */
    double e[3] = {0, 6, 0}, f[3] = {0, -1, 0}, r[3] = {1, 0, 0}, u[3] = {0, 0, -1};
    double th = tan(0.5 * 50.0 * PI / 180.0);
    struct img im;
    int x, y, worst_x = 0, worst_y = 0, bad = 0;
    double worst = 0.0;
    if (render(scene, 0, 2, "path", &im) != 0) {
        T_CHECK(0, "render failed");
        return;
    }
    for (y = 0; y < im.h; y++)
        for (x = 0; x < im.w; x++) {
            double expect = 0.0, got = im.rgb[3 * (y * im.w + x)], rel;
            int i, j;
            for (j = 0; j < 8; j++)
                for (i = 0; i < 8; i++) {
                    double fx = x + (i + 0.5) / 8, fy = y + (j + 0.5) / 8, d[3], t, p[3], w[3], r2,
                           cosl;
                    double sx = (2 * fx / im.w - 1) * th * im.w / im.h, sy = (1 - 2 * fy / im.h) * th;
                    int k;
                    for (k = 0; k < 3; k++)
                        d[k] = f[k] + sx * r[k] + sy * u[k];
                    t = -e[1] / d[1];
                    for (k = 0; k < 3; k++)
                        p[k] = e[k] + t * d[k];
                    w[0] = lx - p[0];
                    w[1] = ly - p[1];
                    w[2] = lz - p[2];
                    r2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
                    cosl = w[1] / sqrt(r2);
                    expect += albedo / PI * I * cosl / r2 / 64.0;
                }
            rel = fabs(got - expect) / expect;
            if (rel > worst) {
                worst = rel;
                worst_x = x;
                worst_y = y;
            }
            bad += rel > 0.005;
        }
    T_NOTE("point light on a plane: worst relative error %.2e at pixel (%d,%d)", worst, worst_x,
           worst_y);
    T_CHECK(bad == 0, "%d pixels off by more than 0.5%%", bad);
    T_CHECK(im.stats.nan_count == 0, "%llu NaN samples", (unsigned long long)im.stats.nan_count);
    free(im.rgb);
}

/* White furnace: a diffuse sphere of albedo 0.8 alone in a constant environment of radiance 1.
 * The sphere is convex, so every bounce sees only the sky: L = 0.8 exactly, and 1 around it. */
static void test_white_furnace(void)
{
    const char *scene = "film { width 64 height 64 spp 32 }\n"
                        "camera { eye 0 0 5 fov 30 }\n"
                        "environment { radiance 1 }\n"
                        "material m { diffuse 0.8 }\n"
                        "sphere { material m }\n";
    struct img im;
    double mean, se;
    /* The sphere's silhouette radius in pixels: tan(asin(1/5)) / tan(15°) · 32. */
    double rad = tan(asin(0.2)) / tan(15.0 * PI / 180.0) * 32.0;
    if (render(scene, 0, 2, NULL, &im) != 0) {
        T_CHECK(0, "render failed");
        return;
    }
    disk_mean(&im, rad - 2.0, &mean, &se);
    T_NOTE("white furnace: sphere mean %.5f ± %.5f (expect 0.8)", mean, se);
    T_CHECK(fabs(mean - 0.8) < 4.0 * se + 1e-6, "sphere mean %.5f, se %.5f", mean, se);
    T_NEAR(im.rgb[0], 1.0, 1e-6, "background");
    free(im.rgb);
}

/* Inside a closed sphere that emits Le = 1 inward and has albedo ρ = 0.5, every path sees the
 * geometric series Le·(1 + ρ + ρ² + …) = Le/(1 − ρ) = 2, whatever the geometry. Russian roulette
 * ends the paths, so this checks that it stays unbiased. */
static void test_emitting_sphere_furnace(void)
{
    const char *scene = "film { width 32 height 32 spp 64 }\n"
                        "camera { eye 0 0 0 look 0 0 -1 fov 90 }\n"
                        "material m { diffuse 0.5 }\n"
                        "sphere { radius 10 material m emit 1 flip }\n";
    struct img im;
    double mean, se;
    if (render(scene, 0, 2, NULL, &im) != 0) {
        T_CHECK(0, "render failed");
        return;
    }
    disk_mean(&im, 1e9, &mean, &se);
    T_NOTE("emitting sphere furnace: mean %.5f ± %.5f (expect 2)", mean, se);
    T_CHECK(fabs(mean - 2.0) < 4.0 * se + 1e-6, "mean %.5f, se %.5f", mean, se);
    free(im.rgb);
}

/* Where only direct light exists (a black, one-sided light over a plane that sees nothing else),
 * path and direct estimate the same image: the difference of their means is within noise. */
static void test_path_equals_direct(void)
{
    const char *scene = "film { width 48 height 48 spp 16 }\n"
                        "camera { eye 0 3 4 look 0 0 0 fov 50 }\n"
                        "material black { diffuse 0 }\n"
                        "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
                        "quad { corner -0.5 1.5 -0.5 edge1 1 0 0 edge2 0 0 1 emit 4 material black }\n";
    struct img a, b;
    double ma, sa, mb, sb;
    if (render(scene, 0, 2, "path", &a) != 0 || render(scene, 0, 2, "direct", &b) != 0) {
        T_CHECK(0, "render failed");
        return;
    }
    disk_mean(&a, 1e9, &ma, &sa);
    disk_mean(&b, 1e9, &mb, &sb);
    T_NOTE("path %.5f ± %.5f, direct %.5f ± %.5f", ma, sa, mb, sb);
    T_CHECK(fabs(ma - mb) < 4.0 * sqrt(sa * sa + sb * sb), "path %.5f vs direct %.5f", ma, mb);
    free(a.rgb);
    free(b.rgb);
}

/* The image depends on (scene, options, seed) only: 1 and 2 threads give identical bits. */
static void test_thread_determinism(void)
{
    const char *scene = "film { width 40 height 24 spp 8 }\n"
                        "material red { diffuse 0.7 0.2 0.2 }\n"
                        "material glass { glass ior 1.5 }\n"
                        "sphere { center -1 0 0 material red }\n"
                        "sphere { center 1.2 0 0 radius 0.8 material glass }\n"
                        "quad { corner -5 -1 5 edge1 10 0 0 edge2 0 0 -10 }\n"
                        "sphere { center 0 4 0 radius 0.5 emit 10 }\n";
    struct img a, b;
    if (render(scene, 0, 1, NULL, &a) != 0 || render(scene, 0, 2, NULL, &b) != 0) {
        T_CHECK(0, "render failed");
        return;
    }
    T_CHECK(memcmp(a.rgb, b.rgb, (size_t)a.w * a.h * 3 * sizeof(float)) == 0,
            "1-thread and 2-thread images differ");
    T_CHECK(a.stats.rays == b.stats.rays, "ray counts differ: %llu vs %llu",
            (unsigned long long)a.stats.rays, (unsigned long long)b.stats.rays);
    free(a.rgb);
    free(b.rgb);
}

/* Every integrator of the table is the same word in a scene and in the options: the scene's
 * `integrator { method NAME }` and mcrt_options.integrator = NAME give the same bits. */
static void test_method_is_option(void)
{
    const char *scene = "film { width 24 height 16 spp 4 }\n"
                        "material mirror { mirror 0.9 }\n"
                        "sphere { center -1 0 0 material mirror }\n"
                        "quad { corner -5 -1 5 edge1 10 0 0 edge2 0 0 -10 }\n"
                        "sphere { center 0 4 0 radius 0.5 emit 10 }\n"
                        "point_light { position 2 3 2 intensity 5 }\n";
    const char *const *names = mcrt_names("integrator");
    const char *name;
    int i;
    for (i = 0; (name = names[i]); i++) {
        char text[1024];
        struct img a, b;
        snprintf(text, sizeof text, "integrator { method %s }\n%s", name, scene);
        if (render(text, 0, 2, NULL, &a) != 0 || render(scene, 0, 2, name, &b) != 0) {
            T_CHECK(0, "%s: render failed", name);
            continue;
        }
        T_CHECK(a.w == b.w && a.h == b.h
                    && memcmp(a.rgb, b.rgb, (size_t)a.w * a.h * 3 * sizeof(float)) == 0,
                "method %s and --integrator %s differ", name, name);
        free(a.rgb);
        free(b.rgb);
    }
    T_CHECK(i >= 5 && mcrt_describe("integrator", "path") && !mcrt_describe("integrator", "bogus")
                && !mcrt_describe("sampler", "random"),
            "%d integrators, described", i);
}

int main(void)
{
    test_point_light_plane();
    test_white_furnace();
    test_emitting_sphere_furnace();
    test_path_equals_direct();
    test_thread_determinism();
    test_method_is_option();
    return t_done();
}
