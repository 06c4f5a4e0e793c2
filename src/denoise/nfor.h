/* nfor.h: an image-space denoiser for Monte Carlo renders that estimates its own error, after
 * NFOR (Bitterli, Rousselle, Moon, Iglesias-Guitián, Adler, Mitchell, Jarosz and Novák 2016,
 * "Nonlinearly Weighted First-order Regression for Denoising Monte Carlo Renderings", EGSR).
 *
 * It takes the two independent half buffers of a render (render/film.h: A and B, each the mean
 * of half of every pixel's samples) and, per half, feature planes (albedo, normal, depth...).
 * A pixel whose halves disagree far beyond its neighbours' (a firefly) has its bright half set to
 * the other's before the steps below, and the difference spread back after them (firefly.h):
 *   1. each feature of one half is filtered by NL-means with weights from the other half's
 *      (cross prefiltering, NFOR §5.1), so that the features' own noise is filtered and what
 *      filters A stays independent of A;
 *   2. each half's colour is regressed, in a window around a pixel, as an affine function of
 *      the other half's prefiltered features and of screen position, with NL-means weights from
 *      the other half's colour and that half's variance from its own samples (first-order
 *      regression, §5.2; the variance not from (A − B)², which would make A's weights depend
 *      on A, and the error estimate below take them as fixed), for two bandwidths k; each
 *      local fit is evaluated over its whole window and the fits averaged by their weights
 *      (collaborative filtering, §5.2). NFOR fits at every pixel; here the pixels of a lattice
 *      of spacing 2, and then each pixel those fits cover too little (nfor.c, LATTICE);
 *   3. each half's two candidates are blended per pixel by a choice between them, made from
 *      their errors as the other half sees them (§5.3): Â_k, filtered from B's guides, has
 *      E[(B − Â_k)²] ≈ MSE(Â_k) + Var(B); the maps of those errors and the choice are smoothed
 *      by NL-means. Each half chooses apart, so that A's choice does not follow A's noise;
 *   4. the blended result's error is estimated per pixel: Â = L·A, a combination of A's pixels
 *      with weights L fixed by B's guides, has E[(A − Â)²] = Var(A)(1 − 2·L_ii) + MSE(Â), L_ii
 *      estimated by regressing a probe of random signs along with the colour, so that
 *          MSE(D) ≈ ½[(A − Â)² − Var(A)(1 − 2ℓ_A) + (B − B̂)² − Var(B)(1 − 2ℓ_B)] − ¼(Â − B̂)²
 *      for the mean D = (Â + B̂)/2, the last term exact from ((a + b)/2)² = (a² + b²)/2 −
 *      ((a − b)/2)², Var(A) the pixel's (A − B)²/2, and in the term with ℓ_A A's own
 *      variance, which unlike (A − B)² does not grow with B's error where ℓ_A does (nfor.c,
 *      mse_estimate); summed over an image, the denoised
 *      image's error without a reference. NFOR's own form, (B − Â)² − Var(B), leaves out the
 *      covariance of B and Â that B's guides create, and read 0.13-0.15 of the true error on the
 *      Cornell box (nfor.c, mse_estimate).
 * NFOR's second pass (§5.4) is left out: it would need its own error estimate.
 *
 * An optional emission per half (the light emitted towards the camera by the first surfaces,
 * render/aov.h) is the part of the colour that needs no regression: it is taken out of each half
 * before step 2, so that a light seen directly cannot bleed into its neighbours (the first-order
 * regression alone put 77% of its error in the 20 pixels around the Cornell box's light,
 * estimators-anchor.md §2), and added back after, fitted along the lights' edges
 * (light_edge.h), its variance added to the error estimate. That variance comes with it, from
 * the samples rather than the halves: its noise is a light edge's coverage by a pixel's rays,
 * which the two halves of a pixel on the light's corner often agree on by chance (one degree of
 * freedom), when its samples show it clearly; the halves set only its scale, pooled over all the
 * pixels of the lights' edges.
 *
 * Tiles of the image run on the render's thread pool (render/tiles.h); every tile writes only
 * its own buffers, and overlapping contributions are summed in tile order afterwards, so the
 * result is bit-identical for any thread count. */
#ifndef MCRT_NFOR_H
#define MCRT_NFOR_H

#include "core/diag.h"

enum { MC_NFOR_MAX_FEATURES = 16 };

struct nfor_input {
    int width, height;
    const float *color[2];   /* half A and half B: W·H·3 floats each, linear RGB */
    const float *color_var[2]; /* per half, W·H·3 floats: the variance of its mean from its own
                                  samples (film.h, mc_film_half_variance), biased or not by the
                                  sampler: it is calibrated against (A − B)²/2 locally */
    int nfeatures;           /* 0 to MC_NFOR_MAX_FEATURES */
    const float *feature[2][MC_NFOR_MAX_FEATURES]; /* per half, planes of W·H floats */
    const float *emission[2]; /* per half, W·H·3 floats, part of color; NULL: none */
    const float *emission_var; /* W·H·3 floats: the variance of the emission's pixel mean */
    const float *depth[2];   /* per half, W·H floats: the depth feature (one of feature[][] too),
                                for the lights' edges (light_edge.h); NULL: not given */
};

/* Denoise in on `threads` threads: rgb receives the denoised mean image (W·H·3 floats) and mse,
 * when not NULL, the per-pixel estimate of its squared error (step 4 above; unbiased terms, so
 * a single pixel's may be negative: only sums over many pixels mean much). mse_var, when not
 * NULL (with mse), receives each term's own variance from one render to the next: with the
 * filtered halves near the truth μ, a term is the product (A − μ)(B − μ) of the halves'
 * independent errors, of variance σ⁴ for a half's variance σ², estimated from the pixel's
 * v = (A − B)²/2 as v²/3 (E[v²] = 3σ⁴ for Gaussian noise and more for heavier tails, so that it
 * errs high there); the emission added back adds its variance V to the term and 2V² to the
 * term's variance, a Gaussian error's (which errs low for a light that few samples hit: on
 * scenes/dof.mcrt's lamps out of focus the estimates scatter 2 to 5 times as widely as it
 * says; README). mean_sq, when not NULL (with mse), receives each pixel's squared true value
 * μ², which a relative error divides by: rgb² less the variance of the emission added back
 * unfiltered, or, where that emission is mostly noise, rgb² with the emission's 3×3 mean in
 * place of its own (where a small lamp out of focus is seen by one sample of 16, rgb² is
 * hundreds of times μ² and hides the pixel's error; nfor.c), and no more than the square of
 * rgb's 5×5 mean (a bright spot left by the noise hides its error alike). Returns MCRT_OK, or
 * MCRT_ERR_NOMEM. */
mcrt_status mc_nfor_denoise(const struct nfor_input *in, int threads, float *rgb, float *mse,
                            float *mse_var, float *mean_sq, mc_diag *d);

#endif
