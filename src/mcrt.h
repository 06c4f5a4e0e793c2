/* mcrt.h: the public C API of mcrt, a Monte Carlo path tracer.
 *
 * The only header a program needs. All types are opaque handles; every call that can fail returns an
 * mcrt_status and leaves a one-line message on the handle (mcrt_scene_error, mcrt_render_error).
 * The library never prints and never exits.
 *
 * Life cycle:
 *     mcrt_scene *s = mcrt_scene_new();
 *     if (mcrt_scene_load_file(s, "box.mcrt") != MCRT_OK) puts(mcrt_scene_error(s));
 *     mcrt_options o; mcrt_options_init(&o); o.spp = 64;
 *     mcrt_render *r = mcrt_render_new(s, &o);      (s must outlive r)
 *     mcrt_render_run(r);
 *     const float *rgb = mcrt_render_pixels(r, &w, &h);
 *     mcrt_render_free(r); mcrt_scene_free(s);
 *
 * Ownership: pointers returned by mcrt_* are borrowed from the handle they came from and stay
 * valid until the next call that changes that handle (a load, a run) or until it is freed. *_free(NULL) is a no-op. Handles may be used from any thread, one call at a time,
 * except mcrt_render_cancel, which may be called from any thread during mcrt_render_run.
 */
#ifndef MCRT_H
#define MCRT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MCRT_VERSION "0.1.0"

typedef enum mcrt_status {
    MCRT_OK = 0,
    MCRT_ERR_NOMEM,       /* out of memory */
    MCRT_ERR_IO,          /* a file could not be read or written */
    MCRT_ERR_PARSE,       /* malformed scene or OBJ: message is "file:line:col: what" */
    MCRT_ERR_INVALID,     /* an argument is out of range or a handle is in the wrong state */
    MCRT_ERR_UNSUPPORTED, /* e.g. an image format this build was compiled without */
    MCRT_ERR_CANCELLED    /* mcrt_render_cancel or the progress callback stopped the render */
} mcrt_status;

/* Library version, e.g. "0.1.0". Static string. */
const char *mcrt_version(void);
/* Short English text for a status code. Static string. */
const char *mcrt_status_string(mcrt_status status);

/* ---- Scenes ---- */

typedef struct mcrt_scene mcrt_scene;

/* A new empty scene, or NULL when out of memory. */
mcrt_scene *mcrt_scene_new(void);
/* Parse a scene file into s (replacing what s held). OBJ paths resolve relative to the file. */
mcrt_status mcrt_scene_load_file(mcrt_scene *s, const char *path);
/* Parse scene text of len bytes; name is used in messages (NULL: "<string>") and OBJ paths resolve
 * relative to the current directory. The text need not be NUL-terminated. */
mcrt_status mcrt_scene_load_string(mcrt_scene *s, const char *text, size_t len, const char *name);
/* The last error on s, "" if none. Owned by s. */
const char *mcrt_scene_error(const mcrt_scene *s);
/* The film size and spp the scene asks for (NULL pointers are skipped). */
void mcrt_scene_film(const mcrt_scene *s, int *width, int *height, int *spp);
/* What a loaded scene uses and what it costs, as `mcrt info` prints it: lines "key: value" with
 * the features found, the sample dimensions one path draws, and the memory of the BVH and the
 * film. Owned by s. */
const char *mcrt_scene_info(mcrt_scene *s);
void mcrt_scene_free(mcrt_scene *s);

/* ---- Rendering ---- */

typedef struct mcrt_render mcrt_render;

typedef struct mcrt_options {
    size_t size;            /* sizeof(mcrt_options), set by mcrt_options_init (ABI check) */
    int spp;                /* samples per pixel; 0 = the scene's */
    int threads;            /* worker threads; 0 = all cores */
    uint64_t seed;          /* the image is a function of (scene, options, seed) only */
    const char *integrator; /* "path" or "direct"; NULL = the scene's */
    /* Nonzero: the general code path, with every feature switched on, instead of the one built
     * for what the scene uses. The image is the same in expectation (for checks and benchmarks). */
    int all_features;
    /* Called from worker threads after each tile with the fraction done; return nonzero to cancel.
     * Calls are serialised. NULL = none. */
    int (*progress)(void *user, double done);
    void *user;
} mcrt_options;

/* Fill o with defaults (all zero / NULL) and set o->size. */
void mcrt_options_init(mcrt_options *o);

/* Prepare a render of s (s must outlive it); NULL when out of memory. Option errors are reported
 * by mcrt_render_run. */
mcrt_render *mcrt_render_new(const mcrt_scene *s, const mcrt_options *o);
/* Render; blocks until done. MCRT_ERR_CANCELLED when cancelled (pixels then hold what was done). */
mcrt_status mcrt_render_run(mcrt_render *r);
/* Ask a running render to stop soon. Safe from any thread and from signal handlers. */
void mcrt_render_cancel(mcrt_render *r);
/* Linear RGB radiance, 3 floats per pixel, rows top to bottom. Borrowed until the next run or
 * mcrt_render_free; NULL before a run. */
const float *mcrt_render_pixels(const mcrt_render *r, int *width, int *height);
/* Write the image; the format is chosen by the suffix: .png (8-bit sRGB), .exr (float), .pfm.
 * The file is written to a temporary name in the same folder and renamed when complete, so an
 * existing file is never left half-written. */
mcrt_status mcrt_render_save(mcrt_render *r, const char *path);

typedef struct mcrt_stats {
    int width, height, spp, threads;
    double seconds;      /* wall-clock time of mcrt_render_run */
    uint64_t rays;       /* rays traced (camera, bounce and shadow rays) */
    uint64_t nan_count;  /* samples that were NaN or infinite: counted, never added */
} mcrt_stats;
/* Facts about the last run. */
void mcrt_render_stats(const mcrt_render *r, mcrt_stats *out);
/* The last error on r, "" if none. Owned by r. */
const char *mcrt_render_error(const mcrt_render *r);
void mcrt_render_free(mcrt_render *r);

/* ---- Images ---- */

/* Whether this build can write (and read) a format: "png", "exr", "pfm". */
int mcrt_format_supported(const char *suffix);

#ifdef __cplusplus
}
#endif
#endif
