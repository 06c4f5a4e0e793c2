/* test_nomem.c: every allocation of a scene load, a render, a save and a comparison made to fail,
 * one at a time, in the manner of Lua's ltests.c (core/alloc.h's mc_alloc_fail_nth).
 *
 * For each operation and every n from 1 to the number of allocations it makes, the n-th
 * allocation fails: the call must return MCRT_ERR_NOMEM with a message on its handle and leave
 * the handle usable (a scene empty, a render without an image). Under `make check`,
 * LeakSanitizer then finds any memory a failure path forgot, and AddressSanitizer any use of
 * what it freed. libpng's and OpenEXR's allocations go through the same allocator (png.c and
 * exr.c give them mc_malloc), so their failures are made too. An operation that succeeds although
 * an allocation failed has made that allocation optional: mcrt has none (the test fails if one
 * appears), OpenEXR's reader has some (exr_start_read gets over failed allocations in its header
 * parsing), which must then give the result of a run without failures. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/alloc.h"
#include "mcrt.h"
#include "t.h"

/* Every kind of material, shape and light, the lens, motion blur (a moving sphere, a spinning
 * mesh), two OBJ meshes and a third large enough for the parallel BVH build (written by main),
 * the environment. OBJ paths are relative to the current directory, the repository's root. */
static const char scene_head[] =
    "film { width 12 height 8 spp 4 sampler sobol filter gaussian }\n"
    "camera { eye 0 2 8  look 0 0.8 0  fov 40  lens_radius 0.02  focus_distance 8  shutter 0 1 }\n"
    "integrator { method path  max_depth 6  rr_depth 3  light_samples 2 }\n"
    "material d { diffuse 0.7 }\n"
    "material m { mirror 0.9 }\n"
    "material g { glass ior 1.5 }\n"
    "material rg { glass ior 1.5  roughness 0.4 }\n"
    "material c { metal 0.9 0.8 0.7  roughness 0.3 }\n"
    "material ek { metal eta 0.2 0.9 1.1  k 3.9 2.4 2.2  roughness 0.5 }\n"
    "material p { plastic 0.5 0.1 0.1  roughness 0.2 }\n"
    "quad { corner -10 0 10  edge1 20 0 0  edge2 0 0 -20  material d }\n"
    "sphere { center -2 0.5 0  radius 0.5  material g  move 0.3 0 0 }\n"
    "sphere { center 2 0.5 0  radius 0.5  material rg }\n"
    "disk { center 0 0.01 2  normal 0 1 0  radius 0.5  material c }\n"
    "triangle { v0 -1 0 -2  v1 1 0 -2  v2 0 1.5 -2  material ek }\n"
    "mesh { file \"scenes/cube.obj\"  scale 0.4  translate 0.8 0.4 0.5  spin 0 1 0 20"
    "  material p }\n"
    "mesh { file \"scenes/icosphere.obj\"  scale 0.4  translate -0.8 0.4 0.5  material m }\n"
    "quad { corner -1 4 -1  edge1 2 0 0  edge2 0 0 2  emit 6 }\n"
    "sphere { center 3 3 1  radius 0.1  emit 50 }\n"
    "point_light { position -3 3 2  intensity 10 }\n"
    "environment { radiance 0.1 }\n";

/* A grid of GRID x GRID quads (2 GRID^2 triangles, above the 4096 of the parallel BVH build). */
#define GRID 48

static char dir[] = "/tmp/mcrt-nomem-XXXXXX";
static char scene_text[4096];

/* One operation under test: its status, and the message it left (copied before its handles are
 * freed). */
typedef mcrt_status (*op_fn)(char *msg, size_t size);

/* Run op with the n-th allocation failing, for n = 1, 2, ... until it makes fewer than n; checks
 * each outcome and reports the number of allocations op makes. optional_ok: op reads EXR images,
 * and may succeed (with the result of a run without failures) when OpenEXR's reader gets over a
 * failed allocation. */
static void sweep(const char *name, op_fn op, int optional_ok)
{
    char msg[512];
    size_t n, count = 0, bad_status = 0, no_message = 0, optional = 0;
    mcrt_status st;
    /* To look at one failure in a debugger: NOMEM_ONLY=n, and NOMEM_SWEEP=a part of the name. */
    const char *only = getenv("NOMEM_ONLY"), *which = getenv("NOMEM_SWEEP");
    if (only && which && !strstr(name, which))
        return;
    for (n = only ? strtoul(only, NULL, 10) : 1;; n++) {
        msg[0] = '\0';
        mc_alloc_fail_nth(n);
        st = op(msg, sizeof msg);
        count = mc_alloc_count();
        mc_alloc_fail_nth(0);
        if (count < n) {
            T_CHECK(st == MCRT_OK, "%s with every allocation granted: status %d: %s", name, (int)st,
                    msg);
            break;
        }
        if (st == MCRT_OK) {
            if (optional++ < 5 && !optional_ok)
                T_NOTE("%s: allocation %zu of %zu failed and the call still succeeded", name, n,
                       count);
        } else if (st != MCRT_ERR_NOMEM) {
            if (bad_status++ < 5)
                printf("  %s: allocation %zu of %zu failed: status %d (%s), want MCRT_ERR_NOMEM: %s\n",
                       name, n, count, (int)st, mcrt_status_string(st), msg);
        } else if (!msg[0] && no_message++ < 5) {
            printf("  %s: allocation %zu of %zu failed: MCRT_ERR_NOMEM without a message\n", name,
                   n, count);
        }
    }
    T_NOTE("%s: %zu allocations, each made to fail in turn", name, n - 1);
    T_CHECK(n > 1, "%s allocates", name);
    T_CHECK(bad_status == 0, "%s: %zu failed allocations reported as another status", name,
            bad_status);
    T_CHECK(no_message == 0, "%s: %zu failed allocations without a message", name, no_message);
    if (optional_ok)
        T_NOTE("%s: %zu allocations were optional (OpenEXR's)", name, optional);
    else
        T_CHECK(optional == 0, "%s: %zu allocations were optional", name, optional);
}

/* A failed load leaves an empty scene, which renders nothing and says so. */
static mcrt_status scene_left_empty(mcrt_scene *s, mcrt_status st, char *msg, size_t size)
{
    snprintf(msg, size, "%s", mcrt_scene_error(s));
    if (st != MCRT_OK && strcmp(mcrt_scene_info(s), "no scene loaded\n") != 0)
        snprintf(msg, size, "a failed load left a scene behind");
    mcrt_scene_free(s);
    return st;
}

static mcrt_status load_file(char *msg, size_t size)
{
    mcrt_scene *s = mcrt_scene_new();
    if (!s)
        return snprintf(msg, size, "mcrt_scene_new: NULL"), MCRT_ERR_NOMEM;
    return scene_left_empty(s, mcrt_scene_load_file(s, "scenes/mesh.mcrt"), msg, size);
}

/* A mesh taking its MTL materials (a map_Kd image texture among them), a checker, an
 * environment map: the MTL reader's, the textures' and the warnings' allocations. */
static mcrt_status load_vase(char *msg, size_t size)
{
    mcrt_scene *s = mcrt_scene_new();
    if (!s)
        return snprintf(msg, size, "mcrt_scene_new: NULL"), MCRT_ERR_NOMEM;
    return scene_left_empty(s, mcrt_scene_load_file(s, "scenes/vase.mcrt"), msg, size);
}

static mcrt_status load_string(char *msg, size_t size)
{
    mcrt_scene *s = mcrt_scene_new();
    if (!s)
        return snprintf(msg, size, "mcrt_scene_new: NULL"), MCRT_ERR_NOMEM;
    return scene_left_empty(s, mcrt_scene_load_string(s, scene_text, strlen(scene_text), "nomem"),
                            msg, size);
}

/* The scene and options of the render operations, set by main. */
static mcrt_scene *scene;
static mcrt_options render_opt;
static mcrt_render *rendered;   /* a finished render with every AOV, for the save operations */
static mcrt_render *plain;      /* and one without, for the formats that hold no layers */
static char exr_path[64], png_path[64], pfm_path[64], stats_path[64], pov_path[64], xml_path[64];
static char ref_path[64], z_path[64];

static mcrt_status render(char *msg, size_t size)
{
    mcrt_render *r = mcrt_render_new(scene, &render_opt);
    mcrt_status st;
    if (!r)
        return snprintf(msg, size, "mcrt_render_new: NULL"), MCRT_ERR_NOMEM;
    st = mcrt_render_run(r);
    snprintf(msg, size, "%s", mcrt_render_error(r));
    if (st != MCRT_OK && mcrt_render_pixels(r, NULL, NULL))
        snprintf(msg, size, "a failed run left an image");
    mcrt_render_free(r);
    return st;
}

/* Save the finished render to path; a failed save leaves no file. */
static mcrt_status save_to(mcrt_render *r, const char *path, char *msg, size_t size)
{
    mcrt_status st = mcrt_render_save(r, path);
    snprintf(msg, size, "%s", mcrt_render_error(r));
    if (st != MCRT_OK && access(path, F_OK) == 0)
        snprintf(msg, size, "a failed save left %s", path);
    remove(path);
    return st;
}

static mcrt_status save_exr(char *msg, size_t size)
{
    return save_to(rendered, exr_path, msg, size);
}
static mcrt_status save_png(char *msg, size_t size) { return save_to(plain, png_path, msg, size); }
static mcrt_status save_pfm(char *msg, size_t size) { return save_to(plain, pfm_path, msg, size); }

static mcrt_status save_stats(char *msg, size_t size)
{
    mcrt_status st = mcrt_render_save_stats(rendered, stats_path, "nomem", NULL);
    snprintf(msg, size, "%s", mcrt_render_error(rendered));
    remove(stats_path);
    return st;
}

/* Export scenes/cornell.mcrt (loaded by main into pov_scene) for POV-Ray. */
static mcrt_scene *pov_scene;
static mcrt_status export_pov(char *msg, size_t size)
{
    mcrt_status st = mcrt_scene_export_pov(pov_scene, pov_path);
    snprintf(msg, size, "%s", mcrt_scene_error(pov_scene));
    remove(pov_path);
    return st;
}

/* Export the same scene for Mitsuba: its XML and its two meshes; a failed export leaves none of
 * them. */
static mcrt_status export_mitsuba(char *msg, size_t size)
{
    mcrt_status st = mcrt_scene_export_mitsuba(pov_scene, xml_path);
    char mesh[80];
    int k, left = 0;
    snprintf(msg, size, "%s", mcrt_scene_error(pov_scene));
    for (k = 0; k < 2; k++) {
        snprintf(mesh, sizeof mesh, "%.*s-mesh%d.obj", (int)strlen(xml_path) - 4, xml_path, k);
        left |= st != MCRT_OK && access(mesh, F_OK) == 0;
        remove(mesh);
    }
    if (st != MCRT_OK && (left || access(xml_path, F_OK) == 0)) {
        snprintf(msg, size, "a failed export left a file");
        st = MCRT_ERR_IO; /* not the MCRT_ERR_NOMEM the sweep wants */
    }
    remove(xml_path);
    return st;
}

/* Compare the saved EXR with a render of another seed, with the z-test and its image; a success
 * must give the result of the first run, kept in diff_want. */
static mcrt_diff_result diff_want;
static int have_diff_want;
static mcrt_status diff(char *msg, size_t size)
{
    mcrt_diff_options o;
    mcrt_diff_result res;
    mcrt_status st;
    mcrt_diff_options_init(&o);
    o.variance = exr_path;
    o.alpha = 0.99;     /* a z-test that fails, so that the z image is written */
    o.min_agree = 1.0;
    o.z_image = z_path;
    st = mcrt_diff(exr_path, ref_path, &o, &res, sizeof res, msg, size);
    if (st == MCRT_OK && !res.z_image_written)
        snprintf(msg, size, "the z image was not written"), st = MCRT_ERR_IO;
    if (st == MCRT_OK && have_diff_want && memcmp(&res, &diff_want, sizeof res) != 0)
        snprintf(msg, size, "a different result"), st = MCRT_ERR_INVALID;
    if (st == MCRT_OK && !have_diff_want)
        diff_want = res, have_diff_want = 1;
    remove(z_path);
    return st;
}

/* Compare the PNG and the PFM image with themselves: their readers. */
static mcrt_status diff_png_pfm(char *msg, size_t size)
{
    mcrt_diff_options o;
    mcrt_diff_result res;
    mcrt_status st;
    mcrt_diff_options_init(&o);
    st = mcrt_diff(pfm_path, pfm_path, &o, &res, sizeof res, msg, size);
    if (st == MCRT_OK && mcrt_format_supported("png"))
        st = mcrt_diff(png_path, png_path, &o, &res, sizeof res, msg, size);
    return st;
}

/* Write the large grid mesh for the parallel BVH build. Its upper half has texture coordinates,
 * so that the scene's uv array is created late (filling in the lower half's) and then grows. */
static int write_grid(const char *path)
{
    FILE *f = fopen(path, "w");
    int i, j;
    if (!f)
        return 0;
    for (j = 0; j <= GRID; j++)
        for (i = 0; i <= GRID; i++)
            fprintf(f, "v %g 0 %g\nvt %g %g\n", (double)i / GRID - 0.5, (double)j / GRID - 0.5,
                    (double)i / GRID, (double)j / GRID);
    for (j = 0; j < GRID; j++)
        for (i = 0; i < GRID; i++) {
            int a = j * (GRID + 1) + i + 1, b = a + 1, c = a + GRID + 2, d = a + GRID + 1;
            if (j < GRID / 2)
                fprintf(f, "f %d %d %d %d\n", a, b, c, d);
            else
                fprintf(f, "f %d/%d %d/%d %d/%d %d/%d\n", a, a, b, b, c, c, d, d);
        }
    return fclose(f) == 0;
}

/* The scene above must keep using every kind of the library's tables, so that a new material or
 * shape is swept too: each material kind appears as "{ KIND", each shape block as "KIND {". */
static void test_scene_covers_tables(void)
{
    static const char *const sets[] = {"material", "shape"};
    size_t i;
    for (i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        const char *const *names = mcrt_names(sets[i]);
        char word[80];
        for (; names && *names; names++) {
            snprintf(word, sizeof word, i == 0 ? "{ %s" : "%s {", *names);
            T_CHECK(strstr(scene_head, word) != NULL, "the scene uses the %s %s", sets[i], *names);
        }
    }
}

int main(void)
{
    char grid[64], msg[512];
    mcrt_render *ref;
    mcrt_options o;
    int exr = mcrt_format_supported("exr");

    if (!mkdtemp(dir)) {
        perror(dir);
        return 1;
    }
    test_scene_covers_tables();
    snprintf(grid, sizeof grid, "%s/grid.obj", dir);
    T_CHECK(write_grid(grid), "write %s", grid);
    snprintf(scene_text, sizeof scene_text,
             "%smesh { file \"%s\"  scale 3  translate 0 0.02 -3  material d }\n", scene_head, grid);
    snprintf(exr_path, sizeof exr_path, "%s/image.exr", dir);
    snprintf(ref_path, sizeof ref_path, "%s/ref.exr", dir);
    snprintf(png_path, sizeof png_path, "%s/image.png", dir);
    snprintf(pfm_path, sizeof pfm_path, "%s/image.pfm", dir);
    snprintf(stats_path, sizeof stats_path, "%s/stats.json", dir);
    snprintf(pov_path, sizeof pov_path, "%s/scene.pov", dir);
    snprintf(xml_path, sizeof xml_path, "%s/scene.xml", dir);
    snprintf(z_path, sizeof z_path, "%s/z.png", dir);

    sweep("mcrt_scene_load_file scenes/mesh.mcrt", load_file, 0);
    sweep("mcrt_scene_load_string of every kind", load_string, 0);
    if (mcrt_format_supported("png") && exr)
        sweep("mcrt_scene_load_file scenes/vase.mcrt", load_vase, 1);
    else
        T_SKIP("scenes/vase.mcrt reads a PNG and an EXR: this build lacks one");

    scene = mcrt_scene_new();
    T_CHECK(scene && mcrt_scene_load_string(scene, scene_text, strlen(scene_text), "nomem")
                         == MCRT_OK,
            "load: %s", mcrt_scene_error(scene));
    /* Adaptive passes (spp 16 in passes of 8), every AOV, two threads. */
    mcrt_options_init(&render_opt);
    render_opt.spp = 16;
    render_opt.threads = 2;
    render_opt.adaptive = 1;
    render_opt.aovs = "variance,albedo,normal,depth";
    sweep("render: adaptive passes with every AOV", render, 0);
    /* Progressive passes to a target error, in a crop. */
    render_opt.adaptive = 0;
    render_opt.spp = 2;
    render_opt.target_error = 1e9;
    render_opt.crop_x0 = 2, render_opt.crop_y0 = 1, render_opt.crop_x1 = 10, render_opt.crop_y1 = 7;
    sweep("render: progressive crop", render, 0);

    mcrt_options_init(&o);
    o.threads = 2;
    plain = mcrt_render_new(scene, &o);
    o.aovs = "variance,albedo,normal,depth";
    rendered = mcrt_render_new(scene, &o);
    o.seed = 9;
    ref = mcrt_render_new(scene, &o);
    T_CHECK(plain && rendered && ref && mcrt_render_run(plain) == MCRT_OK
                && mcrt_render_run(rendered) == MCRT_OK && mcrt_render_run(ref) == MCRT_OK,
            "renders to save");
    if (exr) {
        sweep("mcrt_render_save .exr with every AOV", save_exr, 0);
        T_CHECK(mcrt_render_save(rendered, exr_path) == MCRT_OK
                    && mcrt_render_save(ref, ref_path) == MCRT_OK,
                "save: %s", mcrt_render_error(rendered));
        T_CHECK(diff(msg, sizeof msg) == MCRT_OK && have_diff_want, "diff: %s", msg);
        sweep("mcrt_diff with the z-test and its image", diff, 1);
    }
    if (mcrt_format_supported("png"))
        sweep("mcrt_render_save .png", save_png, 0);
    sweep("mcrt_render_save .pfm", save_pfm, 0);
    sweep("mcrt_render_save_stats", save_stats, 0);
    T_CHECK(mcrt_render_save(plain, pfm_path) == MCRT_OK
                && (!mcrt_format_supported("png") || mcrt_render_save(plain, png_path) == MCRT_OK),
            "save: %s", mcrt_render_error(plain));
    sweep("mcrt_diff of PFM and PNG images", diff_png_pfm, 0);
    pov_scene = mcrt_scene_new();
    T_CHECK(pov_scene && mcrt_scene_load_file(pov_scene, "scenes/cornell.mcrt") == MCRT_OK,
            "load: %s", mcrt_scene_error(pov_scene));
    sweep("mcrt_scene_export_pov scenes/cornell.mcrt", export_pov, 0);
    sweep("mcrt_scene_export_mitsuba scenes/cornell.mcrt", export_mitsuba, 0);
    mcrt_scene_free(pov_scene);

    mcrt_render_free(plain);
    mcrt_render_free(rendered);
    mcrt_render_free(ref);
    mcrt_scene_free(scene);
    remove(exr_path);
    remove(ref_path);
    remove(pfm_path);
    remove(png_path);
    remove(grid);
    rmdir(dir);
    return t_done();
}
