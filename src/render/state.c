/* state.c: a film's sums as words and a render's identity as text (see state.h). */
#include "render/state.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>

static void put64(uint32_t *w, uint64_t v)
{
    w[0] = (uint32_t)(v >> 32);
    w[1] = (uint32_t)v;
}

static uint64_t get64(const uint32_t *w) { return (uint64_t)w[0] << 32 | w[1]; }

static uint64_t bits(double x)
{
    uint64_t v;
    memcpy(&v, &x, sizeof v);
    return v;
}

static double real(uint64_t v)
{
    double x;
    memcpy(&x, &v, sizeof x);
    return x;
}

void mc_state_pack(const struct film *f, uint32_t *words)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int h, c;
    for (i = 0; i < n; i++)
        for (h = 0; h < 2; h++) {
            const struct film_sums *s = &f->pixels[i].half[h];
            uint32_t *w = words + i * MC_STATE_WORDS + (size_t)h * MC_STATE_WORDS / 2;
            for (c = 0; c < 3; c++) {
                put64(w + 2 * c, bits(s->mean[c]));
                put64(w + 6 + 2 * c, bits(s->m2[c]));
            }
            put64(w + 12, s->count);
        }
}

void mc_state_unpack(struct film *f, const uint32_t *words)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int h, c;
    for (i = 0; i < n; i++)
        for (h = 0; h < 2; h++) {
            struct film_sums *s = &f->pixels[i].half[h];
            const uint32_t *w = words + i * MC_STATE_WORDS + (size_t)h * MC_STATE_WORDS / 2;
            for (c = 0; c < 3; c++) {
                s->mean[c] = real(get64(w + 2 * c));
                s->m2[c] = real(get64(w + 6 + 2 * c));
            }
            s->count = get64(w + 12);
        }
}

/* Version 1 of the text; a reader refuses any other first line. */
static const char magic[] = "mcrt-state 1\n";

int mc_state_format(const struct render_state *s, char *buf, size_t size)
{
    return snprintf(buf, size,
                    "%sscene %016" PRIx64 "\nimage %d %d\ncrop %d %d %d %d\nspp %d\n"
                    "integrator %s\nsampler %s\nall-features %d\nadaptive %d\npooled %d\n"
                    "seed %" PRIu64 "\npasses %d %d\nmerged %d\n",
                    magic, s->scene, s->width, s->height, s->crop[0], s->crop[1], s->crop[2],
                    s->crop[3], s->spp, s->integrator, s->sampler, s->all_features, s->adaptive,
                    s->pooled, s->seed, s->first_pass, s->passes, s->merged);
}

int mc_state_parse(const char *text, struct render_state *s, const char **why)
{
    int used = -1;
    memset(s, 0, sizeof *s);
    if (strncmp(text, magic, sizeof magic - 1) != 0) {
        *why = "not an mcrt state of version 1";
        return -1;
    }
    text += sizeof magic - 1;
    if (sscanf(text,
               "scene %16" SCNx64 "\nimage %d %d\ncrop %d %d %d %d\nspp %d\nintegrator %31s\n"
               "sampler %31s\nall-features %d\nadaptive %d\npooled %d\nseed %" SCNu64
               "\npasses %d %d\nmerged %d\n%n",
               &s->scene, &s->width, &s->height, &s->crop[0], &s->crop[1], &s->crop[2],
               &s->crop[3], &s->spp, s->integrator, s->sampler, &s->all_features, &s->adaptive,
               &s->pooled, &s->seed, &s->first_pass, &s->passes, &s->merged, &used) != 17 ||
        used < 0 || text[used] != '\0') {
        *why = "malformed render state";
        return -1;
    }
    if (s->width < 1 || s->height < 1 || s->crop[0] < 0 || s->crop[1] < 0 ||
        s->crop[0] >= s->crop[2] || s->crop[1] >= s->crop[3] || s->crop[2] > s->width ||
        s->crop[3] > s->height || s->spp < 1 || s->first_pass < 0 || s->passes < 1) {
        *why = "render state with an impossible size, crop or pass count";
        return -1;
    }
    return 0;
}

int mc_state_same_render(const struct render_state *a, const struct render_state *b,
                         const char **why)
{
    *why = a->scene != b->scene                             ? "a render of another scene"
           : a->width != b->width || a->height != b->height ? "an image of another size"
           : a->spp != b->spp                               ? "another --spp"
           : strcmp(a->integrator, b->integrator) != 0      ? "another integrator"
           : strcmp(a->sampler, b->sampler) != 0            ? "another sampler"
           : a->all_features != b->all_features             ? "another --all-features"
           : a->adaptive != b->adaptive                     ? "another --adaptive"
           : a->pooled != b->pooled                         ? "another error estimate"
                                                            : NULL;
    return *why == NULL;
}
