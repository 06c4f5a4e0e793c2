/* denoise.h: a render's layers handed to the denoiser (denoise/nfor.h) and back, for
 * mcrt_render_run with opt.denoise and for mcrt_denoise_file: the same inputs either way, the
 * colour halves A and B and, per half, the first-surface layers of render/aov.h. */
#ifndef MCRT_API_DENOISE_H
#define MCRT_API_DENOISE_H

#include "core/diag.h"

/* The layers the denoiser reads, each per half: in an EXR, "NAME.A" and "NAME.B". The
 * first-surface layers of render/aov.h, and "variance", the variance of the half's mean from its
 * own samples (mc_film_half_variance);
 * and the variance of the emission's pixel means (render/aov.h), the layer "emission.var". */
enum { DENOISE_ALBEDO, DENOISE_NORMAL, DENOISE_DEPTH, DENOISE_EMISSION, DENOISE_VARIANCE,
       DENOISE_LAYERS };
extern const char *const mc_denoise_layer_names[DENOISE_LAYERS];
#define MC_DENOISE_EMISSION_VAR "emission.var"

/* The halves (W·H·3 floats each) and layer[l][h], layer l of half h (W·H·3 floats each, depth in
 * every channel), denoised into rgb (W·H·3 floats) on `threads` threads; *est_relmse gets the
 * denoised image's estimated relative MSE, *est_sd, when not NULL, that estimate's own standard
 * deviation from one render to the next (denoised_relmse), and *est_raw, when est_raw is not
 * NULL, the raw image's as the film estimates it from the halves alone. The emission layer is given to the denoiser as the
 * part of the colour that needs no regression (denoise/nfor.h). */
mcrt_status mc_denoise_layers(const float *const halves[2],
                              const float *layer[DENOISE_LAYERS][2], const float *emission_var,
                              int width, int height,
                              int threads, float *rgb, double *est_relmse, double *est_sd,
                              double *est_raw, mc_diag *d);

/* Worker threads when the caller asks for 0: the cores online (api.c). */
int mc_default_threads(void);

#endif
