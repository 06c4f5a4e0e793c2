/* test_features.c: the render is built from the features a scene uses (scene/features.h).
 * `mcrt info` reports them and the sample dimensions they cost; the specialised code paths render
 * the same image in expectation as the general one (--all-features).
 *
 * Image agreement: the two renders use different sample dimensions, so they are independent
 * estimates. The image is cut into 8×8 blocks; in each, the mean of the per-pixel difference has a
 * standard error estimated from the spread of those differences (pixels are independent). A block
 * fails at |z| > 4.5: two-sided p = 6.8e-6 per block, under 2e-3 for the 4 × 64 blocks of all
 * scenes together (Šidák), so a pass is not luck and a real bias of a few standard errors is caught. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mcrt.h"
#include "render_util.h"
#include "t.h"

static float *render(const char *text, int all_features, int spp, int *w, int *h)
{
    struct t_render_opts o = {0, 2, 0, 11, NULL, NULL};
    o.spp = spp;
    o.all_features = all_features;
    return t_render(text, &o, w, h, NULL);
}

/* Worst block z of (a − b) over 8×8 blocks of the green channel; blocks with no spread (both exact,
 * e.g. background) must agree exactly. */
static double worst_block_z(const float *a, const float *b, int w, int h)
{
    double worst = 0.0;
    int bx, by;
    for (by = 0; by < 8; by++)
        for (bx = 0; bx < 8; bx++) {
            double sum = 0.0, sum2 = 0.0, mean, se;
            int x, y, n = 0;
            for (y = by * h / 8; y < (by + 1) * h / 8; y++)
                for (x = bx * w / 8; x < (bx + 1) * w / 8; x++) {
                    size_t i = 3 * ((size_t)y * (size_t)w + (size_t)x) + 1;
                    double d = (double)a[i] - (double)b[i];
                    sum += d;
                    sum2 += d * d;
                    n++;
                }
            mean = sum / n;
            se = sqrt(fmax(0.0, sum2 / n - mean * mean) / (n - 1));
            if (se == 0.0 && mean != 0.0)
                return INFINITY;
            if (se > 0.0 && fabs(mean) / se > worst)
                worst = fabs(mean) / se;
        }
    return worst;
}

struct case_ {
    const char *name, *text, *features;
    int camera_dims;
};

static const struct case_ cases[] = {
    {"point lights only (no MIS)",
     "film { width 64 height 64 }\ncamera { eye 0 2 4 look 0 0 0 }\n"
     "sphere { center 0 0.5 0 radius 0.5 }\n"
     "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
     "point_light { position 1 3 1 intensity 10 }\npoint_light { position -2 2 0 intensity 3 }\n",
     "features: delta_lights\n", 2},
    {"area light, glossy and mirror",
     "film { width 64 height 64 }\ncamera { eye 0 1 4 look 0 0.5 0 }\n"
     "material m { metal 0.9 0.6 0.3 roughness 0.3 }\nmaterial c { mirror 0.9 }\n"
     "sphere { center -0.6 0.5 0 radius 0.5 material m }\n"
     "sphere { center 0.6 0.5 0 radius 0.5 material c }\n"
     "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
     "disk { center 0 3 0 normal 0 -1 0 radius 0.6 emit 8 }\n",
     "features: area_lights glossy specular\n", 2},
    {"lens and light samples",
     "film { width 64 height 64 }\n"
     "camera { eye 0 1 4 look 0 0.5 0 lens_radius 0.1 }\n"
     "integrator { light_samples 3 }\n"
     "sphere { center -0.6 0.5 0 radius 0.5 }\n"
     "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
     "quad { corner -0.5 3 -0.5 edge1 1 0 0 edge2 0 0 1 flip emit 8 }\n"
     "environment { radiance 0.2 }\n",
     "features: lens area_lights environment light_samples\n", 4},
    {"motion under a point light",
     "film { width 64 height 64 }\ncamera { eye 0 1 4 look 0 0.5 0 }\n"
     "sphere { center -0.6 0.5 0 radius 0.5 move 1 0 0 }\n"
     "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
     "point_light { position 0 3 1 intensity 10 }\n",
     "features: motion delta_lights\n", 3},
};

static void test_info(void)
{
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        mcrt_scene *s = mcrt_scene_new();
        const char *info, *dims;
        int n = -1;
        T_CHECK(mcrt_scene_load_string(s, cases[i].text, strlen(cases[i].text), "info") == MCRT_OK,
                "%s", mcrt_scene_error(s));
        info = mcrt_scene_info(s);
        T_CHECK(strncmp(info, cases[i].features, strlen(cases[i].features)) == 0,
                "%s: info says '%.80s'", cases[i].name, info);
        dims = strstr(info, "sample dimensions: ");
        T_CHECK(dims && sscanf(dims, "sample dimensions: %d", &n) == 1 && n == cases[i].camera_dims,
                "%s: %d dimensions per camera ray, expected %d", cases[i].name, n,
                cases[i].camera_dims);
        mcrt_scene_free(s);
    }
}

static void test_general_path_agrees(void)
{
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int w = 0, h = 0, w2 = 0, h2 = 0;
        float *a = render(cases[i].text, 0, 64, &w, &h), *b = render(cases[i].text, 1, 64, &w2, &h2);
        T_CHECK(a && b && w == w2 && h == h2, "%s: both rendered", cases[i].name);
        if (a && b) {
            double z = worst_block_z(a, b, w, h);
            T_CHECK(z < 4.5, "%s: specialised vs general worst block |z| = %.2f (limit 4.5)",
                    cases[i].name, z);
            T_NOTE("%s: specialised vs general, worst block |z| = %.2f", cases[i].name, z);
        }
        free(a);
        free(b);
    }
}

/* Several shadow rays per hit estimate the same image (Veach's multi-sample MIS keeps the weights
 * summing to one for any number of light samples), with less noise in the soft shadows. */
static void test_light_samples(void)
{
    static const char one[] =
        "film { width 64 height 64 }\ncamera { eye 0 3 4 look 0 0 0 }\n"
        "sphere { center 0 0.6 0 radius 0.5 }\n"
        "quad { corner -3 0 3 edge1 6 0 0 edge2 0 0 -6 }\n"
        "disk { center 0.5 2.5 0 normal 0 -1 0 radius 0.8 emit 4 }\n"
        "integrator { light_samples 1 }\n";
    char four[sizeof one];
    int w = 0, h = 0, w2 = 0, h2 = 0;
    float *a, *b;
    memcpy(four, one, sizeof one);
    four[strlen(four) - 4] = '4';
    a = render(one, 0, 64, &w, &h);
    b = render(four, 0, 64, &w2, &h2);
    T_CHECK(a && b && w == w2 && h == h2, "both rendered");
    if (a && b) {
        double z = worst_block_z(a, b, w, h);
        T_CHECK(z < 4.5, "light_samples 1 vs 4: worst block |z| = %.2f (limit 4.5)", z);
        T_NOTE("light_samples 1 vs 4: worst block |z| = %.2f", z);
    }
    free(a);
    free(b);
}

int main(void)
{
    test_info();
    test_general_path_agrees();
    test_light_samples();
    return t_done();
}
