/* api.c: the public API of mcrt.h: argument checks, status codes and messages on the handles.
 * Everything here is a thin layer over the modules; nothing prints and nothing exits. */
#include "mcrt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "api/denoise.h"
#include "api/sized.h"
#include "api/stats_json.h"
#include "core/alloc.h"
#include "core/atomic.h"
#include "core/clock.h"
#include "core/file.h"
#include "core/hash.h"
#include "core/names.h"
#include "export/mitsuba.h"
#include "export/pov.h"
#include "integrator/integrator.h"
#include "io/image.h"
#include "render/adaptive.h"
#include "render/render.h"
#include "render/state.h"
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
    char info[4096];
};

struct mcrt_render {
    const mcrt_scene *scene;
    /* The caller's options, with the strings pointing at the copies below, which the render owns:
     * nothing the caller lent is read after mcrt_render_new (but the progress callback's user). */
    mcrt_options opt;
    char *integrator, *sampler, *aovs, *resume;
    size_t given_size;      /* the caller's opt.size; opt.size is 0 when it was refused */
    struct film film;
    struct aov_film aov;    /* first-hit layers, when opt.aovs asks for any */
    float *rgb;
    /* What the film is a render of, when it can be saved and continued (has_state). */
    struct render_state state;
    int has_state;
    uint32_t *sums;         /* the film as state words, made by mcrt_render_sums */
    int sums_current;       /* whether sums holds the film as it is */
    float *raw;             /* the image before denoising, with opt.denoise */
    mc_atomic_int cancel;
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
    mcrt_scene *s = mc_calloc(1, sizeof *s);
    if (s && mc_scene_init(&s->s) != 0) {
        mcrt_scene_free(s);
        return NULL;
    }
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

const char *mcrt_scene_warnings(const mcrt_scene *s)
{
    return s && s->s.warnings ? s->s.warnings : "";
}

/* Read the image files the parsed scene names: the core reads none itself (src/README). */
static mcrt_status read_images(struct scene *sc, mc_diag *d)
{
    size_t i;
    for (i = 0; i < sc->image_count; i++) {
        struct image im;
        mcrt_status st = mc_image_read(sc->images[i].path, &im, d);
        if (st != MCRT_OK) {
            /* Said where the scene names the file: "FILE:LINE:COL: cannot read ..." */
            mc_diag why = *d;
            return mc_fail(d, st, "%s: %s", sc->images[i].origin, why.msg);
        }
        sc->hash = mc_hash(sc->hash, im.rgb, (size_t)im.width * (size_t)im.height * 3 * sizeof *im.rgb);
        mc_scene_set_image(sc, i, im.rgb, im.width, im.height);
    }
    return MCRT_OK;
}

/* Parse into a fresh scene and prepare it; on failure the scene is left empty but valid. */
static mcrt_status load(mcrt_scene *s, const char *text, size_t len, const char *name,
                        const char *base_dir)
{
    mcrt_status st = MCRT_OK;
    mc_scene_free(&s->s);
    s->loaded = 0;
    s->err.msg[0] = '\0';
    if (mc_scene_init(&s->s) != 0)
        st = mc_fail(&s->err, MCRT_ERR_NOMEM, "%s: out of memory", name);
    s->s.hash = mc_hash(s->s.hash, text, len);
    if (st == MCRT_OK)
        st = mc_scene_parse(&s->s, text, len, name, base_dir, &s->err);
    if (st == MCRT_OK)
        st = read_images(&s->s, &s->err);
    if (st == MCRT_OK)
        st = mc_scene_prepare(&s->s, &s->err);
    if (st != MCRT_OK) {
        /* The defaults are set even when the default material cannot be: an unloaded scene
         * needs none. */
        mc_scene_free(&s->s);
        (void)mc_scene_init(&s->s);
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
    dir = mc_malloc(strlen(path) + 2);
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

/* The checks every exporter's entry point makes, then the export. */
static mcrt_status export_scene(mcrt_scene *s, const char *path, const char *fn,
                                mcrt_status (*save)(const struct scene *, const char *, mc_diag *))
{
    if (!s)
        return MCRT_ERR_INVALID;
    if (!path)
        return mc_fail(&s->err, MCRT_ERR_INVALID, "%s: path is NULL", fn);
    if (!s->loaded)
        return mc_fail(&s->err, MCRT_ERR_INVALID, "%s: no scene loaded", fn);
    return save(&s->s, path, &s->err);
}

mcrt_status mcrt_scene_export_pov(mcrt_scene *s, const char *path)
{
    return export_scene(s, path, "mcrt_scene_export_pov", mc_pov_save);
}

mcrt_status mcrt_scene_export_mitsuba(mcrt_scene *s, const char *path)
{
    return export_scene(s, path, "mcrt_scene_export_mitsuba", mc_mitsuba_save);
}

void mcrt_options_init(mcrt_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->size = sizeof *o;
}

/* A copy of the option string *p, which *p then points at; 0 when out of memory. */
static int own_string(const char **p, char **copy)
{
    if (*p && !(*p = *copy = mc_strdup(*p)))
        return 0;
    return 1;
}

mcrt_render *mcrt_render_new(const mcrt_scene *s, const mcrt_options *o)
{
    mcrt_render *r = mc_calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->scene = s;
    mcrt_options_init(&r->opt);
    /* Options of another version of mcrt.h are read by their size (api/sized.h); a size that
     * cannot be read is refused by mcrt_render_run. */
    if (o) {
        r->given_size = o->size;
        r->opt.size = mc_sized_read(&r->opt, sizeof r->opt, o, o->size) ? sizeof r->opt : 0;
    }
    if (!own_string(&r->opt.integrator, &r->integrator) || !own_string(&r->opt.sampler, &r->sampler)
        || !own_string(&r->opt.aovs, &r->aovs) || !own_string(&r->opt.resume, &r->resume)) {
        mcrt_render_free(r);
        return NULL;
    }
    return r;
}

void mcrt_render_free(mcrt_render *r)
{
    if (!r)
        return;
    mc_film_free(&r->film);
    mc_aov_free(&r->aov);
    free(r->rgb);
    free(r->raw);
    free(r->integrator);
    free(r->sampler);
    free(r->aovs);
    free(r->resume);
    free(r->sums);
    free(r);
}

const char *mcrt_render_error(const mcrt_render *r) { return r ? r->err.msg : "no render"; }

void mcrt_render_cancel(mcrt_render *r)
{
    if (r)
        mc_atomic_store(&r->cancel, 1);
}

const char *mcrt_scene_info(mcrt_scene *s)
{
    const struct scene *sc;
    unsigned f, bit;
    struct sample_dims dims;
    size_t n = 0, bvh_bytes, i;
    int w;
    if (!s)
        return "";
    if (!s->loaded)
        return "no scene loaded\n";
    sc = &s->s;
    f = mc_scene_features(sc);
    dims = mc_scene_dims(sc, f);
    bvh_bytes = mc_bvh_bytes(&sc->bvh) + mc_bvh_bytes(&sc->motion_bvh)
                + sc->prim_count * sizeof *sc->prims + sc->normal_count * sizeof *sc->normals
                + (sc->uvs ? sc->normal_count * sizeof *sc->uvs : 0);
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
    n = strlen(s->info);
    if (sc->envmap && n < sizeof s->info)
        snprintf(s->info + n, sizeof s->info - n, "environment map: %s, %d x %d, %zu bytes\n",
                 sc->images[sc->lights[sc->env_light].image - 1].path, sc->envmap->w,
                 sc->envmap->h, mc_envmap_bytes(sc->envmap));
    for (i = 0; i < sc->texture_count; i++) {
        const struct texture *t = &sc->textures[i];
        n = strlen(s->info);
        if (n >= sizeof s->info)
            break;
        if (t->kind == TEXTURE_IMAGE)
            snprintf(s->info + n, sizeof s->info - n, "texture %s: image %s, %d x %d, %zu bytes\n",
                     t->name, sc->images[t->image - 1].path, t->w, t->h,
                     (size_t)t->w * (size_t)t->h * 3 * sizeof *t->rgb);
        else
            snprintf(s->info + n, sizeof s->info - n, "texture %s: %s, %zu bytes\n", t->name,
                     mc_texture_names[t->kind], sizeof *t);
    }
    return s->info;
}

int mc_default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

/* Whether the comma-separated list names the layer name. */
static int has_aov(const char *list, const char *name)
{
    size_t len = strlen(name);
    const char *p;
    for (p = list; p; p = strchr(p, ','), p = p ? p + 1 : NULL)
        if (strncmp(p, name, len) == 0 && (p[len] == ',' || p[len] == '\0'))
            return 1;
    return 0;
}

/* Whether the list asks for a layer that needs first-hit data (all but the variance). */
static int first_hit_aovs(const char *list)
{
    int i;
    for (i = 0; list && i < AOV_COUNT; i++)
        if (!mc_aov_from_film((enum aov_kind)i) && has_aov(list, mc_aov_names[i]))
            return 1;
    return 0;
}

/* Every name in the list must be a known layer. */
static mcrt_status check_aovs(const char *list, mc_diag *d)
{
    const char *p = list;
    char names[128];
    size_t len;
    while (p) {
        const char *comma = strchr(p, ',');
        len = comma ? (size_t)(comma - p) : strlen(p);
        if (mc_names_find(mc_aov_names, p, len) < 0)
            return mc_fail(d, MCRT_ERR_INVALID, "unknown image layer '%.*s' (use %s)", (int)len, p,
                           mc_names_join(mc_aov_names, ", ", names, sizeof names));
        p = comma ? comma + 1 : NULL;
    }
    return MCRT_OK;
}

/* Resolve the options against the scene into render settings and the integrator, or explain
 * what is wrong. */
static mcrt_status settings(const mcrt_render *r, struct render_settings *rs,
                            const struct integrator **it, mc_diag *d)
{
    const struct scene *s = &r->scene->s;
    const mcrt_options *o = &r->opt;
    enum integrator_kind method = s->integrator.method;
    if (o->size != sizeof *o)
        return mc_fail(d, MCRT_ERR_INVALID,
                       "mcrt_options.size is %zu: not set by mcrt_options_init, or options of a "
                       "newer mcrt.h that this library (%s, %zu bytes) does not know are set",
                       r->given_size, MCRT_VERSION, sizeof *o);
    if (o->spp < 0 || o->spp > MAX_SPP)
        return mc_fail(d, MCRT_ERR_INVALID, "spp must be between 1 and %d, got %d", MAX_SPP, o->spp);
    if (o->threads < 0 || o->threads > MAX_THREADS)
        return mc_fail(d, MCRT_ERR_INVALID, "threads must be between 1 and %d, got %d",
                       MAX_THREADS, o->threads);
    if (o->integrator) {
        int i = mc_names_find(mc_integrator_names, o->integrator, strlen(o->integrator));
        if (i < 0) {
            char choices[256];
            return mc_fail(d, MCRT_ERR_INVALID, "unknown integrator '%s' (use %s)", o->integrator,
                           mc_names_join(mc_integrator_names, " or ", choices, sizeof choices));
        }
        method = (enum integrator_kind)i;
    }
    *it = mc_integrator_get(method);
    rs->spp = o->spp ? o->spp : s->film.spp;
    rs->threads = o->threads ? o->threads : mc_default_threads();
    rs->seed = o->seed;
    rs->pass = 0;
    rs->integrator = s->integrator;
    rs->features = o->all_features ? FEATURE_ALL : mc_scene_features(s);
    rs->progress = o->progress;
    rs->user = o->user;
    rs->sampler = s->film.sampler;
    if (o->sampler) {
        char names[128];
        int k = mc_names_find(mc_sampler_names, o->sampler, strlen(o->sampler));
        if (k < 0)
            return mc_fail(d, MCRT_ERR_INVALID, "unknown sampler '%s' (use %s)", o->sampler,
                           mc_names_join(mc_sampler_names, " or ", names, sizeof names));
        rs->sampler = (enum sampler_kind)k;
    }
    rs->crop_x0 = rs->crop_y0 = 0;
    if (o->crop_x0 || o->crop_y0 || o->crop_x1 || o->crop_y1) {
        if (o->crop_x0 < 0 || o->crop_y0 < 0 || o->crop_x1 > s->film.width
            || o->crop_y1 > s->film.height || o->crop_x0 >= o->crop_x1 || o->crop_y0 >= o->crop_y1)
            return mc_fail(d, MCRT_ERR_INVALID,
                           "crop %d,%d,%d,%d is not a non-empty window inside the %dx%d image",
                           o->crop_x0, o->crop_y0, o->crop_x1, o->crop_y1, s->film.width,
                           s->film.height);
        rs->crop_x0 = o->crop_x0;
        rs->crop_y0 = o->crop_y0;
    }
    if (!(o->time_budget >= 0.0) || !(o->target_error >= 0.0))
        return mc_fail(d, MCRT_ERR_INVALID, "time_budget and target_error must be >= 0");
    if (o->passes < 0 || o->first_pass < 0 || o->passes > MAX_SPP / rs->spp ||
        o->first_pass > INT32_MAX - MAX_SPP)
        return mc_fail(d, MCRT_ERR_INVALID, "passes must be between 1 and %d, first_pass >= 0",
                       MAX_SPP / rs->spp);
    if ((o->passes || o->first_pass || o->resume || o->save_state) && !(*it)->radiance)
        return mc_fail(d, MCRT_ERR_INVALID,
                       "the %s integrator keeps no render state (passes, resume and merge need a "
                       "per-ray integrator)",
                       mc_integrator_names[method]);
    if ((o->passes || o->first_pass || o->resume) && o->adaptive)
        return mc_fail(d, MCRT_ERR_INVALID,
                       "passes, first_pass and resume do not work with adaptive sampling");
    /* The state holds the film, not the first-hit layers, which would then miss the passes
     * done before: the denoiser's features among them. */
    if (o->resume && (first_hit_aovs(o->aovs) || o->denoise))
        return mc_fail(d, MCRT_ERR_INVALID,
                       "resume keeps only the film: no albedo, normal or depth layers%s",
                       o->denoise ? ", which the denoiser needs (resume without it, or "
                                    "render the passes in one run)" : "");
    /* The denoiser needs two independent half images. sppm's are not: every pass's radii
     * shrink with the photons of all passes before, both halves', and its error is mostly bias,
     * the same in both halves, which their difference cannot see; it writes a mean and its
     * error estimate as synthetic halves (v -+ sqrt(mse)) instead. */
    if (o->denoise && !(*it)->radiance)
        return mc_fail(d, MCRT_ERR_INVALID,
                       "the %s integrator has no independent half images for the denoiser "
                       "(--denoise needs a per-ray integrator)",
                       mc_integrator_names[method]);
    return check_aovs(o->aovs, d);
}

double mcrt_seconds_to_relmse(const mcrt_stats *st, double relmse)
{
    if (!st || !(st->est_relmse > 0.0) || !(relmse > 0.0) || !(st->relmse_slope < 0.0))
        return NAN;
    return st->seconds * pow(relmse / st->est_relmse, 1.0 / st->relmse_slope);
}

/* The aov.h layer of each of the denoiser's first-surface layers (api/denoise.h): all but the last,
 * DENOISE_VARIANCE, which the film gives (mc_film_half_variance). */
static const enum aov_kind denoise_aov[DENOISE_VARIANCE] = {AOV_ALBEDO, AOV_NORMAL, AOV_DEPTH,
                                                            AOV_EMISSION};
#define DENOISE_IMAGES (3 + 2 * DENOISE_LAYERS)

/* The denoiser's inputs from r's film and first-surface layers: the halves, each layer per half
 * and the emission's variance, into buf (DENOISE_IMAGES images of the film's size). Returns the
 * emission's variance. */
static const float *denoise_inputs(const mcrt_render *r, float *buf, const float *halves[2],
                                   const float *layer[DENOISE_LAYERS][2])
{
    size_t n3 = (size_t)r->film.width * (size_t)r->film.height * 3;
    int h, l;
    for (h = 0; h < 2; h++) {
        halves[h] = buf + (size_t)h * n3;
        mc_film_resolve_half(&r->film, h, buf + (size_t)h * n3);
        for (l = 0; l < DENOISE_LAYERS; l++) {
            float *dst = buf + (size_t)(2 + 2 * l + h) * n3;
            if (l == DENOISE_VARIANCE)
                mc_film_half_variance(&r->film, h, dst);
            else
                mc_aov_resolve(&r->aov, denoise_aov[l], h, dst);
            layer[l][h] = dst;
        }
    }
    mc_aov_emission_variance(&r->aov, buf + (size_t)(DENOISE_IMAGES - 1) * n3);
    return buf + (size_t)(DENOISE_IMAGES - 1) * n3;
}

/* r->rgb denoised, the raw image kept in r->raw; *est the denoised image's estimated relMSE and
 * *sd that estimate's standard deviation. */
static mcrt_status denoise_render(mcrt_render *r, int threads, double *est, double *sd)
{
    size_t n3 = (size_t)r->film.width * (size_t)r->film.height * 3;
    float *buf = mc_malloc(n3 * DENOISE_IMAGES * sizeof *buf);
    const float *halves[2], *layer[DENOISE_LAYERS][2], *evar;
    mcrt_status st;
    if (!buf || !(r->raw = mc_malloc(n3 * sizeof *r->raw))) {
        free(buf);
        return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for the denoiser");
    }
    memcpy(r->raw, r->rgb, n3 * sizeof *r->raw);
    evar = denoise_inputs(r, buf, halves, layer);
    st = mc_denoise_layers(halves, layer, evar, r->film.width, r->film.height, threads, r->rgb,
                           est, sd, NULL, &r->err);
    free(buf);
    return st;
}

/* What r's film will be a render of (render/state.h), for its state. */
static void identify(mcrt_render *r, const struct render_settings *rs, int w, int h)
{
    const struct scene *s = &r->scene->s;
    struct render_state *id = &r->state;
    memset(id, 0, sizeof *id);
    id->scene = r->scene->s.hash;
    id->width = s->film.width;
    id->height = s->film.height;
    id->crop[0] = rs->crop_x0;
    id->crop[1] = rs->crop_y0;
    id->crop[2] = rs->crop_x0 + w;
    id->crop[3] = rs->crop_y0 + h;
    id->spp = rs->spp;
    snprintf(id->integrator, sizeof id->integrator, "%s",
             r->opt.integrator ? r->opt.integrator : mc_integrator_names[s->integrator.method]);
    snprintf(id->sampler, sizeof id->sampler, "%s", mc_sampler_names[rs->sampler]);
    id->all_features = r->opt.all_features != 0;
    id->adaptive = rs->adaptive;
    id->pooled = r->film.pooled;
    id->seed = rs->seed;
    id->first_pass = rs->first_pass;
}

/* Load the state at r->opt.resume into r's film, when it is a render of what r renders. */
static mcrt_status resume(mcrt_render *r, struct render_settings *rs)
{
    struct image_words words = {MC_STATE_NAME, MC_STATE_WORDS, NULL, NULL};
    struct render_state got;
    const char *path = r->opt.resume, *why = NULL;
    char *text;
    int w, h;
    mcrt_status st = mc_image_read_words(path, &words, &text, &w, &h, &r->err);
    if (st != MCRT_OK) /* a state that cannot be read is bad input, as a bad option is */
        return st == MCRT_ERR_IO ? MCRT_ERR_INVALID : st;
    if (mc_state_parse(text, &got, &why) == 0 && mc_state_same_render(&r->state, &got, &why)) {
        if (got.merged)
            why = "a merge of several renders, which no render continues";
        else if (got.seed != r->state.seed)
            why = "another --seed";
        else if (memcmp(got.crop, r->state.crop, sizeof got.crop) != 0)
            why = "another --crop";
        else if (w != r->film.width || h != r->film.height)
            why = "an image whose size is not its state's";
        else if (rs->passes && rs->passes <= got.passes)
            why = "more passes than --passes asks for in all";
    }
    free(text);
    if (why) {
        free(words.data);
        return mc_fail(&r->err, MCRT_ERR_INVALID, "%s: cannot resume: %s", path, why);
    }
    mc_state_unpack(&r->film, words.data);
    free(words.data);
    rs->first_pass = r->state.first_pass = got.first_pass;
    rs->done_passes = got.passes;
    return MCRT_OK;
}

mcrt_status mcrt_render_run(mcrt_render *r)
{
    struct render_settings rs;
    struct render_result res;
    const struct integrator *it = NULL;
    const struct scene *s;
    void *state = NULL;
    mcrt_status st;
    uint64_t lo, hi;
    int i;
    size_t n;
    int w, h;
    if (!r)
        return MCRT_ERR_INVALID;
    r->err.msg[0] = '\0';
    if (!r->scene || !r->scene->loaded)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "no scene loaded");
    s = &r->scene->s;
    st = settings(r, &rs, &it, &r->err);
    if (st != MCRT_OK)
        return st;
    mc_film_free(&r->film);
    free(r->rgb);
    free(r->raw);
    free(r->sums);
    r->rgb = r->raw = NULL;
    r->sums = NULL;
    r->sums_current = 0;
    w = r->opt.crop_x1 ? r->opt.crop_x1 - r->opt.crop_x0 : s->film.width;
    h = r->opt.crop_y1 ? r->opt.crop_y1 - r->opt.crop_y0 : s->film.height;
    n = (size_t)w * (size_t)h;
    mc_aov_free(&r->aov);
    if (mc_film_init(&r->film, w, h) != 0 || !(r->rgb = mc_malloc(n * 3 * sizeof *r->rgb))
        || ((first_hit_aovs(r->opt.aovs) || r->opt.denoise) && mc_aov_init(&r->aov, w, h) != 0))
        return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for a %dx%d image", w, h);
    /* The random sampler's samples are independent: its pooled sample variance is unbiased and
     * measured more accurate than the halves' (film.h). */
    r->film.pooled = rs.sampler == SAMPLER_RANDOM;
    rs.aov = r->aov.pixels ? &r->aov : NULL;
    rs.pixel_spp = NULL;
    mc_atomic_store(&r->cancel, 0);
    rs.cancel = &r->cancel;
    rs.time_budget = r->opt.time_budget;
    rs.target_error = r->opt.target_error;
    rs.max_passes = MAX_SPP / rs.spp;
    rs.adaptive = r->opt.adaptive != 0;
    rs.passes = r->opt.passes;
    rs.first_pass = r->opt.first_pass;
    rs.done_passes = 0;
    identify(r, &rs, w, h);
    r->has_state = 0;
    if (r->opt.resume && (st = resume(r, &rs)) != MCRT_OK)
        return st;
    if (it->prepare && (st = it->prepare(it, s, &rs, &state, &r->err)) != MCRT_OK)
        return st;
    res.est_relmse_bias2 = res.est_relmse_variance = NAN;
    st = it->render(it, state, s, &rs, &r->film, &res, &r->err);
    if (it->release)
        it->release(state);
    r->state.passes = res.passes;
    r->has_state = it->radiance && res.passes > 0;
    mc_film_resolve(&r->film, r->rgb);
    r->stats.width = w;
    r->stats.height = h;
    r->stats.passes = res.passes;
    /* The mean samples per pixel (rounded), and the extremes, which adaptive passes spread. */
    r->stats.spp = res.passes > 0 ? (int)((res.samples + n / 2) / n) : rs.spp;
    r->stats.adaptive = rs.adaptive;
    mc_adaptive_count_range(&r->film, &lo, &hi);
    r->stats.spp_min = res.passes > 0 ? (int)lo : rs.spp;
    r->stats.spp_max = res.passes > 0 ? (int)hi : rs.spp;
    r->stats.threads = rs.threads;
    r->stats.seconds = res.seconds;
    r->stats.rays = res.rays;
    r->stats.nan_count = res.nan_count;
    r->stats.est_relmse = r->stats.est_relmse_raw = mc_film_est_relmse(&r->film);
    r->stats.denoise_seconds = 0.0;
    r->stats.est_relmse_sd = NAN;
    if (r->opt.denoise && res.passes > 0 && st == MCRT_OK) {
        double t0 = mc_seconds();
        if ((st = denoise_render(r, rs.threads, &r->stats.est_relmse, &r->stats.est_relmse_sd))
            != MCRT_OK)
            return st;
        r->stats.denoise_seconds = mc_seconds() - t0;
        r->stats.seconds += r->stats.denoise_seconds;
    }
    r->stats.efficiency = 1.0 / (r->stats.est_relmse * res.seconds);
    r->stats.est_relmse_bias2 = res.est_relmse_bias2;
    r->stats.est_relmse_variance = res.est_relmse_variance;
    r->stats.relmse_slope = res.relmse_slope;
    for (i = 0; i < 3; i++)
        r->stats.seconds_to_relmse[i] = mcrt_seconds_to_relmse(&r->stats, pow(10.0, -2.0 - i));
    if (st == MCRT_ERR_CANCELLED)
        mc_fail(&r->err, st, "render cancelled after %d complete pass%s", res.passes,
                res.passes == 1 ? "" : "es");
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

/* The image and the layers named in opt.aovs, in the order of mc_aov_names; the film's layers are
 * computed here, as only saving needs them. The halves are two layers, A and B. */
static mcrt_status save_layers(mcrt_render *r, const char *path, const struct image_words *words)
{
    struct image_layer layers[2 + AOV_COUNT + 1 + DENOISE_IMAGES];
    char names[2 * DENOISE_LAYERS][32];
    size_t npix = (size_t)r->film.width * (size_t)r->film.height;
    float *buf = mc_malloc(npix * 3 * (AOV_COUNT + 1 + DENOISE_IMAGES) * sizeof *buf), *rgb = buf;
    int i, n = 1;
    mcrt_status st;
    if (!buf)
        return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for the image layers");
    layers[0].name = NULL;
    layers[0].rgb = r->rgb;
    for (i = 0; i < AOV_COUNT; i++) {
        if (!has_aov(r->opt.aovs, mc_aov_names[i]))
            continue;
        if (i == AOV_HALVES) {
            mc_film_resolve_half(&r->film, 0, rgb);
            layers[n].name = "A";
            layers[n++].rgb = rgb;
            rgb += npix * 3;
            mc_film_resolve_half(&r->film, 1, rgb);
            layers[n].name = "B";
        } else if (i == AOV_VARIANCE) {
            mc_film_variance(&r->film, rgb);
            layers[n].name = mc_aov_names[i];
        } else {
            mc_aov_resolve(&r->aov, (enum aov_kind)i, -1, rgb);
            layers[n].name = mc_aov_names[i];
        }
        layers[n++].rgb = rgb;
        rgb += npix * 3;
    }
    if (r->raw) { /* denoised: the raw image and the denoiser's inputs, to denoise again */
        const float *halves[2], *layer[DENOISE_LAYERS][2];
        int h, l;
        const float *evar = denoise_inputs(r, rgb, halves, layer);
        layers[n].name = "raw";
        layers[n++].rgb = r->raw;
        for (h = 0; h < 2 && !has_aov(r->opt.aovs, "halves"); h++) {
            layers[n].name = h ? "B" : "A";
            layers[n++].rgb = halves[h];
        }
        for (l = 0; l < DENOISE_LAYERS; l++)
            for (h = 0; h < 2; h++) {
                snprintf(names[2 * l + h], sizeof names[0], "%s.%c", mc_denoise_layer_names[l],
                         h ? 'B' : 'A');
                layers[n].name = names[2 * l + h];
                layers[n++].rgb = layer[l][h];
            }
        layers[n].name = MC_DENOISE_EMISSION_VAR;
        layers[n++].rgb = evar;
    }
    st = mc_image_write_words(path, layers, n, words, r->film.width, r->film.height, &r->err);
    free(buf);
    return st;
}

/* r->sums: the film as state words; -1 when out of memory. */
static int pack_sums(mcrt_render *r)
{
    size_t n = (size_t)r->film.width * (size_t)r->film.height * MC_STATE_WORDS;
    if (r->sums_current)
        return 0;
    if (!r->sums && !(r->sums = mc_malloc(n * sizeof *r->sums)))
        return -1;
    mc_state_pack(&r->film, r->sums);
    r->sums_current = 1;
    return 0;
}

mcrt_status mcrt_render_save(mcrt_render *r, const char *path)
{
    if (!r)
        return MCRT_ERR_INVALID;
    if (!path)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "mcrt_render_save: path is NULL");
    if (!r->rgb)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "nothing rendered yet");
    if (r->opt.save_state && !mc_image_layered(path))
        return mc_fail(&r->err, MCRT_ERR_INVALID, "cannot write '%s': a render state needs an EXR",
                       path);
    /* The state goes with every EXR of a limited render, which a user may want to go on with. */
    if (r->has_state && mc_image_layered(path) &&
        (r->opt.save_state || r->opt.time_budget > 0.0 || r->opt.target_error > 0.0)) {
        char text[1024];
        struct image_words words = {MC_STATE_NAME, MC_STATE_WORDS, text, NULL};
        if (pack_sums(r) != 0)
            return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for the render state");
        words.data = r->sums;
        mc_state_format(&r->state, text, sizeof text);
        return save_layers(r, path, &words);
    }
    /* A denoised render keeps its raw image and inputs in an EXR; other formats get the image. */
    if (r->opt.aovs || (r->raw && mc_image_layered(path)))
        return save_layers(r, path, NULL);
    return mc_image_write(path, r->rgb, r->film.width, r->film.height, &r->err);
}

const void *mcrt_render_sums(const mcrt_render *r, size_t *bytes)
{
    mcrt_render *w = (mcrt_render *)r; /* the words are a cache of the film, made on demand */
    if (bytes)
        *bytes = 0;
    if (!r || !r->has_state || pack_sums(w) != 0)
        return NULL;
    if (bytes)
        *bytes = (size_t)r->film.width * (size_t)r->film.height * MC_STATE_WORDS * 4;
    return r->sums;
}

mcrt_status mcrt_render_add_sums(mcrt_render *r, const void *sums, size_t bytes, int first_pass,
                                 int passes)
{
    struct film more;
    size_t n;
    uint64_t lo, hi;
    int i;
    if (!r)
        return MCRT_ERR_INVALID;
    n = (size_t)r->film.width * (size_t)r->film.height;
    if (!r->has_state || !sums || bytes != n * MC_STATE_WORDS * 4 || passes < 1 || first_pass < 0)
        return mc_fail(&r->err, MCRT_ERR_INVALID,
                       "mcrt_render_add_sums: %s", !r->has_state ? "no render state to add to"
                                                   : "sums of another size, or no passes");
    if (mc_film_init(&more, r->film.width, r->film.height) != 0)
        return mc_fail(&r->err, MCRT_ERR_NOMEM, "out of memory for a %dx%d film", r->film.width,
                       r->film.height);
    mc_state_unpack(&more, sums);
    mc_film_merge(&r->film, &more);
    mc_film_free(&more);
    r->sums_current = 0;
    /* Passes right after r's continue its sequence; any others make a merge. */
    if (first_pass != r->state.first_pass + r->state.passes)
        r->state.merged = 1;
    r->state.passes += passes;
    mc_film_resolve(&r->film, r->rgb);
    r->stats.passes = r->state.passes;
    mc_adaptive_count_range(&r->film, &lo, &hi);
    r->stats.spp = (int)(lo + hi) / 2;
    r->stats.spp_min = (int)lo;
    r->stats.spp_max = (int)hi;
    r->stats.est_relmse = mc_film_est_relmse(&r->film);
    r->stats.efficiency = 1.0 / (r->stats.est_relmse * r->stats.seconds);
    for (i = 0; i < 3; i++)
        r->stats.seconds_to_relmse[i] = mcrt_seconds_to_relmse(&r->stats, pow(10.0, -2.0 - i));
    return MCRT_OK;
}

mcrt_status mcrt_render_save_stats(mcrt_render *r, const char *path, const char *scene,
                                   const char *image)
{
    struct mc_output out;
    mcrt_status st;
    if (!r)
        return MCRT_ERR_INVALID;
    if (!path)
        return mc_fail(&r->err, MCRT_ERR_INVALID, "mcrt_render_save_stats: path is NULL");
    if ((st = mc_output_open(&out, path, &r->err)) != MCRT_OK)
        return st;
    mc_stats_json(out.f, &r->stats, r->opt.seed, scene, image);
    return mc_output_close(&out, MCRT_OK, &r->err);
}

void mcrt_render_stats(const mcrt_render *r, mcrt_stats *out, size_t out_size)
{
    mcrt_stats none;
    if (!out)
        return;
    memset(&none, 0, sizeof none);
    mc_sized_write(out, out_size, r ? &r->stats : &none, sizeof none);
}

int mcrt_format_supported(const char *suffix) { return suffix && mc_image_supported(suffix); }

/* The scene language's shape blocks: the shapes of MC_SHAPES, and meshes of triangles. */
#define X(kind, name) #name,
static const char *const shape_blocks[] = {MC_SHAPES(X) "mesh", NULL};
#undef X

const char *const *mcrt_names(const char *set)
{
    static const struct {
        const char *set;
        const char *const *names;
    } sets[] = {{"integrator", mc_integrator_names}, {"sampler", mc_sampler_names},
                {"aov", mc_aov_names},               {"filter", mc_filter_names},
                {"shape", shape_blocks},             {"light", mc_light_names},
                {"material", mc_material_names},     {"texture", mc_texture_names}};
    size_t i;
    for (i = 0; set && i < sizeof sets / sizeof sets[0]; i++)
        if (strcmp(set, sets[i].set) == 0)
            return sets[i].names;
    return NULL;
}

const char *mcrt_describe(const char *set, const char *name)
{
    int i;
    if (!set || !name || strcmp(set, "integrator") != 0)
        return NULL;
    i = mc_names_find(mc_integrator_names, name, strlen(name));
    return i < 0 ? NULL : mc_integrator_get((enum integrator_kind)i)->description;
}
