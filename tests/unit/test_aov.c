/* test_aov.c: the extra image layers of a render (mcrt_options.aovs) read back from its EXR: the
 * albedo, normal and depth of a plane facing the camera are known exactly, and the variance layer
 * is the one src/render/film.c computes; through a mirror, the layers of the first non-specular
 * surface and its emission (the denoiser's, per half). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/image.h"
#include "mcrt.h"
#include "t.h"

/* A quad at z = -5 filling the view of a camera at the origin looking down -z, lit by the
 * environment; its colour is (0.5, 0.25, 0.125). */
static const char scene_text[] =
    "film { width 8 height 6 spp 4 }\n"
    "camera { eye 0 0 0  look 0 0 -1  fov 30 }\n"
    "material m { diffuse 0.5 0.25 0.125 }\n"
    "quad { corner -50 -50 -5  edge1 100 0 0  edge2 0 100 0  material m }\n"
    "environment { radiance 1 }\n";

/* The same camera before a mirror of reflectance 0.8 at z = -2 facing it; behind the camera, at
 * z = 5 facing it, the quad of colour m emitting (2, 3, 4): the first non-specular surface. */
static const char mirror_text[] =
    "film { width 8 height 6 spp 4 }\n"
    "camera { eye 0 0 0  look 0 0 -1  fov 30 }\n"
    "material m { diffuse 0.5 0.25 0.125 }\n"
    "material mir { mirror 0.8 }\n"
    "quad { corner -50 -50 -2  edge1 100 0 0  edge2 0 100 0  material mir }\n"
    "quad { corner -50 -50 5  edge1 0 100 0  edge2 100 0 0  material m  emit 2 3 4 }\n";

/* Whether every pixel of layer `name` of path is v within 1e-6 relative (float products). */
static int layer_is(const char *path, const char *name, float r, float g, float b)
{
    struct image im = {0, 0, NULL};
    mc_diag d;
    int i, ok = mc_image_read_layer(path, name, &im, &d) == MCRT_OK;
    for (i = 0; ok && i < im.width * im.height; i++)
        ok = fabsf(im.rgb[3 * i] - r) <= 1e-6f * fabsf(r) && fabsf(im.rgb[3 * i + 1] - g) <= 1e-6f * fabsf(g)
             && fabsf(im.rgb[3 * i + 2] - b) <= 1e-6f * fabsf(b);
    mc_image_free(&im);
    return ok;
}

/* The first non-specular surface through a mirror (mcrt_options.denoise records its layers per
 * half): albedo and emission times the mirror's 0.8, the normal facing the reflected ray, the
 * depth the whole path, 2 + 7 = 9 on the axis; and the denoised render keeps its raw image. */
static void mirror(const char *path)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r;
    mcrt_options o;
    struct image im = {0, 0, NULL}, raw = {0, 0, NULL};
    mc_diag d;
    int i, ok;
    T_CHECK(mcrt_scene_load_string(s, mirror_text, strlen(mirror_text), NULL) == MCRT_OK, "%s",
            mcrt_scene_error(s));
    mcrt_options_init(&o);
    o.denoise = 1;
    r = mcrt_render_new(s, &o);
    T_CHECK(mcrt_render_run(r) == MCRT_OK && mcrt_render_save(r, path) == MCRT_OK, "%s",
            mcrt_render_error(r));
    T_CHECK(layer_is(path, "albedo.A", 0.4f, 0.2f, 0.1f) && layer_is(path, "albedo.B", 0.4f, 0.2f, 0.1f),
            "albedo through the mirror: 0.8 times the quad's");
    T_CHECK(layer_is(path, "emission.A", 1.6f, 2.4f, 3.2f) && layer_is(path, "emission.B", 1.6f, 2.4f, 3.2f),
            "emission through the mirror: 0.8 times the quad's");
    T_CHECK(layer_is(path, "normal.A", 0.0f, 0.0f, -1.0f), "the normal faces the reflected ray");
    ok = mc_image_read_layer(path, "depth.B", &im, &d) == MCRT_OK;
    for (i = 0; ok && i < 8 * 6; i++)
        ok = im.rgb[3 * i] >= 8.9999f && im.rgb[3 * i] < 9.0f * 1.0955f;
    T_CHECK(ok, "depth: the path's length, between 9 and 9.86 (pixel %d)", i - 1);
    mc_image_free(&im);
    /* The emission's variance is 0: every ray sees the same. */
    T_CHECK(layer_is(path, "emission.var", 0.0f, 0.0f, 0.0f), "emission.var 0");
    ok = mc_image_read_layer(path, "raw", &raw, &d) == MCRT_OK;
    T_CHECK(ok, "a denoised render keeps the layer raw: %s", ok ? "" : d.msg);
    mc_image_free(&raw);
    mcrt_render_free(r);
    mcrt_scene_free(s);
    unlink(path);
}

int main(void)
{
    char dir[] = "/tmp/mcrt-aov-XXXXXX", path[64];
    mcrt_scene *s = mcrt_scene_new();
    mcrt_render *r;
    mcrt_options o;
    mcrt_stats st;
    struct image im = {0, 0, NULL}, var = {0, 0, NULL}, ha = {0, 0, NULL}, hb = {0, 0, NULL};
    mc_diag d;
    int ok, i, halves_ok = 1;
    double est = 0.0;

    if (!mcrt_format_supported("exr")) {
        T_SKIP("the AOV layers: built without OpenEXR");
        return t_done();
    }
    if (!mkdtemp(dir)) {
        T_CHECK(0, "mkdtemp");
        return t_done();
    }
    snprintf(path, sizeof path, "%s/a.exr", dir);
    T_CHECK(mcrt_scene_load_string(s, scene_text, strlen(scene_text), NULL) == MCRT_OK, "%s",
            mcrt_scene_error(s));
    mcrt_options_init(&o);
    o.aovs = "depth,albedo,normal,variance,halves";
    r = mcrt_render_new(s, &o);
    T_CHECK(mcrt_render_run(r) == MCRT_OK && mcrt_render_save(r, path) == MCRT_OK, "%s",
            mcrt_render_error(r));

    ok = mc_image_read_layer(path, "albedo", &im, &d) == MCRT_OK;
    for (i = 0; ok && i < 8 * 6; i++)
        ok = im.rgb[3 * i] == 0.5f && im.rgb[3 * i + 1] == 0.25f && im.rgb[3 * i + 2] == 0.125f;
    T_CHECK(ok, "albedo is the material colour everywhere");
    mc_image_free(&im);
    /* The normal (0, 0, 1) faces the camera; averages of equal unit vectors stay exact. */
    ok = mc_image_read_layer(path, "normal", &im, &d) == MCRT_OK;
    for (i = 0; ok && i < 8 * 6; i++)
        ok = im.rgb[3 * i] == 0.0f && im.rgb[3 * i + 1] == 0.0f && im.rgb[3 * i + 2] == 1.0f;
    T_CHECK(ok, "normal (0, 0, 1) everywhere");
    mc_image_free(&im);
    /* Depth is the distance 5/cos θ to the plane: between 5 and 5/cos θ at the corners, where
     * tan θ = tan 15° · sqrt(1 + (8/6)²) = 0.447, so 5·sqrt(1 + 0.2) = 5.477; all channels equal. */
    ok = mc_image_read_layer(path, "depth", &im, &d) == MCRT_OK;
    for (i = 0; ok && i < 8 * 6; i++)
        ok = im.rgb[3 * i] >= 4.9999f && im.rgb[3 * i] < 5.478f && im.rgb[3 * i] == im.rgb[3 * i + 2];
    T_CHECK(ok, "depth between 5 and 5.477 (pixel %d)", i - 1);
    mc_image_free(&im);
    /* The variance layer and the halves give back the render's est_relmse, Σ var/(A·B + 0.01)
     * (float rounding of the stored layers: relative 1e-6), and the mean of the halves is the
     * image (equal halves: 2 + 2 samples). */
    ok = mc_image_read_layer(path, "variance", &var, &d) == MCRT_OK &&
         mc_image_read_layer(path, "A", &ha, &d) == MCRT_OK &&
         mc_image_read_layer(path, "B", &hb, &d) == MCRT_OK && mc_image_read(path, &im, &d) == MCRT_OK;
    T_CHECK(ok, "the variance, A and B layers: %s", ok ? "" : d.msg);
    for (i = 0; ok && i < 8 * 6 * 3; i++) {
        est += var.rgb[i] / ((double)ha.rgb[i] * hb.rgb[i] + 0.01);
        halves_ok &= fabsf(0.5f * (ha.rgb[i] + hb.rgb[i]) - im.rgb[i]) <= 1e-6f * im.rgb[i];
    }
    T_CHECK(halves_ok, "the image is the mean of the halves A and B");
    mc_image_free(&ha);
    mc_image_free(&hb);
    mcrt_render_stats(r, &st, sizeof st);
    T_NEAR(est / (8 * 6 * 3) / st.est_relmse, 1.0, 1e-5, "est_relmse from the layers");
    T_CHECK(st.est_relmse > 0.0, "the estimate is positive: %g", st.est_relmse);
    mc_image_free(&im);
    mc_image_free(&var);
    mcrt_render_free(r);
    mcrt_scene_free(s);
    unlink(path);
    mirror(path);
    rmdir(dir);
    return t_done();
}
