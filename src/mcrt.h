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
 * valid until the next call that changes that handle (a load, a run) or until it is freed.
 * Besides the scene given to mcrt_render_new, nothing the caller passes is kept: mcrt_render_new
 * copies the options and their strings, all but the progress callback's user pointer, which is
 * handed back to the callback as given. *_free(NULL) is a no-op. Handles may be used from any thread, one call at a time,
 * except mcrt_render_cancel, which may be called from any thread during mcrt_render_run.
 *
 * Versions: the structs the caller fills begin with a size, set by their *_init; the library
 * reads the fields that size covers and gives the later ones their defaults, so a program built
 * against an older mcrt.h keeps working. A larger size (a newer mcrt.h) is accepted when the
 * fields this library does not know are all zero (their defaults), and refused otherwise, as is a
 * size above 4096 bytes (garbage). The structs the library fills are passed with their size, and
 * only that many bytes are written.
 */
#ifndef MCRT_H
#define MCRT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MCRT_VERSION "0.1.0"
/* The same version as one number, major * 10000 + minor * 100 + patch, for #if. */
#define MCRT_VERSION_NUM 100

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
/* The names of one closed set, as a static NULL-terminated array: "integrator" (the values of
 * mcrt_options.integrator and of a scene's integrator method), "sampler" (the values of
 * mcrt_options.sampler), "aov" (the layers of mcrt_options.aovs), "filter" and "shape" (the
 * scene language's film filters and shape blocks), "light" (the kinds of light: point, area,
 * environment), "material" (the kinds of material), "texture" (the kinds of texture: image,
 * checker). NULL for any other set. */
const char *const *mcrt_names(const char *set);
/* A one-line description of the member name of set, for listing it (mcrt --help); NULL when
 * the set has none (only "integrator" has them) or name is not in it. Static string. */
const char *mcrt_describe(const char *set, const char *name);

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
/* What the last successful load of s ignored or doubted in its input but could read past (an
 * MTL statement mcrt does not support, say): lines "file:line:col: warning: what", each ending in
 * a newline, each said once; "" if none (and after a failed load). Owned by s. */
const char *mcrt_scene_warnings(const mcrt_scene *s);
/* The film size and spp the scene asks for (NULL pointers are skipped). */
void mcrt_scene_film(const mcrt_scene *s, int *width, int *height, int *spp);
/* What a loaded scene uses and what it costs, as `mcrt info` prints it: lines "key: value" with
 * the features found, the sample dimensions one path draws, and the memory of the BVH and the
 * film. Owned by s. */
const char *mcrt_scene_info(mcrt_scene *s);
/* Write a loaded scene as a POV-Ray 3.7 scene file at path, with the physical mapping of mcrt(1)
 * `mcrt pov`, for an independent reference render; the second line holds the pinned POV-Ray flags.
 * MCRT_ERR_UNSUPPORTED, with a message naming the feature, when the scene uses something POV-Ray
 * cannot reproduce faithfully; no file is then written. Written to a temporary name and renamed. */
mcrt_status mcrt_scene_export_pov(mcrt_scene *s, const char *path);
/* Write a loaded scene as a Mitsuba 3 XML scene at path (variant scalar_rgb), its triangles as OBJ
 * files beside it (path without .xml, then -mesh0.obj, ...), with the mapping of mcrt(1)
 * `mcrt mitsuba`. MCRT_ERR_UNSUPPORTED, with a message "file:line:col: cannot export ..." naming
 * the construct, when the scene uses something Mitsuba cannot reproduce; nothing is then written.
 * Each file is written to a temporary name and renamed. */
mcrt_status mcrt_scene_export_mitsuba(mcrt_scene *s, const char *path);
void mcrt_scene_free(mcrt_scene *s);

/* ---- Rendering ---- */

typedef struct mcrt_render mcrt_render;

typedef struct mcrt_options {
    size_t size;            /* sizeof(mcrt_options), set by mcrt_options_init (see Versions) */
    int spp;                /* samples per pixel; 0 = the scene's */
    int threads;            /* worker threads; 0 = all cores */
    uint64_t seed;          /* the image is a function of (scene, options, seed) only */
    /* "path", "direct", "mis", "bsdf", "light" or "sppm" (see mcrt_names); NULL = the scene's */
    const char *integrator;
    /* Nonzero: the general code path, with every feature switched on, instead of the one built
     * for what the scene uses. The image is the same in expectation (for checks and benchmarks). */
    int all_features;
    /* Called from worker threads after tiles with the fraction done; return nonzero to cancel.
     * Calls are serialised but hold no lock of the render, so a slow callback delays only its
     * own thread: a tile finished meanwhile is reported by that call's thread when it returns.
     * The fractions of a pass never decrease and end at 1. NULL = none. */
    int (*progress)(void *user, double done);
    void *user;
    /* Extra layers mcrt_render_save writes into an EXR, comma-separated: "variance" (the
     * estimated variance of each pixel mean), and of the surface each camera ray meets first,
     * averaged over the pixel: "albedo" (the material's colour, textured), "normal" (the unit
     * shading normal facing the camera), "depth" (the distance from the ray's origin, in all three
     * channels); mcrt_names("aov") lists them. Each is the layer NAME.R/G/B, and a miss gives 0.
     * NULL = none. */
    const char *aovs;
    /* Render only the pixels crop_x0 <= x < crop_x1, crop_y0 <= y < crop_y1 of the scene's image
     * (each the value it has in the whole image with the same seed). All 0: the whole image. */
    int crop_x0, crop_y0, crop_x1, crop_y1;
    /* Progressive rendering: passes of spp samples per pixel, each with its own seed, until
     * time_budget seconds are spent (a pass is not started when, lasting as long as the last, it
     * would end later) or the estimated relative MSE falls to target_error. 0: no limit. With
     * neither, one pass. The image depends on the seed and the number of passes only. */
    double time_budget;
    double target_error;
    const char *sampler;    /* one of mcrt_names("sampler"): "random", "stratified", "sobol";
                             * NULL = the scene's */
    /* Nonzero: adaptive sampling. A uniform first pass, then passes that give each pixel samples
     * in proportion to its estimated error (sigma / sqrt(mean^2 + 0.01)), with a fifth of each
     * pass spread uniformly so that no pixel is starved. spp is then the mean samples per pixel:
     * of the whole render (in passes of spp/8, at least 8) without time_budget and target_error,
     * of each pass with either. Deterministic like the passes; a crop is sampled by its own
     * errors, so its pixels differ from the whole image's. */
    int adaptive;
    /* Render farms (mcrt(1), mcrt-mpi), for the per-ray integrators, not adaptive.
     * passes > 0: the image is to hold this many passes in all (a resumed state's included),
     * unless time_budget or target_error stop it first. first_pass: the index of the first
     * pass in the seed's sequence of passes, so that renders of passes 0 to k-1 and k to n-1
     * merge (mcrt_merge) into the samples of one render of n. resume: an EXR written with a
     * render state (save_state) to continue, refused unless it is a render of this scene with
     * these options and seed; the passes it holds come first, and the result is bit-identical
     * to one render of the same total passes (without passes, time_budget or target_error: one
     * pass more). save_state: mcrt_render_save writes the state (each pixel's sums exactly,
     * the scene's hash, the options and the passes) into the EXR, as it always does with
     * time_budget or target_error when the image is an EXR. */
    int passes, first_pass;
    const char *resume;
    int save_state;
    /* Nonzero: denoise the image after rendering (NFOR, Bitterli et al. 2016: features of the
     * first non-specular surface prefiltered across the two half buffers, first-order
     * regression of colour on them, candidate filters chosen per pixel by their error estimated
     * from the halves). mcrt_render_pixels is then the denoised image, est_relmse its estimated
     * error (est_relmse_raw the raw image's), and an EXR from mcrt_render_save holds the layers
     * "raw", "A", "B" and, per half, "albedo.A", "albedo.B", "normal.*", "depth.*",
     * "emission.*", which mcrt_denoise_file reads again. Refused with resume (the state holds
     * no features of the passes before) and with "sppm" (its halves are not independent). */
    int denoise;
} mcrt_options;

/* Fill o with defaults (all zero / NULL) and set o->size. */
void mcrt_options_init(mcrt_options *o);

/* Prepare a render of s (s must outlive it) with a copy of the options o (NULL: the defaults);
 * NULL when out of memory. Option errors, a size that cannot be read among them, are reported by
 * mcrt_render_run. */
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
    /* The image's relative MSE estimated from its own samples: the mean over pixels and channels
     * of Var(mean)/(max(A*B, m^2/2) + 0.01), A and B the means of the two halves of a pixel's
     * samples (m theirs), each an independent randomization of the sampler. Var(mean) is
     * unbiased for every sampler: (A - B)^2/4, or with the random sampler the pooled sample
     * variance s^2/n. Measured against the truth in mcrt(1) and the README. NaN below 2 spp. */
    double est_relmse;
    double efficiency;   /* 1 / (est_relmse * seconds): higher is better at equal quality */
    int passes;          /* complete passes in the image (spp counts all of them) */
    int adaptive;        /* whether the render was adaptive (spp is then the mean per pixel) */
    int spp_min, spp_max; /* the fewest and most samples a pixel has (both spp when uniform) */
    /* A biased integrator's (sppm's) est_relmse in its two parts, the same mean over pixels and
     * channels of bias^2 and of the variance, each over (mean^2 + 0.01); est_relmse is their
     * sum (with each pixel's total kept >= 0). NaN for the unbiased integrators, whose
     * est_relmse is all variance, and below 2 passes. */
    double est_relmse_bias2, est_relmse_variance;
    /* How est_relmse falls with the samples taken, est ~ samples^relmse_slope (and so with
     * time at a steady rate): fitted over the later half of the passes from 8 passes on, else
     * -1, the rate of a render continued by passes (each an independent randomization, whatever
     * the sampler). */
    double relmse_slope;
    /* The seconds a render like this one would need for a relMSE of 1e-2, 1e-3 and 1e-4, from
     * est_relmse, seconds and relmse_slope (NaN when est_relmse is). */
    double seconds_to_relmse[3];
    /* The raw (not denoised) image's est_relmse, equal to est_relmse without opt.denoise. */
    double est_relmse_raw;
    double denoise_seconds; /* the denoiser's part of seconds; 0 without opt.denoise */
    /* With opt.denoise, est_relmse's own standard deviation from one render to the next: its
     * per-pixel terms are, up to the filter's error, products of the two halves' independent
     * noises, whose variances it sums (the README's denoiser section). It does not cover what
     * neither half sampled. NaN without opt.denoise. */
    double est_relmse_sd;
} mcrt_stats;
/* Facts about the last run (all zero before one), into the first out_size bytes of out:
 * pass sizeof *out. */
void mcrt_render_stats(const mcrt_render *r, mcrt_stats *out, size_t out_size);
/* The seconds a render like the one st describes would need to reach this relMSE, its time
 * growing with its samples: st->seconds times (relmse / st->est_relmse)^(1 / st->relmse_slope);
 * NaN when st has no estimate. */
double mcrt_seconds_to_relmse(const mcrt_stats *st, double relmse);
/* Write the last run's statistics and seed as a JSON object (the keys of mcrt(1)'s --stats), with
 * the labels scene and image (NULL: null), in the same all-or-nothing way as mcrt_render_save. */
mcrt_status mcrt_render_save_stats(mcrt_render *r, const char *path, const char *scene,
                                   const char *image);
/* The last run's per-pixel sums (a render state's words, for sending to another process) as
 * *bytes bytes; borrowed like mcrt_render_pixels. NULL when there is no state (before a run, or
 * an integrator without one). */
const void *mcrt_render_sums(const mcrt_render *r, size_t *bytes);
/* Add the sums of another render of the same scene, options and size, holding `passes` passes
 * from first_pass on, to r's (Chan, Golub and LeVeque 1979), as if r had rendered them after
 * its own: its pixels, statistics and state follow. When they are r's next passes, the result is
 * bit-identical to a render of them all in one run. */
mcrt_status mcrt_render_add_sums(mcrt_render *r, const void *sums, size_t bytes, int first_pass,
                                 int passes);
/* The last error on r, "" if none. Owned by r. */
const char *mcrt_render_error(const mcrt_render *r);
void mcrt_render_free(mcrt_render *r);

/* ---- Comparing images ---- */

/* Denoise the EXR at in as opt.denoise does a render: in must hold the layers A and B and the
 * per-half layers that a render with opt.denoise saves (albedo.A, albedo.B, normal.A, normal.B,
 * depth.A, depth.B, emission.A, emission.B, variance.A, variance.B, emission.var), all of one
 * size. out (EXR) gets the denoised image
 * as its RGB and the layer "raw", written to a temporary file renamed when complete. threads 0:
 * all cores. est_raw and est_denoised, when not NULL, get the estimated relMSE of the raw and the
 * denoised image, est_denoised_sd the latter's own standard deviation (as mcrt_stats'
 * est_relmse_sd). On failure a message "in: what is wrong" is written into error (error_size
 * bytes) and out is left as it was. */
mcrt_status mcrt_denoise_file(const char *in, const char *out, int threads, double *est_raw,
                              double *est_denoised, double *est_denoised_sd, char *error,
                              size_t error_size);

typedef struct mcrt_diff_options {
    size_t size;            /* sizeof(mcrt_diff_options), set by mcrt_diff_options_init */
    const char *layer;      /* EXR layer of TEST and REF to compare; NULL = the first RGB one */
    int crop_x0, crop_y0;   /* the crop window x0 <= x < x1, y0 <= y < y1 in pixels; */
    int crop_x1, crop_y1;   /* all 0 = none */
    /* The z-test runs when variance is set: the image of the variance of TEST's pixel means (its
     * "variance" layer if it has one, else its first RGB layer). */
    const char *variance;
    double floor;           /* added in quadrature to each pixel's standard deviation */
    double alpha;           /* family-wise significance over all pixels; 0 = 0.01 */
    double min_agree;       /* pass when this fraction of pixels agree; 0 = 0.9975 */
    const char *z_image;    /* when the z-test fails, write a false-colour PNG of z here; NULL = no */
} mcrt_diff_options;

typedef struct mcrt_diff_stats {
    size_t pixels;
    double mse;             /* mean over pixels and channels of (t - r)^2 */
    double relmse;          /* mean over pixels and channels of (t - r)^2 / (r^2 + 0.01) */
    double psnr;            /* dB, peak 1: 10 log10(1 / mse); infinite when mse is 0 */
    double max_abs;         /* largest |t - r| */
    double bias;            /* mean of t - r over pixels and channels */
    double bias_r, bias_g, bias_b; /* mean of t - r per channel */
} mcrt_diff_stats;

typedef struct mcrt_diff_result {
    int width, height;      /* 0 when an image could not be read */
    mcrt_diff_stats whole;  /* the whole image */
    mcrt_diff_stats crop;   /* the crop window (the whole image without one) */
    int ztest, ztest_pass;  /* whether the z-test ran (over the crop window) and passed */
    double alpha_test;      /* Sidak per-channel level: 1 - (1 - alpha)^(1 / (3 pixels)) */
    double z_crit;          /* the |z| that level corresponds to */
    double agree;           /* fraction of pixels with every channel below z_crit */
    double max_z;
    size_t rejected;        /* pixels with a significant channel */
    int z_image_written;
} mcrt_diff_result;

/* Fill o with defaults (all zero / NULL) and set o->size. */
void mcrt_diff_options_init(mcrt_diff_options *o);
/* Compare the images test and ref (PNG, EXR or PFM, the same size) into the first out_size bytes
 * of out (pass sizeof *out). MCRT_ERR_IO or MCRT_ERR_UNSUPPORTED when an image cannot be read
 * (out->width is then 0), MCRT_ERR_INVALID for a bad option or mismatched sizes, MCRT_ERR_IO when
 * the z image cannot be written, MCRT_ERR_NOMEM when out of memory; a one-line reason goes to
 * error (error_size bytes; NULL to skip). A failed z-test is not an error: see out->ztest_pass. */
mcrt_status mcrt_diff(const char *test, const char *ref, const mcrt_diff_options *o,
                      mcrt_diff_result *out, size_t out_size, char *error, size_t error_size);

/* ---- Merging renders ---- */

/* Merge the n EXR images with render states (mcrt_options.save_state) at inputs into one
 * written at output (an EXR with the merged state; written whole or not at all): renders of one
 * scene and options with other seeds or passes of the same pixels are merged exactly (Chan,
 * Golub and LeVeque 1979), in the order given, and crops are assembled into the window they
 * tile. Files of other scenes, options or sizes, crops that overlap without being the same
 * window or leave a gap, and damaged files are refused: MCRT_ERR_INVALID, or MCRT_ERR_IO for a
 * file that cannot be read, with "file: what is wrong" in error. The merged image's statistics
 * (size, spp, passes, est_relmse) go into the first out_size bytes of out (NULL: none). */
mcrt_status mcrt_merge(const char *const *inputs, int n, const char *output, mcrt_stats *out,
                       size_t out_size, char *error, size_t error_size);

/* ---- Images ---- */

/* Whether this build can write (and read) a format: "png", "exr", "pfm". */
int mcrt_format_supported(const char *suffix);

#ifdef __cplusplus
}
#endif
#endif
