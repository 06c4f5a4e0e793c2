/* state.h: a render's state as exact data, for continuing it later (--resume) and merging it with
 * others (mcrt merge, mcrt-mpi): every pixel's two half sums (film.h) as 32-bit words, bit for
 * bit, and what the film is a render of as a line-per-field text. The image of a render is a
 * function of the scene, the options, the seed and the passes (passes.h), so a film with this
 * text continues exactly: its next pass is the one a longer render would have done next.
 * io/ stores both in an EXR (image_words); this module knows nothing of files. */
#ifndef MCRT_STATE_H
#define MCRT_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "render/film.h"

/* Words per pixel: each half's mean[3], m2[3] and count as 64-bit halves, high word first. */
#define MC_STATE_WORDS 28
/* The EXR attribute and channel prefix the state is stored under. */
#define MC_STATE_NAME "mcrtState"

struct render_state {
    uint64_t scene;         /* the scene's fingerprint: struct scene's hash (core/hash.h) */
    int width, height;      /* the scene's image */
    int crop[4];            /* the film's window x0, y0, x1, y1 (the whole image: 0, 0, W, H) */
    int spp;                /* samples per pixel of a pass */
    char integrator[32], sampler[32];
    int all_features, adaptive, pooled;
    uint64_t seed;
    /* The film holds passes first_pass to first_pass + passes - 1 of seed, merged in order;
     * merged: it holds other passes or seeds too (from mcrt merge), and cannot be continued. */
    int first_pass, passes, merged;
};

/* The film's sums as MC_STATE_WORDS words per pixel into words. */
void mc_state_pack(const struct film *f, uint32_t *words);
/* The inverse: f (sized already) gets the sums of words. */
void mc_state_unpack(struct film *f, const uint32_t *words);

/* s as text into buf; the length it needs (as snprintf). */
int mc_state_format(const struct render_state *s, char *buf, size_t size);
/* Parse text into s; 0, or -1 with the reason in why (a static string). */
int mc_state_parse(const char *text, struct render_state *s, const char **why);

/* Whether a and b are renders of one scene with one set of options (all but the seed, the
 * passes and the crop); when not, why names the first difference (a static string). */
int mc_state_same_render(const struct render_state *a, const struct render_state *b,
                         const char **why);

#endif
