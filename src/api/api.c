/* api.c: the public API of mcrt.h: argument checks, status codes and messages on the handles.
 * Everything here is a thin layer over the modules; nothing prints and nothing exits. */
#include "mcrt.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/file.h"
#include "geom/bvh_node.h"
#include "integrator/integrator.h"
#include "io/image.h"
#include "render/render.h"
#include "scene/features.h"
#include "scene/scene.h"

/* Largest scene file read: text beyond this is surely not a hand-written scene. */
#define MAX_SCENE_BYTES ((size_t)256 << 20)
#define MAX_SPP (1 << 24)
#define MAX_THREADS 1024

struct mcrt_scene {
    struct scene s;
    mc_diag err;
    int loaded;
    char info[1024];
};

struct mcrt_render {
    const mcrt_scene *scene;
    mcrt_options opt;
    struct film film;
    float *rgb;
    int cancel;
    mcrt_stats stats;
    mc_diag err;
};

const char *mcrt_version(void) { return MCRT_VERSION; }

const char *mcrt_status_string(mcrt_status status)
{
    switch (status) {
    case MCRT_OK: return "ok";
    case MCRT_ERR_NOMEM: return "out of memory";
    case MCRT_ERR_IO: return "input/output error";
    case MCRT_ERR_PARSE: return "malformed input";
    case MCRT_ERR_INVALID: return "invalid argument";
    case MCRT_ERR_UNSUPPORTED: return "unsupported";
    case MCRT_ERR_CANCELLED: return "cancelled";
    }
    return "unknown status";
}

mcrt_scene *mcrt_scene_new(void)
{
    mcrt_scene *s = calloc(1, sizeof *s);
    if (s)
        mc_scene_init(&s->s);
    return s;
}

void mcrt_scene_free(mcrt_scene *s)
{
    if (!s)
        return;
    mc_scene_free(&s->s);
    free(s);
}

const char *mcrt_scene_error(const mcrt_scene *s) { return s ? s->err.msg : "no scene"; }

/* Parse into a fresh scene and prepare it; on failure the scene is left empty but valid. */
static mcrt_status load(mcrt_scene *s, const char *text, size_t len, const char *name,
                        const char *base_dir)
{
    mcrt_status st;
    mc_scene_free(&s->s);
    mc_scene_init(&s->s);
    s->loaded = 0;
    s->err.msg[0] = '\0';
    st = mc_scene_parse(&s->s, text, len, name, base_dir, &s->err);
    if (st == MCRT_OK)
        st = mc_scene_prepare(&s->s, &s->err);
    if (st != MCRT_OK) {
        mc_scene_free(&s->s);
        mc_scene_init(&s->s);
        return st;
    }
    s->loaded = 1;
    return MCRT_OK;
}

mcrt_status mcrt_scene_load_file(mcrt_scene *s, const char *path)
{
    char *text, *dir, *slash;
    size_t len;
    mcrt_status st;
    if (!s)
        return MCRT_ERR_INVALID;
    if (!path)
        return mc_fail(&s->err, MCRT_ERR_INVALID, "mcrt_scene_load_file: path is NULL");
    st = mc_read_file(path, MAX_SCENE_BYTES, NULL, &text, &len, &s->err);
    if (st != MCRT_OK)
        return st;
    dir = malloc(strlen(path) + 2);
    if (!dir) {
        free(text);
        return mc_fail(&s->err, MCRT_ERR_NOMEM, "out of memory");
    }
    strcpy(dir, path);
    slash = strrchr(dir, '/');
    if (slash)
        slash[1] = '\0';
    else
        strcpy(dir, ".");
    st = load(s, text, len, path, dir);
    free(dir);
    free(text);
    return st;
}

mcrt_status mcrt_scene_load_string(mcrt_scene *s, const char *text, size_t len, const char *name)
{
    if (!s)
        return MCRT_ERR_INVALID;
    if (!text && len > 0)
        return mc_fail(&s->err, MCRT_ERR_INVALID, "mcrt_scene_load_string: text is NULL");
    return load(s, text ? text : "", len, name ? name : "<string>", NULL);
}

void mcrt_scene_film(const mcrt_scene *s, int *width, int *height, int *spp)
{
    if (width)
        *width = s ? s->s.film.width : 0;
    if (height)
        *height = s ? s->s.film.height : 0;
    if (spp)
        *spp = s ? s->s.film.spp : 0;
}

void mcrt_options_init(mcrt_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->size = sizeof *o;
}

mcrt_render *mcrt_render_new(const mcrt_scene *s, const mcrt_options *o)
{
    mcrt_render *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->scene = s;
    if (o && o->size == sizeof *o)
        r->opt = *o;
    else
        mcrt_options_init(&r->opt);
    /* A caller built against another version of mcrt_options is refused at run time. */
    if (o && o->size != sizeof *o)
        r->opt.size = 0;
    return r;
}

void mcrt_render_free(mcrt_render *r)
{
    if (!r)
        return;
    mc_film_free(&r->film);
    free(r->rgb);
    free(r);
}

const char *mcrt_render_error(const mcrt_render *r) { return r ? r->err.msg : "no render"; }

void mcrt_render_cancel(mcrt_render *r)
{
    if (r)
        __atomic_store_n(&r->cancel, 1, __ATOMIC_RELAXED);
}

const char *mcrt_scene_info(mcrt_scene *s)
{
    const struct scene *sc;
    unsigned f, bit;
    struct sample_dims dims;
    size_t n = 0, bvh_bytes;
    int w;
    if (!s)
        return "";
    if (!s->loaded)
        return "no scene loaded\n";
    sc = &s->s;
    f = mc_scene_features(sc);
    dims = mc_feature_dims(f, &sc->integrator);
    bvh_bytes = (sc->bvh.node_count + sc->motion_bvh.node_count) * sizeof(struct bvh_node)
                + sc->prim_count * sizeof *sc->prims + sc->normal_count * sizeof *sc->normals;
    w = snprintf(s->info, sizeof s->info, "features:");
    n = w > 0 ? (size_t)w : 0;
    for (bit = 1; bit <= FEATURE_ALL && n < sizeof s->info; bit <<= 1)
        if (f & bit) {
            w = snprintf(s->info + n, sizeof s->info - n, " %s", mc_feature_name(bit));
            n += w > 0 ? (size_t)w : 0;
        }
    if (n < sizeof s->info)
        snprintf(s->info + n, sizeof s->info - n,
                 "\nprimitives: %zu (%zu moving), lights: %zu\n"
                 "sample dimensions: %d per camera ray, %d per bounce, %d more per bounce from "
                 "depth %d (roulette)\n"
                 "bvh bytes: %zu (%.1f per primitive)\n"
                 "film bytes: %zu (%d x %d)\n",
                 sc->prim_count, sc->prim_count - sc->static_count, sc->light_count, dims.camera,
                 dims.per_bounce, dims.roulette, sc->integrator.rr_depth, bvh_bytes,
                 sc->prim_count ? (double)bvh_bytes / (double)sc->prim_count : 0.0,
                 (size_t)sc->film.width * (size_t)sc->film.height * sizeof(struct film_pixel),
                 sc->film.width, sc->film.height);
    return s->info;
}

static int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

/* Resolve the options against the scene into render settings, or explain what is wrong. */
static mcrt_status settings(const mcrt_render *r, struct render_settings *rs, mc_diag *d)
{
    const struct scene *s = &r->scene->s;
    const mcrt_options *o = &r->opt;
    enum integrator_kind method = s->integrator.method;
    if (o->size != sizeof *o)
        return mc_fail(d, MCRT_ERR_INVALID, "mcrt_options not initialised by mcrt_options_init");
    if (o->spp < 0 || o->spp > MAX_SPP)
        return mc_fail(d, MCRT_ERR_INVALID, "spp must be between 1 and %d, got %d", MAX_SPP, o->spp);
    if (o->threads < 0 || o->threads > MAX_THREADS)
        return mc_fail(d, MCRT_ERR_INVALID, "threads must be between 1 and %d, got %d",
                       MAX_THREADS, o->threads);
    if (o->integrator) {
        if (strcmp(o->integrator, "path") == 0)
            method = INTEGRATOR_PATH;
        else if (strcmp(o->integrator, "direct") == 0)
            method = INTEGRATOR_DIRECT;
        else
            return mc_fail(d, MCRT_ERR_INVALID, "unknown integrator '%s' (use path or direct)",
                           o->integrator);
    }
    rs->spp = o->spp ? o->spp : s->film.spp;
    rs->threads = o->threads ? o->threads : default_threads();
    rs->seed = o->seed;
    rs->integrator = mc_integrator_config(&s->integrator, method);
    rs->features = o->all_features ? FEATURE_ALL : mc_scene_features(s);
    rs->progress = o->progress;
    rs->user = o->user;
    return MCRT_OK;
}

mcrt_status mcrt_render_run(mcrt_render *r)
{
    struct render_settings rs;
    struct render_result res;
    const struct scene *s;
    mcrt_status st;
    size_t n;
    if (!r)
        return MCRT_ERR_INVALID;
    r->err.msg[0] = '\0';
    if (!r->scene || !r->scene->loaded)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "no scene loaded");
    s = &r->scene->s;
    st = settings(r, &rs, &r->err);
    if (st != MCRT_OK)
        return st;
    mc_film_free(&r->film);
    free(r->rgb);
    r->rgb = NULL;
    n = (size_t)s->film.width * (size_t)s->film.height;
    if (mc_film_init(&r->film, s->film.width, s->film.height) != 0
        || !(r->rgb = malloc(n * 3 * sizeof *r->rgb)))
        return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for a %dx%d image", s->film.width,
                       s->film.height);
    __atomic_store_n(&r->cancel, 0, __ATOMIC_RELAXED);
    rs.cancel = &r->cancel;
    st = mc_render(s, &rs, &r->film, &res, &r->err);
    mc_film_resolve(&r->film, r->rgb);
    r->stats.width = s->film.width;
    r->stats.height = s->film.height;
    r->stats.spp = rs.spp;
    r->stats.threads = rs.threads;
    r->stats.seconds = res.seconds;
    r->stats.rays = res.rays;
    r->stats.nan_count = res.nan_count;
    if (st == MCRT_ERR_CANCELLED)
        mc_fail(&r->err, st, "render cancelled");
    return st;
}

const float *mcrt_render_pixels(const mcrt_render *r, int *width, int *height)
{
    if (width)
        *width = r && r->rgb ? r->film.width : 0;
    if (height)
        *height = r && r->rgb ? r->film.height : 0;
    return r ? r->rgb : NULL;
}

mcrt_status mcrt_render_save(mcrt_render *r, const char *path)
{
    if (!r)
        return MCRT_ERR_INVALID;
    if (!path)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "mcrt_render_save: path is NULL");
    if (!r->rgb)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "nothing rendered yet");
    return mc_image_write(path, r->rgb, r->film.width, r->film.height, &r->err);
}

void mcrt_render_stats(const mcrt_render *r, mcrt_stats *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (r)
        *out = r->stats;
}

int mcrt_format_supported(const char *suffix) { return suffix && mc_image_supported(suffix); }
