/* test_api.c: the public API keeps nothing it borrowed, and reads and writes its sized structs by
 * the caller's size (mcrt.h, "Versions").
 * - Options whose strings live in a caller's buffers, overwritten after mcrt_render_new: the
 *   render is the one the original options asked for, bit for bit.
 * - An "old" mcrt_options, its size ending before sampler: the later fields take their defaults
 *   even when the bytes after the size say otherwise. A "newer" one with a zero tail is accepted,
 *   with a nonzero tail refused with a message.
 * - mcrt_render_stats and mcrt_diff with a smaller size write only that many bytes.
 * - MCRT_VERSION_NUM is MCRT_VERSION as a number. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mcrt.h"
#include "t.h"

static const char scene_text[] =
    "film { width 24 height 16 spp 4 sampler stratified }\n"
    "camera { eye 0 3 6  look 0 0.5 0  fov 40 }\n"
    "material m { diffuse 0.7 }\n"
    "quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8  material m }\n"
    "sphere { center 0 0.7 0  radius 0.7  material m }\n"
    "quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 20 }\n";

#define NPIX (24 * 16)
#define GUARD 0xA5

/* A folder of this run's files, made by main. */
static char dir[] = "/tmp/mcrt-api-XXXXXX";

/* Render s with o into rgb (NPIX * 3 floats); the status of the run, the message in err. */
static mcrt_status render(const mcrt_scene *s, const mcrt_options *o, float *rgb, char *err,
                          size_t err_size)
{
    mcrt_render *r = mcrt_render_new(s, o);
    mcrt_status st = r ? mcrt_render_run(r) : MCRT_ERR_NOMEM;
    const float *px = r ? mcrt_render_pixels(r, NULL, NULL) : NULL;
    if (st == MCRT_OK && px)
        memcpy(rgb, px, NPIX * 3 * sizeof *rgb);
    snprintf(err, err_size, "%s", r ? mcrt_render_error(r) : "out of memory");
    mcrt_render_free(r);
    return st;
}

/* Whether the bytes p[from, to) all hold GUARD. */
static int untouched(const void *p, size_t from, size_t to)
{
    const unsigned char *b = p;
    for (; from < to; from++)
        if (b[from] != GUARD)
            return 0;
    return 1;
}

static void borrowed_strings(const mcrt_scene *s)
{
    char integrator[16], sampler[16], aovs[32], err[512];
    static float want[NPIX * 3], got[NPIX * 3];
    mcrt_options o;
    mcrt_render *r;
    mcrt_status st;

    mcrt_options_init(&o);
    o.seed = 3;
    o.threads = 2;
    o.integrator = "direct";
    o.sampler = "sobol";
    o.aovs = "albedo,depth";
    T_CHECK(render(s, &o, want, err, sizeof err) == MCRT_OK, "reference: %s", err);

    strcpy(integrator, "direct");
    strcpy(sampler, "sobol");
    strcpy(aovs, "albedo,depth");
    o.integrator = integrator;
    o.sampler = sampler;
    o.aovs = aovs;
    r = mcrt_render_new(s, &o);
    /* The buffers reused after mcrt_render_new, as a caller may. */
    strcpy(integrator, "bogus");
    strcpy(sampler, "bogus");
    strcpy(aovs, "bogus");
    memset(&o, 0xff, sizeof o);
    st = r ? mcrt_render_run(r) : MCRT_ERR_NOMEM;
    T_CHECK(st == MCRT_OK, "a render whose option buffers were overwritten: %s",
            r ? mcrt_render_error(r) : "out of memory");
    if (st == MCRT_OK)
        memcpy(got, mcrt_render_pixels(r, NULL, NULL), sizeof got);
    T_CHECK(st == MCRT_OK && memcmp(want, got, sizeof got) == 0,
            "it is the render the original options asked for, bit for bit");
    if (st == MCRT_OK && mcrt_format_supported("exr")) {
        char path[64];
        snprintf(path, sizeof path, "%s/aovs.exr", dir);
        /* The layers are read from the copy of aovs when saving. */
        T_CHECK(mcrt_render_save(r, path) == MCRT_OK, "save with the AOVs: %s",
                mcrt_render_error(r));
        remove(path);
    }
    mcrt_render_free(r);
}

static void old_and_new_options(const mcrt_scene *s)
{
    /* A caller's struct with room past the library's, as a newer mcrt.h would have. */
    struct {
        mcrt_options o;
        unsigned char newer[16];
    } big;
    static float want[NPIX * 3], got[NPIX * 3];
    char err[512];
    mcrt_options o;

    mcrt_options_init(&o);
    o.seed = 5;
    o.threads = 2;
    T_CHECK(render(s, &o, want, err, sizeof err) == MCRT_OK, "defaults: %s", err);

    /* Built against an mcrt.h whose struct ended before sampler: the bytes after the size are
     * not the caller's, so what they say is ignored. */
    o.size = offsetof(mcrt_options, sampler);
    o.sampler = "bogus";
    o.adaptive = 1;
    T_CHECK(render(s, &o, got, err, sizeof err) == MCRT_OK, "an old, smaller size: %s", err);
    T_CHECK(memcmp(want, got, sizeof got) == 0,
            "an old options struct renders with the defaults for the later fields");

    memset(&big, 0, sizeof big);
    mcrt_options_init(&big.o);
    big.o.size = sizeof big;
    big.o.seed = 5;
    big.o.threads = 2;
    T_CHECK(render(s, &big.o, got, err, sizeof err) == MCRT_OK && memcmp(want, got, sizeof got) == 0,
            "a newer, larger size whose unknown fields are zero is accepted: %s", err);
    big.newer[3] = 1;
    T_CHECK(render(s, &big.o, got, err, sizeof err) == MCRT_ERR_INVALID && strstr(err, "size"),
            "a newer size with an unknown field set is refused with a message: %s", err);
    o.size = 0;
    T_CHECK(render(s, &o, got, err, sizeof err) == MCRT_ERR_INVALID && err[0],
            "size 0 (not initialised) is refused with a message: %s", err);
    o.size = (size_t)-1 / 2; /* garbage: refused without reading past the struct */
    T_CHECK(render(s, &o, got, err, sizeof err) == MCRT_ERR_INVALID && err[0],
            "a garbage size is refused with a message: %s", err);
}

static void stats_by_size(const mcrt_scene *s)
{
    struct {
        mcrt_stats st;
        unsigned char guard[32];
    } g;
    const size_t part = offsetof(mcrt_stats, seconds);
    mcrt_options o;
    mcrt_render *r;

    mcrt_options_init(&o);
    o.threads = 2;
    r = mcrt_render_new(s, &o);
    T_CHECK(r && mcrt_render_run(r) == MCRT_OK, "render: %s", mcrt_render_error(r));
    memset(&g, GUARD, sizeof g);
    mcrt_render_stats(r, &g.st, part);
    T_CHECK(g.st.width == 24 && g.st.height == 16 && g.st.spp == 4 && g.st.threads == 2,
            "the fields within the size are filled (%dx%d, %d spp, %d threads)", g.st.width,
            g.st.height, g.st.spp, g.st.threads);
    T_CHECK(untouched(&g, part, sizeof g), "nothing past the size is written");
    memset(&g, GUARD, sizeof g);
    mcrt_render_stats(r, &g.st, sizeof g.st);
    T_CHECK(g.st.passes == 1 && untouched(&g, sizeof g.st, sizeof g),
            "the whole struct is filled, and nothing after it");
    mcrt_render_free(r);
}

static void diff_by_size(const mcrt_scene *s)
{
    struct {
        mcrt_diff_result res;
        unsigned char guard[32];
    } g;
    const size_t part = offsetof(mcrt_diff_result, crop);
    char path[64], err[512];
    mcrt_diff_options d;
    mcrt_options o;
    mcrt_render *r;
    mcrt_status st;

    mcrt_options_init(&o);
    r = mcrt_render_new(s, &o);
    snprintf(path, sizeof path, "%s/image.pfm", dir);
    T_CHECK(r && mcrt_render_run(r) == MCRT_OK && mcrt_render_save(r, path) == MCRT_OK,
            "render and save: %s", mcrt_render_error(r));
    mcrt_render_free(r);
    mcrt_diff_options_init(&d);
    memset(&g, GUARD, sizeof g);
    st = mcrt_diff(path, path, &d, &g.res, part, err, sizeof err);
    T_CHECK(st == MCRT_OK && g.res.width == 24 && g.res.whole.mse == 0.0, "diff: %s", err);
    T_CHECK(untouched(&g, part, sizeof g), "mcrt_diff writes nothing past the size");
    /* An old, smaller mcrt_diff_options: the crop after its size is ignored. */
    d.size = offsetof(mcrt_diff_options, crop_x0);
    d.crop_x0 = -5;
    st = mcrt_diff(path, path, &d, &g.res, sizeof g.res, err, sizeof err);
    T_CHECK(st == MCRT_OK && g.res.crop.pixels == NPIX,
            "old diff options: the later fields take their defaults: %s", err);
    d.size = 0;
    st = mcrt_diff(path, path, &d, &g.res, sizeof g.res, err, sizeof err);
    T_CHECK(st == MCRT_ERR_INVALID && err[0], "diff options of size 0 are refused: %s", err);
    remove(path);
}

static void version_number(void)
{
    int major = -1, minor = -1, patch = -1;
    T_CHECK(sscanf(MCRT_VERSION, "%d.%d.%d", &major, &minor, &patch) == 3 &&
                MCRT_VERSION_NUM == major * 10000 + minor * 100 + patch &&
                strcmp(mcrt_version(), MCRT_VERSION) == 0,
            "MCRT_VERSION_NUM %d is MCRT_VERSION %s", MCRT_VERSION_NUM, MCRT_VERSION);
}

int main(void)
{
    mcrt_scene *s = mcrt_scene_new();
    if (!mkdtemp(dir)) {
        perror(dir);
        return 1;
    }
    T_CHECK(s && mcrt_scene_load_string(s, scene_text, strlen(scene_text), NULL) == MCRT_OK,
            "load: %s", mcrt_scene_error(s));
    borrowed_strings(s);
    old_and_new_options(s);
    stats_by_size(s);
    diff_by_size(s);
    version_number();
    mcrt_scene_free(s);
    rmdir(dir);
    return t_done();
}
