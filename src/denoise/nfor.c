/* nfor.c: the NFOR-style denoiser (see nfor.h). */
#include "denoise/nfor.h"

#include <math.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"
#include "core/simd.h"
#include "denoise/firefly.h"
#include "denoise/ldl.h"
#include "denoise/light_edge.h"
#include "render/render.h"

/* NFOR's parameters (Bitterli et al. 2016, §5; Tungsten's defaults): patch radius F, window
 * radius R and bandwidth k of the feature prefilter, the regression and the smoothing of the
 * error and selection maps. */
#define PRE_F 3
/* The prefilter's window: 9×9 rather than Tungsten's 11×11, two thirds of the offsets. The
 * features (albedo, normal, depth of the first surface) are noisy only where a pixel's samples
 * see different surfaces, edges and what a lens or motion blurs; measured by the denoised error,
 * make bench-denoise (160², 10 seeds, 16 and 64 spp): the Cornell box and cornell-spheres moved
 * by -0.2% to 0.0%, and scenes/dof.mcrt and scenes/motion.mcrt (320×180, 16 spp, 4 seeds) by
 * +0.2% each; 7×7 moved motion.mcrt by +2.3%. 6% fewer instructions (callgrind, a 128² Cornell
 * box at 4 spp: 1.889 G -> 1.770 G). */
#define PRE_R 4
#define PRE_K 0.5f
#define REG_F 3
/* The regression's window: 17×17 rather than Tungsten's 19×19, 0.8 of the pixels. Measured by
 * the denoised error of the Cornell box and cornell-spheres (160², 10 seeds, 16 and 64 spp):
 * from -4% (cornell-spheres, 64 spp) to +0.2% (the Cornell box, 16 spp), with 12% less time for
 * a 512² image; 15×15 had lost 1.5-9% on two seeds each. */
#define REG_R 8
#define MAP_F 1
/* The maps' window: 7 rather than Tungsten's 9, 0.6 of the offsets. Measured by the denoised
 * error of the Cornell box and cornell-spheres (160², 10 seeds, 16 and 64 spp, each half's choice
 * made apart, step 3): from -1.4% to +0.4%. */
#define MAP_R 7
#define MAP_K 1.0f
/* The regression's two bandwidths: Tungsten's are 0.5 and 1. The wider second candidate does
 * better where the per-pixel selection picks it (flat walls, the Cornell box's ceiling), while
 * 0.5 stays for what must not be smeared (cornell-spheres' fireflies: 1 and 2 doubled its error
 * at 16 spp). Measured by make bench-denoise (160², 16 and 64 spp, seeds 1 and 2, the same
 * inputs): {0.5, 2} lowered the true relMSE of all eight renders against {0.5, 1}, by 3-23%
 * ({0.5, 1.5}, {0.5, 3} and {0.5, 4} did about as well, {0.25, 2} worse on the Cornell box). */
static const float reg_k[2] = {0.5f, 2.0f};
/* The colour variance the regression's weights divide by, a half's (OWN_R below), is averaged
 * over (2·REG_VAR_R + 1)² pixels, the patch's 7×7 and a pixel around it, rather than the 3×3 of the
 * prefilter and the maps: a firefly's one-degree-of-freedom variance, spread over 3×3 only, made
 * its neighbours' patches match anything, so that the regression spread it and the error
 * estimate, which takes the weights as independent of the other half, missed it. Measured by
 * make bench-denoise (the same inputs, with (A − B)²/2 as the variance then; radius 1 -> 4):
 * cornell-spheres 16 spp relMSE 1.53e-2 ->
 * 9.5e-3, 64 spp 3.08e-3 -> 2.88e-3, est/true 0.48 -> 0.83 and 0.27 -> 0.57; cornell 16 spp
 * 7.69e-4 -> 7.58e-4, 64 spp 1.69e-4 -> 1.65e-4. Radii 2-3 and 6-9 did worse on cornell-spheres
 * at 16 spp (1.1-1.5e-2), 5 about as well; one variance for the whole image (each channel's
 * mean) did about as well here, but cannot follow a scene's brightness. */
#define REG_VAR_R (REG_F + 1)
/* The regression's weights for half A come from B's colour and B's variance alone, and B's from
 * A's: the variance of a half's mean from its own samples (nfor.h). With (A − B)²/2, which A's
 * noise moves as much as B's, A's weights followed A, where the error estimate takes them as
 * fixed; on the scenes of make bench-denoise (10 seeds at 160², 16 and 64 spp) the denoised
 * relMSE fell by 0.9% and 1.8% on the Cornell box and 8% and 3% on cornell-spheres, and at
 * their own sizes (512², 400²) by 0.9% and 0.7%, and 9% and 2%. Those variances are biased up
 * for stratified and Sobol samples (film.h), by a factor that varies over the image, so each is
 * calibrated by the ratio of the box means, over (2·OWN_R + 1)² pixels, of the halves'
 * (A − B)²/2, unbiased, and of their own variances: a ratio that any one pixel moves by less than
 * half a percent, and that follows the sampler's gain from one part of the image to another
 * (the Cornell box's lit walls and its ceiling, lit only indirectly). 15×15, as the maps. */
#define OWN_R 7
/* Where the colour changes across a pixel, stratified and Sobol samples cancel more of the
 * within-pixel variation than OWN_R's box ratio, mostly of smooth pixels, says: there the own
 * variances read the realised (A − μ)² 1.12 to 1.20 times on the Cornell box (160², 16 and 64
 * spp, 40 seeds, weighted by the leverage as the error estimate weighs them; 0.96 to 0.99 in
 * each class of smoother pixels) and 0.88 times on cornell-spheres (400², 64 spp). The error
 * estimate's covariance term, about 3.5 times the error it helps to estimate, took that whole:
 * the Cornell box's estimate read 1.40 of the truth at 160² and 64 spp away from the light. So
 * for the estimate (edge_calibrate), the pixels whose 3×3 mean colour changes across them by
 * EDGE_GRADIENT of itself or more (the sum of the central differences' magnitudes, per channel)
 * get one more ratio, over all of them: the halves' (A − B)²/2 summed over their own variances
 * summed. The regression's weights keep the box's ratio: with this one their images were worse
 * (the Cornell box's denoised relMSE +0.6% and +0.3% at 160², 16 and 64 spp). */
#define EDGE_GRADIENT 0.5f
/* The denoised value f squared overstates μ², which the relative error divides by, by MSE(f) on
 * average, and by far more where a noisy spot is left bright: E[f²] = μ² + MSE(f). Each pixel's
 * μ² is taken as no more than the square of the (2·MEAN_SQ_R + 1)² mean of the denoised image
 * around it, a far less noisy value, which a lone bright pixel moves by a 25th of its excess. On
 * cornell-spheres at 400² (make bench-denoise, 10 seeds), where some 600 pixels that the
 * caustic's noise left over twice as bright as the truth made four fifths of the difference
 * between dividing by f² and by the reference's μ² (two seeds), the estimate of the whole image
 * read 0.67 and 0.47 of the truth at 16 and 64 spp with f², 1.14 and 0.84 with this; the Cornell
 * box's at 160² and 16 spp moved from 1.36 to 1.43. A legitimately bright pixel, a thin line,
 * counts a little more error than it has. */
#define MEAN_SQ_R 2

/* NL-means distances (Rousselle, Manzi and Zwicker 2012, eq. 3): the patch distance, with the
 * variances' share taken off, over the variances; clamped so exp() stays finite (and a NaN
 * becomes the clamp). A weight never goes below MIN_WEIGHT at the pixel itself, and weights
 * below 2^-19.5 = 1.4e-6 are 0 (exp_neg), left out of the sums: they change nothing visible and
 * cost as much as the others. */
#define DIST_EPS 1e-7f
#define DIST_CLAMP 10000.0f
#define MIN_WEIGHT 1e-4f

/* The width of the partial sums the vectorised loops keep (AVX2's 8 floats; SSE2 takes two
 * registers for each), whatever the instruction set: the same sums in the same order. */
#define LANES 8
#define MAX_DIM (3 + MC_NFOR_MAX_FEATURES) /* regression columns: 1, x, y, the features */
#define PAD (REG_R + REG_F) /* the widest reach of a patch around a window pixel */

/* What NL-means weights are computed from: gc channels and their variances (already scaled by
 * the guide's variance scale), each copied with a border of PAD pixels (the image's edge pixels
 * repeated, pad_copy), so that a patch around any window pixel is read without bounds checks;
 * patch radius f, bandwidth k. A guide that weights each channel by its own distance (features)
 * has its channels interleaved; one that weights all by their mean distance (colours) has each
 * padded row as gc planes one after the other, so that the mean is taken in the same vectorised
 * pass as the distances (patch_dist). */
struct guide {
    const float *img, *var;
    int gc, f;
    float k;
    int each; /* each channel weighted by its own distance, interleaved; else all by the mean of
                 the channels' distances, planar rows */
};

/* The image's size, the threads the tiles run on, and a tile's failure to get memory. */
struct pool {
    int width, height, threads;
    mcrt_status status;          /* MCRT_ERR_NOMEM when a tile could not get its buffers */
};

/* The hot loops (patch distances, weights, the regression's dot products) are plain C that GCC
 * vectorises for SSE2, the x86-64 baseline; on a processor with AVX2 the tile functions run as
 * copies compiled for it (core/simd.h's dispatch, as geom/bvh.c does), twice as wide. No FMA
 * is enabled and C99 forbids contracting a·b + c, and the vectoriser never reorders a sum: both
 * copies compute the same operations in the same order, so the image is the same bits on
 * either. MCRT_NFOR_NO_AVX keeps to the SSE2 copy. */
#if defined(MC_AVX2_DISPATCH) && !defined(MCRT_NFOR_NO_AVX)
#define NFOR_AVX_DISPATCH 1
#endif

/* A tile function NAME(ctx, w, x0, y0, x1, y1) that runs BODY, with its AVX2 copy NAME_avx2
 * under the dispatch; TILE_FN(NAME) is the one this processor runs. */
#ifdef NFOR_AVX_DISPATCH
#define TILE_FUNCTIONS(name, body)                                                             \
    static void name(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)         \
    {                                                                                          \
        body(ctx, w, x0, y0, x1, y1);                                                          \
    }                                                                                          \
    static MC_AVX2_TARGET void name##_avx2(void *ctx, struct tile_worker *w, int x0, int y0,   \
                                           int x1, int y1)                                     \
    {                                                                                          \
        body(ctx, w, x0, y0, x1, y1);                                                          \
    }
#define TILE_FN(name) (mc_cpu_has_avx2() ? name##_avx2 : name)
#else
#define TILE_FUNCTIONS(name, body)                                                             \
    static void name(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)         \
    {                                                                                          \
        body(ctx, w, x0, y0, x1, y1);                                                          \
    }
#define TILE_FN(name) name
#endif

/* The tile functions NAME (TILE_FUNCTIONS) of a band of rows, run's bands: TILE_BODY over its
 * tiles TILE_W wide, left to right; JOB, the context's type, holds the pool pl. */
#define BAND_FUNCTIONS(name, tile_body, job, tile_w)                                            \
    static MC_ALWAYS_INLINE void name##_body(void *ctx, struct tile_worker *w, int x0, int y0,  \
                                             int x1, int y1)                                   \
    {                                                                                          \
        int x, width = ((job *)ctx)->pl->width;                                                \
        (void)x0;                                                                              \
        (void)x1;                                                                              \
        for (x = 0; x < width; x += (tile_w))                                                  \
            tile_body(ctx, w, x, y0, x + (tile_w) < width ? x + (tile_w) : width, y1);         \
    }                                                                                          \
    TILE_FUNCTIONS(name, name##_body)

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* src (nc interleaved channels, width × height) copied times scale into dst with a border of PAD
 * pixels on every side, each border pixel a copy of the nearest edge pixel; each padded row's
 * channels interleaved, or, planar, as nc planes one after the other (struct guide). */
static void pad_copy(const float *src, int nc, int planar, int width, int height, float scale,
                     float *dst)
{
    size_t pw = (size_t)(width + 2 * PAD), rw = (size_t)width * (size_t)nc, i;
    int y, x, c;
    for (y = 0; y < height + 2 * PAD; y++) {
        const float *s = src + (size_t)clampi(y - PAD, 0, height - 1) * rw, *last = s + rw - nc;
        float *d = dst + (size_t)y * pw * (size_t)nc;
        for (c = 0; c < nc; c++) {
            /* channel c of pixel x goes to d[x·cs + c·ps] */
            size_t cs = planar ? 1 : (size_t)nc, ps = planar ? pw : 1;
            float *dc = d + (size_t)c * ps;
            for (x = 0; x < PAD; x++) {
                dc[(size_t)x * cs] = s[c] * scale;
                dc[(size_t)(PAD + width + x) * cs] = last[c] * scale;
            }
            for (i = 0; i < (size_t)width; i++)
                dc[(PAD + i) * cs] = s[i * (size_t)nc + (size_t)c] * scale;
        }
    }
}

/* e^-v[i] for each of n distances 0 <= v[i] <= DIST_CLAMP, in place: 2^-t (t = v·log2 e) as
 * 2^-k·e^f with k = t rounded and |f| <= ln2/2, e^f by its Taylor polynomial to f^4 (relative
 * error below 6e-5, measured against exp() over [0, 13.5]; to f^6 it was 1e-6, and the
 * denoised Cornell box and cornell-spheres, 10 seeds each at 16 and 64 spp, moved by under 0.1%
 * with 3% less time), 2^-k built in the float's exponent bits; 0 from k = 20 on (v > 13.5).
 * Plain arithmetic that vectorises, and the same bits on every machine, which libm's expf (a
 * per-processor variant) does not promise. */
static MC_ALWAYS_INLINE void exp_neg(float *v, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        float t = v[i] * 1.44269504f;
        int k = (int)(t + 0.5f);
        float f = ((float)k - t) * 0.693147181f;
        float e = 1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6 + f * (1.0f / 24))));
        union { int32_t i; float f; } scale;
        scale.i = (127 - (k < 20 ? k : 127)) << 23;
        v[i] = e * scale.f;
    }
}

/* Box sums: out[j] = Σ_{i < taps} in[j + i·step] for j < n, tap by tap from 0 (the order the
 * bits depend on). The taps unrolled (box_sum), GCC vectorises the loop over j with each sum in
 * a register; an array of LANES partial sums had been kept on the stack and copied out in
 * halves, a sixth of NL-means' time (perf). out must not overlap in. */
static MC_ALWAYS_INLINE void box_sum_taps(const float *restrict in, size_t step, int taps, int n,
                                          float *restrict out)
{
    int j, i;
    for (j = 0; j < n; j++) {
        float s = 0.0f;
#pragma GCC unroll 8
        for (i = 0; i < taps; i++)
            s += in[(size_t)j + (size_t)i * step];
        out[j] = s;
    }
}

/* box_sum_taps, its taps unrolled for the patch sizes used. */
static MC_ALWAYS_INLINE void box_sum(const float *in, size_t step, int taps, int n, float *out)
{
    if (taps == 2 * PRE_F + 1)
        box_sum_taps(in, step, 2 * PRE_F + 1, n, out);
    else if (taps == 2 * MAP_F + 1)
        box_sum_taps(in, step, 2 * MAP_F + 1, n, out);
    else
        box_sum_taps(in, step, taps, n, out);
}

/* The NL-means distance of one channel of two pixels, values p and q, variances vp and vq. */
static MC_ALWAYS_INLINE float pair_dist(float p, float q, float vp, float vq, float kk)
{
    float diff = p - q, dd = (diff * diff - (vp + (vp < vq ? vp : vq))) / (DIST_EPS + kk * (vp + vq));
    return dd < DIST_CLAMP ? dd : DIST_CLAMP;
}

/* out[x] = the mean over the gc planes (plane floats apart) of the channels' distances of pixel
 * x of ip against iq, x < n; three channels spelt out, as GCC vectorises an inner loop over the
 * channels instead of the pixels. */
static MC_ALWAYS_INLINE void mean_dist(const float *ip, const float *iq, const float *vp,
                                       const float *vq, size_t plane, int gc, int n, float kk,
                                       float *restrict out)
{
    const size_t p2 = 2 * plane;
    float inv = 1.0f / (float)gc;
    int x, c;
    if (gc == 3)
        for (x = 0; x < n; x++) {
            float s = pair_dist(ip[x], iq[x], vp[x], vq[x], kk);
            s += pair_dist(ip[plane + x], iq[plane + x], vp[plane + x], vq[plane + x], kk);
            s += pair_dist(ip[p2 + x], iq[p2 + x], vp[p2 + x], vq[p2 + x], kk);
            out[x] = s * inv;
        }
    else
        for (x = 0; x < n; x++) {
            float s = pair_dist(ip[x], iq[x], vp[x], vq[x], kk);
            for (c = 1; c < gc; c++) {
                size_t i = (size_t)c * plane + (size_t)x;
                s += pair_dist(ip[i], iq[i], vp[i], vq[i], kk);
            }
            out[x] = s * inv;
        }
}

/* Which rows of a tile patch_dist computes: out[y] for the tile's row y, and in[y] for the row
 * y - f of the patches around it, set when a computed row's patch reaches it. */
struct row_mask {
    unsigned char out[MC_TILE], in[MC_TILE + 2 * PAD];
};

/* m->in from m->out, for a tile th rows high and patches of radius f. */
static void row_mask_reach(struct row_mask *m, int th, int f)
{
    int y, i;
    memset(m->in, 0, sizeof m->in);
    for (y = 0; y < th; y++)
        for (i = 0; m->out[y] && i <= 2 * f; i++)
            m->in[y + i] = 1;
}

/* The NL-means patch distances of pixel p = (x, y) against p + (dx, dy), for every p of the tile
 * [x0, x1) × [y0, y1), into wt (row-major, tile-sized): per channel for a guide that weights
 * each channel by its own (g->each; interleaved as the guide's channels), else their mean over
 * the channels, as NL-means for colour images has it (Buades, Coll and Morel 2011, "Non-Local
 * Means Denoising", IPOL, the squared distance averaged over the three channels; Tungsten's NFOR
 * takes the largest channel's instead, which did worse here: README, the denoiser's section).
 * Only the rows of the tile that rows marks, or all when rows is NULL (the others' rows of wt are
 * left as they were). scratch holds scratch_floats(g, x1 - x0) floats.
 * Pixels outside the image read the padded guide's copies of its border. Each loop runs along
 * rows of contiguous floats (a row's pixels and their channels), so that it vectorises. */
static MC_ALWAYS_INLINE void patch_dist(const struct guide *g, int width, int x0, int y0, int x1,
                                         int y1, const struct row_mask *rows, int dx, int dy,
                                         float *wt, float *scratch)
{
    int f = g->f, gc = g->gc, oc = g->each ? gc : 1; /* the channels of the distances */
    int tw = x1 - x0, th = y1 - y0, ph = th + 2 * f;
    int rw = (tw + 2 * f) * oc, tr = tw * oc, y, i, j;
    size_t plane = (size_t)(width + 2 * PAD), stride = plane * (size_t)gc;
    ptrdiff_t off = (ptrdiff_t)dy * (ptrdiff_t)stride + (ptrdiff_t)dx * oc;
    float *dist = scratch, *col = scratch + (size_t)rw * ph;
    float norm = 1.0f / (float)((2 * f + 1) * (2 * f + 1)), kk = g->k * g->k;
    for (y = 0; y < ph; y++) {
        size_t p = (size_t)(y0 - f + y + PAD) * stride + (size_t)(x0 - f + PAD) * (size_t)oc;
        const float *ip = g->img + p, *iq = ip + off, *vpp = g->var + p, *vqp = vpp + off;
        float *dr = dist + (size_t)y * rw;
        if (rows && !rows->in[y])
            continue;
        if (!g->each)
            mean_dist(ip, iq, vpp, vqp, plane, gc, rw, kk, dr);
        else
            for (i = 0; i < rw; i++)
                dr[i] = pair_dist(ip[i], iq[i], vpp[i], vqp[i], kk);
    }
    /* The box filter over the patch, separably: down the columns for each row computed, then
     * along that row. Columns first, so that the pass along the rows covers the tile's th rows
     * only, not the th + 2f rows of the patches' reach (a sixth fewer sums in NL-means' tiles,
     * 128 wide, and two fifths fewer in the regression's lattice pass, which needs every other
     * row). */
    for (y = 0; y < th; y++) {
        float *o = wt + (size_t)y * tr;
        if (rows && !rows->out[y])
            continue;
        box_sum(dist + (size_t)y * rw, (size_t)rw, 2 * f + 1, rw, col);
        box_sum(col, (size_t)oc, 2 * f + 1, tr, o);
        for (j = 0; j < tr; j++) {
            float v = o[j] * norm;
            o[j] = v > 0.0f ? v : 0.0f;
        }
    }
}

/* The weights of the distances patch_dist gave for the offset (0, 0) or not (centre), in place. */
static MC_ALWAYS_INLINE void weights(float *wt, int n, int centre)
{
    int i;
    exp_neg(wt, n);
    for (i = 0; centre && i < n; i++)
        wt[i] = wt[i] < MIN_WEIGHT ? MIN_WEIGHT : wt[i];
}

/* patch_dist's scratch for tiles up to tw wide and MC_TILE high: the distances of the rows
 * read and one row's sums down the columns. */
static size_t scratch_floats(const struct guide *g, int tw)
{
    size_t f2 = (size_t)(2 * g->f), w = (size_t)tw;
    return (w + f2) * (MC_TILE + f2 + 1) * (size_t)g->gc;
}

/* Run fn over the tiles of the image on the pool's threads; with bands, over bands of MC_TILE
 * rows, each a tile of the runner's with x0 = 0, x1 = 1 standing for the image's width. */
static mcrt_status run(struct pool *pl, int bands, mc_tile_fn fn, void *ctx, mc_diag *d)
{
    struct render_settings rs;
    struct tile_result tr;
    mcrt_status st;
    memset(&rs, 0, sizeof rs);
    rs.threads = pl->threads;
    pl->status = MCRT_OK;
    st = mc_tiles_run(&rs, 0, 0, bands ? 1 : pl->width, pl->height, fn, ctx, &tr, d);
    if (st == MCRT_OK && pl->status != MCRT_OK)
        st = mc_fail(d, pl->status, "out of memory for the denoiser's tiles");
    return st;
}

/* ---- NL-means: dst = the weighted mean of src (sc channels) over a window of radius r. ---- */

struct nlm_job {
    struct pool *pl;
    const struct guide *g;
    const float *src; /* a colour guide's: sc planes of width × height (nlm's copy of its
                         interleaved src); a feature guide's: src as it is, interleaved */
    int sc, r;
    float *dst;
};

/* al[i] += w[i]·s[i] for i < n: a weight of 0 adds nothing, even to a value that is not
 * finite. */
static MC_ALWAYS_INLINE void add_weighted(float *al, const float *w, const float *s, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        float ws = w[i] * s[i];
        al[i] += w[i] != 0.0f ? ws : 0.0f;
    }
}

/* al[i] += w[i] for i < n. */
static MC_ALWAYS_INLINE void add_weights(float *al, const float *w, int n)
{
    int i;
    for (i = 0; i < n; i++)
        al[i] += w[i];
}

static MC_ALWAYS_INLINE void nlm_tile_body(void *ctx, struct tile_worker *w, int x0, int y0, int x1,
                                        int y1)
{
    struct nlm_job *j = ctx;
    int width = j->pl->width, height = j->pl->height, tw = x1 - x0, th = y1 - y0;
    int sc = j->sc, wc = j->g->each ? sc : 1, dx, dy, x, y, c;
    size_t np = (size_t)tw * th, n = (size_t)width * (size_t)height;
    float *wt = mc_malloc((np * (size_t)wc + scratch_floats(j->g, tw)) * sizeof *wt);
    /* The sums of weighted values, then of weights (a colour guide's: a plane per channel, then
     * one of weights; a feature guide's: interleaved as its channels), over a row of offsets
     * in float (part, psum: twice as many in a vector as doubles), then
     * added to the whole window's in double (acc), where the sums of the error maps' terms,
     * which span many orders of magnitude, keep their precision. */
    double *acc = mc_calloc(np * (size_t)(sc + wc), sizeof *acc);
    float *part = mc_malloc(np * (size_t)(sc + wc) * sizeof *part), *psum = part + np * (size_t)sc;
    size_t i;
    (void)w;
    if (!wt || !acc || !part) {
        j->pl->status = MCRT_ERR_NOMEM;
        free(wt);
        free(acc);
        free(part);
        return;
    }
    for (dy = -j->r; dy <= j->r; dy++) {
        memset(part, 0, np * (size_t)(sc + wc) * sizeof *part);
        for (dx = -j->r; dx <= j->r; dx++) {
            /* The tile's pixels whose neighbour p + (dx, dy) is inside the image. */
            int xa = x0 + dx < 0 ? -dx : x0, xb = x1 + dx > width ? width - dx : x1;
            int ya = y0 + dy < 0 ? -dy : y0, yb = y1 + dy > height ? height - dy : y1;
            patch_dist(j->g, width, x0, y0, x1, y1, NULL, dx, dy, wt, wt + np * (size_t)wc);
            weights(wt, (int)np * wc, dx == 0 && dy == 0);
            for (y = ya; y < yb; y++) {
                size_t l = (size_t)(y - y0) * tw + (size_t)(xa - x0);
                int m = xb - xa;
                if (wc > 1) {
                    /* Each channel by its own weight: values, weights and sums interleaved. */
                    const float *s = j->src + ((size_t)(y + dy) * width + (size_t)(xa + dx)) * sc;
                    add_weighted(part + l * sc, wt + l * sc, s, m * sc);
                    add_weights(psum + l * sc, wt + l * sc, m * sc);
                    continue;
                }
                for (c = 0; c < sc; c++)
                    add_weighted(part + (size_t)c * np + l, wt + l,
                                 j->src + (size_t)c * n + (size_t)(y + dy) * width
                                     + (size_t)(xa + dx), m);
                add_weights(psum + l, wt + l, m);
            }
        }
        for (i = 0; i < np * (size_t)(sc + wc); i++)
            acc[i] += part[i];
    }
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++) {
            size_t l = (size_t)(y - y0) * tw + (size_t)(x - x0);
            for (c = 0; c < sc; c++)
                j->dst[((size_t)y * width + x) * sc + c]
                    = (float)(wc > 1 ? acc[l * sc + c] / acc[(np + l) * sc + c]
                                     : acc[(size_t)c * np + l] / acc[np * sc + l]);
        }
    free(wt);
    free(acc);
    free(part);
}

/* A band of rows [y0, y1) (run's bands), as tiles NLM_W wide: wider than the runner's tiles, so
 * that the padding of the patches around a tile is recomputed less often and the loops along a
 * tile's rows are long (the result is the same for any tiling: a pixel's sums over the offsets
 * are taken in the same order). */
enum { NLM_W = 128 };
BAND_FUNCTIONS(nlm_band, nlm_tile_body, struct nlm_job, NLM_W)

/* src: sc interleaved channels, dst the same. */
static mcrt_status nlm(struct pool *pl, const struct guide *g, const float *src, int sc, int r,
                       float *dst, mc_diag *d)
{
    size_t i, n = (size_t)pl->width * (size_t)pl->height;
    /* A colour guide's values as planes (nlm_tile_body); a feature guide's as they are. */
    float *planes = g->each ? NULL : mc_malloc(n * (size_t)sc * sizeof *planes);
    struct nlm_job j;
    mcrt_status st;
    int c;
    if (!g->each && !planes)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser");
    for (i = 0; planes && i < n; i++)
        for (c = 0; c < sc; c++)
            planes[(size_t)c * n + i] = src[i * (size_t)sc + (size_t)c];
    j.pl = pl;
    j.g = g;
    j.src = planes ? planes : src;
    j.sc = sc;
    j.r = r;
    j.dst = dst;
    st = run(pl, 1, TILE_FN(nlm_band), &j, d);
    free(planes);
    return st;
}

/* ---- First-order regression (NFOR §5.2) ---- */

/* The channels regressed: the colour's three and the leverage probe (regress). */
enum { REG_C = 4 };

/* The regression's window: offset o = (dy + R)·SIDE + (dx + R), padded with zero weights to NWP,
 * a multiple of LANES. */
enum { SIDE = 2 * REG_R + 1, NW = SIDE * SIDE, NWP = (NW + LANES - 1) / LANES * LANES };
/* The regression's tiles: MC_TILE rows, REG_W columns. A tile's patches reach f beyond it on
 * each side, computed again by its neighbour: 64 wide rather than 32 took 5% fewer instructions
 * (callgrind, 256² Cornell box at 16 spp: 8.09 G -> 7.68 G; 128 wide, 7.53 G, with twice the
 * distances' memory, up to 1.2 MB a thread at 64) and 4.42 s against 4.86 s at best of five
 * alternated one-thread runs at 512²; the image moves only by the order in which the tiles'
 * overlapping sums are added (relMSE 1e-14). */
enum { REG_W = 64 };

/* The regression's tiles across the image. */
static int reg_tiles_across(const struct pool *pl) { return (pl->width + REG_W - 1) / REG_W; }

/* Σ_o a_k[o]·col_b[o] for both bandwidths' a_0 and a_1 and nb <= DOT_BLOCK columns, into
 * out[k][b], each in LANES partial sums added in double at the end: the same operations in the
 * same order whatever vector width the compiler picks. The columns go together so that each a_k
 * is loaded once for all of them and the 2·DOT_BLOCK sums stay in registers (all but 5 of
 * AVX2's 16): each spelt out, as GCC keeps an array indexed by a loop in memory, and called with
 * a constant nb, which inlining folds. */
enum { DOT_BLOCK = 4 };
static MC_ALWAYS_INLINE void dots(const float *a0, const float *a1, const float *const *col, int nb,
                               double out[2][DOT_BLOCK])
{
    const float *c0 = col[0], *c1 = col[nb > 1], *c2 = col[nb > 2 ? 2 : 0];
    const float *c3 = col[nb > 3 ? 3 : 0];
    float s[2][DOT_BLOCK][LANES] = {{{0.0f}}};
    int o, l, b, k;
    for (o = 0; o < NWP; o += LANES)
        for (l = 0; l < LANES; l++) {
            s[0][0][l] += a0[o + l] * c0[o + l];
            s[1][0][l] += a1[o + l] * c0[o + l];
            if (nb > 1) {
                s[0][1][l] += a0[o + l] * c1[o + l];
                s[1][1][l] += a1[o + l] * c1[o + l];
            }
            if (nb > 2) {
                s[0][2][l] += a0[o + l] * c2[o + l];
                s[1][2][l] += a1[o + l] * c2[o + l];
            }
            if (nb > 3) {
                s[0][3][l] += a0[o + l] * c3[o + l];
                s[1][3][l] += a1[o + l] * c3[o + l];
            }
        }
    for (k = 0; k < 2; k++)
        for (b = 0; b < nb; b++) {
            double t = 0.0;
#pragma GCC unroll 8
            for (l = 0; l < LANES; l++)
                t += s[k][b][l];
            out[k][b] = t;
        }
}

struct reg_job {
    struct pool *pl;
    const struct guide *g;     /* with k = 1: the distances, to which each bandwidth k applies */
    const float *img;          /* the colour and the probe regressed, padded (REG_C channels) */
    const float *const *feat;  /* nf planes, padded */
    int nf;
    const unsigned char *need; /* NULL: the lattice's pass; else the pixels of the second */
    float *acc;                /* per tile, reg_tile_floats() from tile ti's: per bandwidth
                                  REG_C + 1 planes (R, G, B, probe, weight) of the tile and the
                                  windows' reach R around it, zeros until a fit adds to them */
    unsigned char *used;       /* per tile: whether a fit has added to its sums */
};

/* A regression tile's sums (reg_job.acc): allocated once for every tile of the image and both
 * halves' passes, zeroed again as they are merged, rather than a tile's own zeroed allocation
 * each pass. With regress's other buffers allocated once too, the denoiser of a 512² Cornell
 * box took 92 k page faults rather than 115 k (perf stat). */
static size_t reg_tile_floats(void)
{
    return 2 * (REG_C + 1) * (size_t)(REG_W + 2 * REG_R) * (size_t)(MC_TILE + 2 * REG_R);
}

/* Every pixel's fit is evaluated over its whole window and the fits that cover a pixel are
 * averaged (collaborative filtering), so the fits of neighbouring pixels, whose windows nearly
 * coincide, say nearly the same there: fitting only the pixels of a lattice of spacing LATTICE
 * (both coordinates multiples of it) gives each pixel the fits of the lattice points within its
 * window, about (2R + 1)²/4 of them, at a quarter of the cost. A pixel whose lattice fits
 * weigh little where it is (a firefly, an edge's thin side: the weights follow the colour's
 * patches) gets its own fit in a second pass, as every pixel has in the full method: those
 * whose weight summed over the fits covering it is below COVER_MIN for either bandwidth (a
 * fit's own pixel has weight 1). Measured by make bench-denoise and callgrind: see the README's
 * denoiser section. */
enum { LATTICE = 2 };
#define COVER_MIN 3.0

static int on_lattice(int x, int y) { return x % LATTICE == 0 && y % LATTICE == 0; }

/* Whether pixel (x, y) is fitted in this pass. */
static int fitted(const struct reg_job *j, int x, int y)
{
    return j->need ? j->need[(size_t)y * (size_t)j->pl->width + (size_t)x] : on_lattice(x, y);
}

/* One pixel's window, column by column (the columns of the design matrix: 1, the offset, and each
 * feature's difference from the pixel's own, so that the fit is centred on it), the colours and
 * the probe,
 * per bandwidth, the weights, the weighted columns and the fit. */
struct window {
    float x[MAX_DIM][NWP], y[REG_C][NWP], w[2][NWP], wx[2][MAX_DIM][NWP], fit[2][REG_C][NWP];
};

/* The columns every window shares: 1 and the offset, and 0 in the padding. */
static void window_init(struct window *v)
{
    int o;
    memset(v, 0, sizeof *v);
    for (o = 0; o < NW; o++) {
        v->x[0][o] = 1.0f;
        v->x[1][o] = (float)(o % SIDE - REG_R);
        v->x[2][o] = (float)(o / SIDE - REG_R);
    }
}

/* A feature differing from the pixel's own by less than FEATURE_EPS of it is the rounding of the
 * prefilter's weighted means (their float products and sums, ~1e-7 each), not a difference of
 * the surfaces: as a column of the design matrix it would pass the factorisation's test (ldl.h), which is relative
 * to the column's own scale, and the regression would fit the colour's noise to it. Measured by
 * make bench-denoise: with NL-means' sums in float (nlm_tile_body), the Cornell box's error rose
 * 0.1-2% without the cut and not at all with it (with double sums too, within 0.1%). */
#define FEATURE_EPS 1e-5f

/* Pixel (x, y)'s window (stride: a padded row), its distances dist (NWP of them, from
 * patch_dist with k = 1) turned into each bandwidth's weights, 0 outside the image: row by row
 * of the window, each a run of contiguous floats of the padded planes. */
static MC_ALWAYS_INLINE void window_fill(const struct reg_job *j, int x, int y, const float *dist,
                                      struct window *v)
{
    const int R = REG_R, width = j->pl->width, height = j->pl->height;
    size_t stride = (size_t)width + 2 * PAD, p = (size_t)(y + PAD) * stride + (size_t)(x + PAD);
    int lo = clampi(R - x, 0, SIDE), hi = clampi(width - x + R, 0, SIDE); /* inside: [lo, hi) */
    int a, c, k, o, i, dy;
    for (o = 0, dy = -R; dy <= R; dy++, o += SIDE) {
        size_t q = p + (size_t)((ptrdiff_t)dy * (ptrdiff_t)stride - R);
        int row_in = y + dy >= 0 && y + dy < height;
        for (a = 0; a < j->nf; a++) {
            const float *fq = j->feat[a] + q;
            float fp = j->feat[a][p], *xa = v->x[3 + a] + o;
            for (i = 0; i < SIDE; i++) {
                float diff = fq[i] - fp;
                xa[i] = fabsf(diff) > FEATURE_EPS * fabsf(fp) ? diff : 0.0f;
            }
        }
        for (c = 0; c < REG_C; c++)
            for (i = 0; i < SIDE; i++)
                v->y[c][o + i] = j->img[(q + (size_t)i) * REG_C + (size_t)c];
        for (k = 0; k < 2; k++) {
            float *wk = v->w[k] + o;
            for (i = 0; i < SIDE; i++)
                wk[i] = dist[o + i] / (reg_k[k] * reg_k[k]);
            for (i = 0; i < SIDE; i++)
                if (!row_in || i < lo || i >= hi)
                    wk[i] = DIST_CLAMP;
        }
    }
    for (k = 0; k < 2; k++) {
        for (o = NW; o < NWP; o++)
            v->w[k][o] = DIST_CLAMP;
        exp_neg(v->w[k], NWP);
        if (v->w[k][R * SIDE + R] < MIN_WEIGHT)
            v->w[k][R * SIDE + R] = MIN_WEIGHT;
    }
}

/* The weighted least squares of the window v for both bandwidths: X^T W X into M[k] (nd × nd)
 * and X^T W Y into B[k] (nd × REG_C), for mc_ldl_solve. Row a of both at once: its weighted column against
 * the columns a..nd-1 and the colours, DOT_BLOCK at a time. */
static MC_ALWAYS_INLINE void normal_equations(struct window *v, int nd, double M[2][MAX_DIM * MAX_DIM],
                                           double B[2][MAX_DIM * REG_C])
{
    const float *col[MAX_DIM + REG_C];
    double r[2][DOT_BLOCK];
    int a, b, c, k, o, n, i;
    for (k = 0; k < 2; k++)
        for (a = 0; a < nd; a++)
            for (o = 0; o < NWP; o++)
                v->wx[k][a][o] = v->w[k][o] * v->x[a][o];
    for (a = 0; a < nd; a++) {
        for (n = 0, b = a; b < nd; b++)
            col[n++] = v->x[b];
        for (c = 0; c < REG_C; c++)
            col[n++] = v->y[c];
        for (i = 0; i < n; i += DOT_BLOCK) {
            const float *wa0 = v->wx[0][a], *wa1 = v->wx[1][a];
            switch (n - i) {
            case 1: dots(wa0, wa1, col + i, 1, r); break;
            case 2: dots(wa0, wa1, col + i, 2, r); break;
            case 3: dots(wa0, wa1, col + i, 3, r); break;
            default: dots(wa0, wa1, col + i, DOT_BLOCK, r); break;
            }
            for (b = i; b < n && b < i + DOT_BLOCK; b++)
                for (k = 0; k < 2; k++) {
                    if (a + b < nd)
                        M[k][a * nd + a + b] = M[k][(a + b) * nd + a] = r[k][b - i];
                    else
                        B[k][a * REG_C + b - (nd - a)] = r[k][b - i];
                }
        }
    }
}

/* Each bandwidth's local fit, coefficients beta[k] (nd × REG_C), evaluated over the window into
 * v->fit; the sums over the columns in column order, the eight of a LANES-wide run spelt out so
 * that they stay in registers. */
static MC_ALWAYS_INLINE void fit_eval(struct window *v, int nd, float beta[2][MAX_DIM * REG_C])
{
    int o, a, l;
    for (o = 0; o < NWP; o += LANES) {
        /* The first column's products start the sums (not zeros, which GCC stores to memory
         * with rep stos and reads back: 3.5% of the regression's time, perf); 0 + x·b is x·b. */
        float f[8][LANES];
        const float *x0 = v->x[0] + o;
        for (l = 0; l < LANES; l++) {
            f[0][l] = x0[l] * beta[0][0];
            f[1][l] = x0[l] * beta[0][1];
            f[2][l] = x0[l] * beta[0][2];
            f[3][l] = x0[l] * beta[0][3];
            f[4][l] = x0[l] * beta[1][0];
            f[5][l] = x0[l] * beta[1][1];
            f[6][l] = x0[l] * beta[1][2];
            f[7][l] = x0[l] * beta[1][3];
        }
        for (a = 1; a < nd; a++) {
            const float *xa = v->x[a] + o, *b0 = beta[0] + a * REG_C, *b1 = beta[1] + a * REG_C;
            for (l = 0; l < LANES; l++) {
                f[0][l] += xa[l] * b0[0];
                f[1][l] += xa[l] * b0[1];
                f[2][l] += xa[l] * b0[2];
                f[3][l] += xa[l] * b0[3];
                f[4][l] += xa[l] * b1[0];
                f[5][l] += xa[l] * b1[1];
                f[6][l] += xa[l] * b1[2];
                f[7][l] += xa[l] * b1[3];
            }
        }
        for (l = 0; l < LANES; l++) {
            v->fit[0][0][o + l] = f[0][l];
            v->fit[0][1][o + l] = f[1][l];
            v->fit[0][2][o + l] = f[2][l];
            v->fit[0][3][o + l] = f[3][l];
            v->fit[1][0][o + l] = f[4][l];
            v->fit[1][1][o + l] = f[5][l];
            v->fit[1][2][o + l] = f[6][l];
            v->fit[1][3][o + l] = f[7][l];
        }
    }
}

/* The offsets whose distances reg_tile_body computes for the whole tile before it copies them into
 * the fitted pixels' windows: eight floats of a window a store rather than one float a cache line
 * (the copy had been 2.6% of the regression's samples, perf). */
enum { OFF_BLOCK = 8 };

static MC_ALWAYS_INLINE void reg_tile_body(void *ctx, struct tile_worker *w, int x0, int y0, int x1,
                                        int y1)
{
    struct reg_job *j = ctx;
    const int R = REG_R, nd = 3 + j->nf;
    int width = j->pl->width, tw = x1 - x0, th = y1 - y0;
    int aw = tw + 2 * R, dx, dy, x, y, c, a, o, k, i, nfit = 0;
    size_t np = (size_t)tw * th, npl = (size_t)aw * (size_t)(th + 2 * R);
    size_t ti = (size_t)(y0 / MC_TILE) * (size_t)reg_tiles_across(j->pl) + (size_t)(x0 / REG_W);
    struct row_mask rows;
    int fit[MC_TILE * REG_W]; /* the fitted pixels, tile-local indices in row-major order */
    float *dist, *acc;
    struct window *v;
    (void)w;
    memset(rows.out, 0, sizeof rows.out);
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++)
            if (fitted(j, x, y)) {
                fit[nfit++] = (y - y0) * tw + (x - x0);
                rows.out[y - y0] = 1;
            }
    if (nfit == 0)
        return;
    row_mask_reach(&rows, th, j->g->f);
    /* The fitted pixels' window distances, NWP each, then OFF_BLOCK tiles of an offset's each and
     * the patches' scratch. */
    dist = mc_malloc(((size_t)nfit * NWP + OFF_BLOCK * np + scratch_floats(j->g, REG_W))
                     * sizeof *dist);
    acc = j->acc + ti * reg_tile_floats();
    v = mc_malloc(sizeof *v);
    if (!dist || !v) {
        j->pl->status = MCRT_ERR_NOMEM;
        free(dist);
        free(v);
        return;
    }
    j->used[ti] = 1;
    window_init(v);
    /* Every offset's distances for the tile's rows with fitted pixels, then per fitted pixel
     * its window's, OFF_BLOCK offsets at a time. */
    for (o = 0; o < NW; o += OFF_BLOCK) {
        int nb = NW - o < OFF_BLOCK ? NW - o : OFF_BLOCK, b;
        float *t = dist + (size_t)nfit * NWP;
        for (b = 0; b < nb; b++)
            patch_dist(j->g, width, x0, y0, x1, y1, &rows, (o + b) % SIDE - R, (o + b) / SIDE - R,
                       t + (size_t)b * np, t + OFF_BLOCK * np);
        for (i = 0; i < nfit; i++) {
            float *di = dist + (size_t)i * NWP + (size_t)o;
            for (b = 0; b < nb; b++)
                di[b] = t[(size_t)b * np + (size_t)fit[i]];
        }
    }
    for (i = 0; i < nfit; i++) {
        double M[2][MAX_DIM * MAX_DIM], B[2][MAX_DIM * REG_C];
        float beta[2][MAX_DIM * REG_C];
        x = x0 + fit[i] % tw;
        y = y0 + fit[i] / tw;
        window_fill(j, x, y, dist + (size_t)i * NWP, v);
        normal_equations(v, nd, M, B);
        for (k = 0; k < 2; k++) {
            double D[MAX_DIM];
            mc_ldl_factor(M[k], nd, D);
            mc_ldl_solve(M[k], D, nd, B[k], REG_C);
            for (a = 0; a < nd * REG_C; a++)
                beta[k][a] = (float)B[k][a];
        }
        /* The local fit evaluated over the window, weighted by the same weights (the
         * collaborative step): every pixel is the mean of the fits that cover it. */
        fit_eval(v, nd, beta);
        for (k = 0; k < 2; k++) {
            const float *wk = v->w[k];
            for (o = 0, dy = -R; dy <= R; dy++, o += SIDE) {
                float *t = acc + (size_t)k * (REG_C + 1) * npl
                           + (size_t)(y - y0 + R + dy) * aw + (size_t)(x - x0);
                for (c = 0; c < REG_C; c++)
                    for (dx = 0; dx < SIDE; dx++)
                        t[c * npl + (size_t)dx] += wk[o + dx] * v->fit[k][c][o + dx];
                for (dx = 0; dx < SIDE; dx++)
                    t[REG_C * npl + (size_t)dx] += wk[o + dx];
            }
        }
    }
    free(dist);
    free(v);
}

/* A band of MC_TILE rows (run's bands), as tiles REG_W wide: wider than the runner's tiles, so
 * that less of the patches' and the windows' reach around a tile is computed and summed again. */
BAND_FUNCTIONS(reg_band, reg_tile_body, struct reg_job, REG_W)

/* The tiles' overlapping sums of j->acc added into sum (per bandwidth k and channel c, R, G, B,
 * probe and weight, a plane (k·(REG_C + 1) + c) of the image's pixels), in tile order whatever
 * the threads' order was, and the tiles' sums zeroed. */
static void merge_tiles(const struct pool *pl, const struct reg_job *j, double *sum)
{
    int nty = (pl->height + MC_TILE - 1) / MC_TILE, ntx = reg_tiles_across(pl), tx, ty, x, y, p;
    size_t n = (size_t)pl->width * (size_t)pl->height;
    for (ty = 0; ty < nty; ty++)
        for (tx = 0; tx < ntx; tx++) {
            size_t ti = (size_t)ty * (size_t)ntx + (size_t)tx;
            float *acc = j->acc + ti * reg_tile_floats();
            int x0 = tx * REG_W - REG_R, y0 = ty * MC_TILE - REG_R;
            int aw = (tx * REG_W + REG_W > pl->width ? pl->width - tx * REG_W : REG_W)
                     + 2 * REG_R;
            int ah = (ty * MC_TILE + MC_TILE > pl->height ? pl->height - ty * MC_TILE : MC_TILE)
                     + 2 * REG_R;
            /* the part of the tile's sums inside the image: [xa, xb) × [ya, yb) */
            int xa = x0 < 0 ? -x0 : 0, xb = x0 + aw > pl->width ? pl->width - x0 : aw;
            int ya = y0 < 0 ? -y0 : 0, yb = y0 + ah > pl->height ? pl->height - y0 : ah;
            size_t npl = (size_t)aw * (size_t)ah;
            if (!j->used[ti])
                continue;
            for (p = 0; p < 2 * (REG_C + 1); p++)
                for (y = ya; y < yb; y++) {
                    const float *a = acc + (size_t)p * npl + (size_t)y * aw;
                    double *o = sum + (size_t)p * n + (size_t)(y0 + y) * pl->width + x0;
                    for (x = xa; x < xb; x++)
                        o[x] += a[x];
                }
            memset(acc, 0, 2 * (REG_C + 1) * npl * sizeof *acc);
            j->used[ti] = 0;
        }
}

/* The leverage probe of half h at pixel i (of n): a sign, +1 or -1 with probability 1/2 each,
 * from a hash of i + h·n, so that the halves' probes are independent (regress). */
static float probe(size_t i, int h, size_t n)
{
    return mc_hash64((uint64_t)(i + (size_t)h * n)) >> 63 ? 1.0f : -1.0f;
}

/* Each half h's colour col[h] (3 channels, not padded) regressed on the features feat[h]
 * (padded) with weights from guide g[h] (k = 1), for both bandwidths: out[h][0] for reg_k[0],
 * out[h][1] for reg_k[1]. The lattice's fits, then those of the pixels they cover too little
 * (LATTICE). The halves one after the other, through the same buffers.
 *
 * The result is linear in the colour: out[k] = L_k·col, each row of L_k the weights with which
 * the fits covering a pixel combine the window's colours, all fixed by g and the features. The
 * error estimate (mse_estimate) needs L_k's diagonal, the weight of a pixel's own colour in its
 * result. It is estimated as Bekas, Kokiopoulou and Saad do ("An estimator for the diagonal of a
 * matrix", Appl. Numer. Math. 57, 2007), from the same regression of a fourth channel, a probe b
 * of independent random signs: E[b_i·(L b)_i] = Σ_j L_ij E[b_i b_j] = L_ii. Into lev[k], one
 * plane each: unbiased, with a spread of (Σ_{j≠i} L_ij²)^½ per pixel, which sums of many pixels
 * average out. A fourth column of the normal equations' right side costs far less than a
 * second regression or each fit's own leverages (x_oᵀ M⁻¹ x_o for each window pixel). Each half
 * has its own probe: the halves' L are nearly alike, so with one probe for both their leverages'
 * spreads had coincided and their mean in the estimate kept all of it; with two independent ones
 * one render's estimate spread over 8 probe patterns by 4-29% of itself rather than 6-42% (four
 * renders of make bench-denoise's inputs, three of them lower; the denoised image unchanged). */
static mcrt_status regress(struct pool *pl, const struct guide g[2], const float *const col[2],
                           const float *const *const feat[2], int nf, float *const out[2][2],
                           float *const lev[2][2], mc_diag *d)
{
    int nty = (pl->height + MC_TILE - 1) / MC_TILE, ntiles = reg_tiles_across(pl) * nty, c, k, h;
    size_t i, n = (size_t)pl->width * (size_t)pl->height;
    size_t np = (size_t)(pl->width + 2 * PAD) * (size_t)(pl->height + 2 * PAD);
    struct reg_job j;
    mcrt_status st = MCRT_OK;
    unsigned char *need = mc_malloc(n);
    double *sum = mc_malloc(n * 2 * (REG_C + 1) * sizeof *sum);
    float *img = mc_malloc((np + n) * REG_C * sizeof *img), *in = img + np * REG_C;
    j.pl = pl;
    j.img = img;
    j.nf = nf;
    j.acc = mc_calloc((size_t)ntiles * reg_tile_floats(), sizeof *j.acc);
    j.used = mc_calloc((size_t)ntiles, 1);
    if (!j.acc || !j.used || !sum || !need || !img) {
        free(j.acc);
        free(j.used);
        free(sum);
        free(need);
        free(img);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser");
    }
    for (h = 0; h < 2 && st == MCRT_OK; h++) {
        j.g = &g[h];
        j.feat = feat[h];
        j.need = NULL;
        memset(sum, 0, n * 2 * (REG_C + 1) * sizeof *sum);
        for (i = 0; i < n; i++) {
            for (c = 0; c < 3; c++)
                in[i * REG_C + (size_t)c] = col[h][i * 3 + (size_t)c];
            in[i * REG_C + 3] = probe(i, h, n);
        }
        pad_copy(in, REG_C, 0, pl->width, pl->height, 1.0f, img);
        st = run(pl, 1, TILE_FN(reg_band), &j, d);
        merge_tiles(pl, &j, sum);
        for (i = 0; i < n; i++) {
            int x = (int)(i % (size_t)pl->width), y = (int)(i / (size_t)pl->width);
            need[i] = !on_lattice(x, y) && (sum[REG_C * n + i] < COVER_MIN
                                            || sum[(2 * REG_C + 1) * n + i] < COVER_MIN);
        }
        j.need = need;
        if (st == MCRT_OK)
            st = run(pl, 1, TILE_FN(reg_band), &j, d);
        merge_tiles(pl, &j, sum);
        for (i = 0; i < n; i++)
            for (k = 0; k < 2; k++) {
                const double *s = sum + (size_t)k * (REG_C + 1) * n + i, wsum = s[REG_C * n];
                for (c = 0; c < 3; c++)
                    out[h][k][i * 3 + (size_t)c] = (float)(s[(size_t)c * n] / wsum);
                lev[h][k][i] = (float)(s[3 * n] / wsum) * in[i * REG_C + 3]; /* the probe */
            }
    }
    free(j.acc);
    free(j.used);
    free(sum);
    free(need);
    free(img);
    return st;
}

/* ---- The pipeline ---- */

static float sq(float x) { return x * x; }

/* The (2r + 1)² box mean of v (nc channels), the image's edge pixels repeated, through tmp (as
 * large as v): variance estimates of one degree of freedom each made steadier for the weights
 * (the error estimates use the unsmoothed ones, which are unbiased). */
static void box_mean(const float *v, int nc, int width, int height, int r, float *tmp, float *out)
{
    size_t rw = (size_t)width * (size_t)nc, j;
    int x, y, c, i, in0 = r < width ? r : width, in1 = width - r > in0 ? width - r : in0;
    float norm = 1.0f / (float)((2 * r + 1) * (2 * r + 1));
    /* Along the rows: the pixels [in0, in1) reach no edge, the others repeat it. */
    for (y = 0; y < height; y++) {
        const float *row = v + (size_t)y * rw;
        float *t = tmp + (size_t)y * rw;
        for (x = 0; x < width; x++) {
            if (x == in0 && in1 > in0) {
                box_sum_taps(row + (size_t)(in0 - r) * nc, (size_t)nc, 2 * r + 1,
                             (in1 - in0) * nc, t + (size_t)in0 * nc);
                x = in1 - 1;
                continue;
            }
            for (c = 0; c < nc; c++) {
                float s = 0.0f;
                for (i = -r; i <= r; i++)
                    s += row[(size_t)clampi(x + i, 0, width - 1) * nc + (size_t)c];
                t[(size_t)x * nc + (size_t)c] = s;
            }
        }
    }
    /* Along the columns, the rows' sums added row by row in the same order. */
    for (y = 0; y < height; y++) {
        float *o = out + (size_t)y * rw;
        for (j = 0; j < rw; j++)
            o[j] = 0.0f;
        for (i = -r; i <= r; i++) {
            const float *t = tmp + (size_t)clampi(y + i, 0, height - 1) * rw;
            for (j = 0; j < rw; j++)
                o[j] += t[j];
        }
        for (j = 0; j < rw; j++)
            o[j] *= norm;
    }
}

/* Each firefly pixel's three channels of img set to its window's variance (with_var) or to 0. */
static void set_fireflies(float *img, const struct firefly *ff, int nff, int with_var)
{
    int i;
    for (i = 0; i < nff; i++) {
        size_t p = 3 * (size_t)ff[i].pixel;
        img[p] = img[p + 1] = img[p + 2] = with_var ? ff[i].var : 0.0f;
    }
}

/* Whether pixel i's halves' own variances are those of the colour filtered: not where either
 * half has emission, which is taken out of the colour (nfor.h) but not out of those variances. */
static int own_pixel(const struct nfor_input *in, size_t i)
{
    int h, c;
    for (h = 0; h < 2 && in->emission[0]; h++)
        for (c = 0; c < 3; c++)
            if (in->emission[h][3 * i + (size_t)c] != 0.0f)
                return 0;
    return 1;
}

/* Each half's variance from its own samples (in->color_var), calibrated by OWN_R's local ratio,
 * into own[0] and own[1]; where the pixel has emission or a firefly, var, the pixel's (A − B)²/2
 * after the fireflies' split (0 at a firefly). Through the four images of scratch and tmp. */
static void own_variance(const struct nfor_input *in, const float *var, const struct firefly *ff,
                         int nff, float *const scratch[4], float *tmp, float *const own[2])
{
    float *num = scratch[0], *den = scratch[1], *snum = scratch[2], *sden = scratch[3];
    int w = in->width, h = in->height, half, c;
    size_t n = (size_t)w * (size_t)h, i, k;
    for (i = 0; i < n; i++) {
        int o = own_pixel(in, i);
        for (c = 0, k = 3 * i; c < 3; c++, k++) {
            num[k] = o ? var[k] : 0.0f;
            den[k] = o ? 0.5f * (in->color_var[0][k] + in->color_var[1][k]) : 0.0f;
        }
    }
    set_fireflies(num, ff, nff, 0);
    set_fireflies(den, ff, nff, 0);
    box_mean(num, 3, w, h, OWN_R, tmp, snum);
    box_mean(den, 3, w, h, OWN_R, tmp, sden);
    for (i = 0; i < n; i++) {
        int o = own_pixel(in, i);
        for (half = 0; half < 2; half++)
            for (c = 0, k = 3 * i; c < 3; c++, k++)
                own[half][k] = !o ? var[k]
                               : (sden[k] > 0.0f ? snum[k] / sden[k] : 1.0f)
                                     * in->color_var[half][k];
    }
    set_fireflies(own[0], ff, nff, 0); /* var's there */
    set_fireflies(own[1], ff, nff, 0);
}

/* The own variances own[0] and own[1] of the pixels on a colour edge of mean (the halves' mean)
 * scaled by the ratio of the sums there of var, the halves' (A − B)²/2, and of the own variances'
 * mean (EDGE_GRADIENT); a pixel with emission keeps its var (own_pixel). Through box and tmp,
 * W·H·3 floats each. */
static void edge_calibrate(const struct nfor_input *in, const float *mean, const float *var,
                           float *box, float *tmp, float *const own[2])
{
    int w = in->width, h = in->height, x, y, c;
    size_t row = 3 * (size_t)w, n3 = 3 * (size_t)w * (size_t)h, k;
    double halves = 0.0, owns = 0.0;
    float ratio;
    box_mean(mean, 3, w, h, 1, tmp, box);
    /* tmp: 1 on an edge, else 0 */
    memset(tmp, 0, n3 * sizeof *tmp);
    for (y = 1; y < h - 1; y++)
        for (x = 1; x < w - 1; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (!own_pixel(in, i))
                continue;
            for (c = 0, k = 3 * i; c < 3; c++, k++) {
                float g = fabsf(box[k + 3] - box[k - 3]) + fabsf(box[k + row] - box[k - row]);
                float m = fabsf(box[k]) > 1e-3f ? fabsf(box[k]) : 1e-3f;
                if (g < EDGE_GRADIENT * m)
                    continue;
                tmp[k] = 1.0f;
                halves += var[k];
                owns += 0.5 * ((double)own[0][k] + own[1][k]);
            }
        }
    if (!(owns > 0.0) || !isfinite(halves / owns))
        return;
    ratio = (float)(halves / owns);
    for (k = 0; k < n3; k++)
        if (tmp[k] != 0.0f) {
            own[0][k] *= ratio;
            own[1][k] *= ratio;
        }
}

/* The MSE of D = (fa + fb)/2 per pixel and channel (nfor.h, step 4). fa is A regressed with B's
 * guides, fa = L_a·A with L_a fixed by B and the features, so that with A = μ + n (the noise n
 * independent of L_a, of variance Var(A) in each pixel, independent between pixels)
 *     E[(A − fa)²] = Var(A) − 2·L_a,ii·Var(A) + MSE(fa),
 * the middle term the covariance of A's noise with its own share of fa. In the first term Var(A)
 * is estimated by the pixel's (A − B)²/2 (var_half), unbiased: a term as large as Var(A), where
 * MSE(fa) is a few percent of it, wants no bias at all. L_a,ii is estimated by la (regress). In
 * the covariance term Var(A) must not come from B, though: la comes from B's guides, and where B
 * is far from μ its patch matches little, A's regression leans on the pixel itself and la is
 * large, so that la and (A − B)²/2 grow together and their product's mean is more than the
 * product of their means (cornell-spheres at 16 spp: 1.7 times the true error over 10 seeds).
 * A's own variance va (own_variance) is independent of B. It replaces (A − fb)², fb being B
 * regressed with A's guides, which did not grow with B's errors but did with A's: where A is far
 * from μ, A's patch matches little and fb leans on B, so that (A − fb)² was (A − B)² there, and
 * on the Cornell box at 160² and 16 spp, with the candidate of bandwidth 0.5 alone, the
 * covariance term read 1.20 times its true value over 6 seeds, and the estimate of fa's error
 * 1.66 times the truth (1.14 with va). fb alike; then
 *     MSE(D) = [MSE(fa) + MSE(fb)]/2 − (fa − fb)²/4,
 * exact from ((a + b)/2)² = (a² + b²)/2 − ((a − b)/2)². NFOR's own estimate, (B − fa)² − Var(B),
 * leaves out the covariance of B with fa, which B's guides make large: 0.13-0.15 of the true
 * error on the Cornell box at 16 and 64 spp (10 seeds). One image's estimate is noisy, though:
 * each pixel's term is about the product of its halves' noises, whose spread is Var(A) where the
 * error is a few percent of it (README). */
static void mse_estimate(const float *A, const float *B, const float *fa, const float *fb,
                         const float *la, const float *lb, const float *var_half,
                         const float *va, const float *vb, size_t n3, float *out)
{
    size_t i;
    for (i = 0; i < n3; i++)
        out[i] = 0.5f * (sq(A[i] - fa[i]) - var_half[i] + 2.0f * va[i] * la[i]
                         + sq(B[i] - fb[i]) - var_half[i] + 2.0f * vb[i] * lb[i])
                 - 0.25f * sq(fa[i] - fb[i]);
}

mcrt_status mc_nfor_denoise(const struct nfor_input *in, int threads, float *rgb, float *mse,
                            float *mse_var, float *mean_sq, mc_diag *d)
{
    int w = in->width, h = in->height, nf = in->nfeatures, f, half;
    size_t n = (size_t)w * (size_t)h, n3 = n * 3, i;
    const float *A = in->color[0], *B = in->color[1];
    const float *const *E = in->emission;
    /* One block of floats: 3-channel images, then feature planes. */
    enum {
        VAR, VARS, VARG, MEAN,
        OWN,                     /* 2: each half's own variance, calibrated (own_variance) */
        VG = OWN + 2,            /* 2: each half's, averaged for the weights */
        CAND,                    /* A's first candidate, B's, A's second, B's */
        ERR = CAND + 4,          /* 4 images: the error maps' differences, then the results */
        SMOOTH = ERR + 4,        /* 2: the differences smoothed */
        SEL = SMOOTH + 2,        /* 2: the choices, 6 channels */
        LEV = SEL + 2,           /* 2: the four candidates' leverage planes */
        TMP = LEV + 2, TMP2, CA, CB, EM, EMV, NIMG
    };
    /* Then the padded guides (pad_copy), 3 channels each: the halves, each half's variance, the
     * variance of the mean, the mean. */
    enum { PA, PB, PVARA, PVARB, PVARM, PMEAN, NPAD };
    size_t np3 = (size_t)(w + 2 * PAD) * (size_t)(h + 2 * PAD) * 3;
    size_t np1 = np3 / 3;
    float *buf = mc_malloc((n3 * NIMG + n * (size_t)(2 * nf + 2) + np3 * NPAD
                            + np1 * (size_t)(2 * nf)) * sizeof *buf);
    float *img[NIMG], *pre[2][MC_NFOR_MAX_FEATURES], *fvar, *fvars, *pad[NPAD];
    const float *cpre[2][MC_NFOR_MAX_FEATURES]; /* the prefiltered features, padded */
    struct pool pl;
    struct guide g;
    struct firefly *ff = NULL;
    int nff = 0;
    mcrt_status st = MCRT_OK;
    if (!buf)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser (%dx%d)", w, h);
    for (i = 0; i < NIMG; i++)
        img[i] = buf + i * n3;
    for (f = 0; f < nf; f++)
        for (half = 0; half < 2; half++) {
            pre[half][f] = buf + NIMG * n3 + (size_t)(2 * f + half) * n;
            cpre[half][f] = buf + NIMG * n3 + n * (size_t)(2 * nf + 2) + np3 * NPAD
                            + np1 * (size_t)(2 * f + half);
        }
    fvar = buf + NIMG * n3 + (size_t)(2 * nf) * n;
    fvars = fvar + n;
    for (i = 0; i < NPAD; i++)
        pad[i] = fvars + n + i * np3;
    pl.width = w;
    pl.height = h;
    pl.threads = threads;

    /* The halves to filter: the colour, less the emission. */
    for (i = 0; i < n3; i++) {
        img[CA][i] = E[0] ? A[i] - E[0][i] : A[i];
        img[CB][i] = E[0] ? B[i] - E[1][i] : B[i];
    }
    A = img[CA];
    B = img[CB];

    /* The fireflies' excesses taken out (firefly.h), found by the channel mean of each pixel's
     * (A − B)²/2 against its REG_VAR_R box's. */
    {
        float *v = img[TMP], *vbox = v + n, *tmp = vbox + n, *m = img[VAR], *mbox = m + n;
        for (i = 0; i < n; i++) {
            v[i] = (sq(A[3 * i] - B[3 * i]) + sq(A[3 * i + 1] - B[3 * i + 1])
                    + sq(A[3 * i + 2] - B[3 * i + 2])) * (0.5f / 3.0f);
            m[i] = (A[3 * i] + B[3 * i] + A[3 * i + 1] + B[3 * i + 1] + A[3 * i + 2]
                    + B[3 * i + 2]) / 6.0f;
        }
        box_mean(v, 1, w, h, REG_VAR_R, tmp, vbox);
        box_mean(m, 1, w, h, REG_VAR_R, tmp, mbox);
        if (mc_firefly_split(img[CA], img[CB], v, vbox, mbox,
                             (2 * REG_VAR_R + 1) * (2 * REG_VAR_R + 1), w, h, &ff, &nff) != 0) {
            free(buf);
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser (%dx%d)", w, h);
        }
    }

    /* The variance of one half per pixel, (A − B)²/2 (film.h), and of the mean, a quarter. */
    for (i = 0; i < n3; i++) {
        img[VAR][i] = 0.5f * sq(A[i] - B[i]);
        img[MEAN][i] = 0.5f * (A[i] + B[i]);
    }
    /* A firefly's halves now agree, but the guides' variance there is its window's: with 0 the
     * weights around a caustic's fireflies grew sharper and filtered less (cornell-spheres at 16
     * spp, make bench-denoise, fireflies found at a level of 4: 1.17e-2 against 1.09e-2). The error
     * estimate keeps the pixel's own (A − B)²/2, 0. */
    set_fireflies(img[VAR], ff, nff, 1);
    box_mean(img[VAR], 3, w, h, 1, img[TMP], img[VARS]);
    box_mean(img[VAR], 3, w, h, REG_VAR_R, img[TMP], img[VARG]);
    set_fireflies(img[VAR], ff, nff, 0);
    own_variance(in, img[VAR], ff, nff, img + CAND, img[TMP], img + OWN);
    /* The weights' variance of each half: its own over the REG_VAR_R box, a firefly's the
     * window's, as above. */
    for (half = 0; half < 2; half++) {
        memcpy(img[TMP2], img[OWN + half], n3 * sizeof *img[TMP2]);
        set_fireflies(img[TMP2], ff, nff, 1);
        box_mean(img[TMP2], 3, w, h, REG_VAR_R, img[TMP], img[VG + half]);
    }
    pad_copy(A, 3, 1, w, h, 1.0f, pad[PA]);
    pad_copy(B, 3, 1, w, h, 1.0f, pad[PB]);

    /* 1. Cross prefiltering of the features (NFOR §5.1): A's feature with weights from B's, whose
     * variance, that of a half, is (f_A − f_B)²/2. */
    if (nf > 0) {
        /* All the features at once, interleaved, each channel with its own weights. */
        float *pb = mc_malloc((n * (size_t)nf * 4 + np1 * (size_t)nf * 2) * sizeof *pb);
        float *fa = pb, *fb = fa + n * nf, *fv = fb + n * nf, *out = fv + n * nf;
        float *gimg = out + n * nf, *gvar = gimg + np1 * nf;
        if (!pb) {
            free(buf);
            free(ff);
            return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser (%dx%d)", w, h);
        }
        for (f = 0; f < nf; f++) {
            for (i = 0; i < n; i++) {
                fa[i * nf + f] = in->feature[0][f][i];
                fb[i * nf + f] = in->feature[1][f][i];
                fvar[i] = 0.5f * sq(in->feature[0][f][i] - in->feature[1][f][i]);
            }
            box_mean(fvar, 1, w, h, 1, img[TMP], fvars);
            for (i = 0; i < n; i++)
                fv[i * nf + f] = fvars[i];
        }
        pad_copy(fv, nf, 0, w, h, 1.0f, gvar);
        for (half = 0; half < 2 && st == MCRT_OK; half++) {
            pad_copy(half ? fa : fb, nf, 0, w, h, 1.0f, gimg);
            g.img = gimg;
            g.var = gvar;
            g.gc = nf;
            g.f = PRE_F;
            g.k = PRE_K;
            g.each = 1;
            st = nlm(&pl, &g, half ? fb : fa, nf, PRE_R, out, d);
            for (f = 0; f < nf; f++) {
                for (i = 0; i < n; i++)
                    pre[half][f][i] = out[i * nf + f];
                pad_copy(pre[half][f], 1, 0, w, h, 1.0f, (float *)cpre[half][f]);
            }
        }
        free(pb);
    }
    g.each = 0;

    /* 2. Each half regressed on the other half's features with the other half's weights, for
     * two bandwidths, with the leverages of the results (regress); 3. the choice between them. */
    pad_copy(img[VG], 3, 1, w, h, 1.0f, pad[PVARA]);
    pad_copy(img[VG + 1], 3, 1, w, h, 1.0f, pad[PVARB]);
    pad_copy(img[VARS], 3, 1, w, h, 0.5f, pad[PVARM]);
    pad_copy(img[MEAN], 3, 1, w, h, 1.0f, pad[PMEAN]);
    g.gc = 3;
    g.f = REG_F;
    g.k = 1.0f; /* the distances, to which each bandwidth applies (regress) */
    if (st == MCRT_OK) {
        /* A on B's guide and features, B on A's. */
        struct guide rg[2];
        const float *const rc[2] = {A, B};
        const float *const *const rf[2] = {cpre[1], cpre[0]};
        float *const cand[2][2] = {{img[CAND], img[CAND + 2]}, {img[CAND + 1], img[CAND + 3]}};
        float *const lev[2][2] = {{img[LEV], img[LEV] + n}, {img[LEV] + 2 * n, img[LEV] + 3 * n}};
        rg[0] = rg[1] = g;
        rg[0].img = pad[PB];
        rg[0].var = pad[PVARB];
        rg[1].img = pad[PA];
        rg[1].var = pad[PVARA];
        st = regress(&pl, rg, rc, rf, nf, cand, lev, d);
    }
    if (st == MCRT_OK) {
        /* Each half's candidates are chosen between by their errors estimated from the other
         * half alone (NFOR §5.3): E[(B − Â_k)²] = MSE(Â_k) + Var(B) up to the covariance of B
         * and Â_k, the same for both k. Not by the estimate of step 4: its terms (A − Â_k)² are
         * the very ones it sums, so that a choice by them would pick, pixel by pixel, the
         * candidate whose error A's noise happens to hide, and the estimate of the result would
         * read low (on the Cornell box at 16 spp, 0.53 of the truth over 10 seeds, against
         * 0.71 chosen this way). Only the sign of the difference of the two candidates' errors
         * matters, and NL-means, a weighted mean, smooths a difference as it does each term: the
         * differences, second candidate's error minus first's (6 channels, interleaved: A's, then
         * B's), are smoothed in one pass by NL-means on the mean image, whose variance is half a
         * half's; the choices, 0 for the first candidate and 1 for the second, are smoothed the
         * same way into SEL. */
        float *diff = img[ERR], *sm = img[SMOOTH];
        for (half = 0; half < 2; half++) {
            const float *other = half ? A : B, *c0 = img[CAND + half], *c1 = img[CAND + 2 + half];
            for (i = 0; i < n3; i++)
                diff[i / 3 * 6 + (size_t)(3 * half) + i % 3] = sq(other[i] - c1[i])
                                                               - sq(other[i] - c0[i]);
        }
        g.img = pad[PMEAN];
        g.var = pad[PVARM];
        g.f = MAP_F;
        g.k = MAP_K;
        st = nlm(&pl, &g, diff, 6, MAP_R, sm, d);
        for (i = 0; st == MCRT_OK && i < 2 * n3; i++)
            diff[i] = sm[i] > 0.0f ? 0.0f : 1.0f;
        if (st == MCRT_OK)
            st = nlm(&pl, &g, diff, 6, MAP_R, img[SEL], d);
    }
    if (st == MCRT_OK) {
        /* Each half's choice blends its candidates and their leverages per pixel and channel
         * (reusing ERR); the result is the mean of the halves. */
        float *fa = img[ERR], *fb = img[ERR + 1], *la = img[ERR + 2], *lb = img[ERR + 3];
        for (i = 0; i < n3; i++) {
            size_t p = i / 3;
            float sa = img[SEL][p * 6 + i % 3], sb = img[SEL][p * 6 + 3 + i % 3];
            const float *l = img[LEV];
            fa[i] = img[CAND][i] + sa * (img[CAND + 2][i] - img[CAND][i]);
            fb[i] = img[CAND + 1][i] + sb * (img[CAND + 3][i] - img[CAND + 1][i]);
            la[i] = l[p] + sa * (l[n + p] - l[p]);
            lb[i] = l[2 * n + p] + sb * (l[3 * n + p] - l[2 * n + p]);
            rgb[i] = 0.5f * (fa[i] + fb[i]);
        }
        /* 4. */
        if (mse) {
            edge_calibrate(in, img[MEAN], img[VAR], img[SMOOTH], img[TMP], img + OWN);
            mse_estimate(A, B, fa, fb, la, lb, img[VAR], img[OWN], img[OWN + 1], n3, mse);
        }
        for (i = 0; mse && mse_var && i < n3; i++)
            mse_var[i] = sq(img[VAR][i]) / 3.0f;
        /* The fireflies' excesses back (firefly.h), by the standard error of the mean, from a
         * half's variance over the REG_VAR_R box. */
        for (i = 0; nff > 0 && i < n3; i++)
            img[TMP][i] = sqrtf(0.5f * img[VARG][i]);
        mc_firefly_spread(ff, nff, img[TMP], w, h, rgb, mse);
        /* The emission back, fitted along the lights' edges (light_edge.h), and its variance:
         * its error and the rest's add, as the rest's filter never sees it. */
        if (E[0]
            && mc_light_edge_fit(E, in->emission_var, in->depth, w, h, img[EM], img[EMV]) != 0)
            st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for the denoiser (%dx%d)", w, h);
        for (i = 0; E[0] && st == MCRT_OK && i < n3; i++) {
            rgb[i] += img[EM][i];
            if (mse)
                mse[i] += img[EMV][i];
            /* Its term's own variance (nfor.h), as a Gaussian error's square has: 2σ⁴. */
            if (mse && mse_var)
                mse_var[i] += 2.0f * img[EMV][i] * img[EMV][i];
        }
        /* No radiance is negative, but a first-order fit extrapolates below 0 in dark pixels
         * beside bright ones (cornell-spheres, 64² at 4 spp: a sixth of the pixels had a
         * negative channel, down to -0.14). Each channel is clamped at 0, which can only bring
         * it closer to the truth: over make bench-denoise's ten seeds the Cornell box's error
         * moved by -0.1% and 0.0% at 16 and 64 spp, cornell-spheres' by -0.6% and -0.3%. The
         * error estimate is left as it was, a little over where a channel was clamped. */
        for (i = 0; i < n3; i++)
            rgb[i] = rgb[i] < 0.0f ? 0.0f : rgb[i];
        /* μ² for the relative errors (nfor.h). The emission added back is the halves' mean (or its
         * fit), unbiased and as noisy as the samples left it, so that E[f²] = μ² + V for the
         * pixel's value f and that light's variance V: f² − V is unbiased for μ², and on the
         * Cornell box's light edges, hit by many of their pixels' samples, it is what is used (the
         * estimate's mean over ten seeds at 160² and 16 spp 0.79 -> 0.84 of the truth). Where a
         * light is seen by few of a pixel's samples it is not: the lamps of scenes/dof.mcrt,
         * points out of focus, are hit by one sample of 16 in pixels whose μ is 0.1 to 0.5 (value
         * 2.6), and with one hit s²/n = m², so that f² − V is exactly 0 and the relative term
         * mse/ε (a 48² Cornell box at 16 spp read 4 times its truth); divided by f² instead, those
         * pixels' error (82% of the denoised image's, in 0.1% of its pixels) counted for 1/300 of
         * itself, and the image's estimate read 0.20 of the truth (make bench-denoise). So where
         * f² − V < V (the noise's standard deviation over 1/√2 of the value) the pixel's emission
         * is taken as its 3×3 mean, a ninth as noisy: dof 0.70 of the truth, 0.20 before. */
        if (mse && mean_sq) {
            float *em_box = img[TMP], *rgb_box = img[TMP2], *tmp = img[ERR];
            if (E[0])
                box_mean(img[EM], 3, w, h, 1, tmp, em_box);
            box_mean(rgb, 3, w, h, MEAN_SQ_R, tmp, rgb_box);
            for (i = 0; i < n3; i++) {
                float v = E[0] ? img[EMV][i] : 0.0f, q = rgb[i] * rgb[i] - v;
                if (E[0] && q < v) {
                    float m = rgb[i] - img[EM][i] + em_box[i];
                    q = m > 0.0f ? m * m : 0.0f;
                }
                mean_sq[i] = q < rgb_box[i] * rgb_box[i] ? q : rgb_box[i] * rgb_box[i];
            }
        }
    }
    free(buf);
    free(ff);
    return st;
}
