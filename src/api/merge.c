/* merge.c: mcrt_merge (mcrt.h), merging renders from their states (render/state.h): each input's
 * film is merged into the output's at its crop's place, in the order given, so that renders of
 * one window with other seeds or passes combine by Chan, Golub and LeVeque's exact update and
 * disjoint crops assemble the image (a pixel merged into an empty one is copied bit for bit). */
#include "mcrt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "api/sized.h"
#include "core/alloc.h"
#include "io/image.h"
#include "render/adaptive.h"
#include "render/state.h"

/* One input: its state and its film. */
struct input {
    struct render_state st;
    struct film film;
};

/* Read input path into in (its film allocated; nothing to free on failure). */
static mcrt_status read_input(const char *path, struct input *in, mc_diag *d)
{
    struct image_words words = {MC_STATE_NAME, MC_STATE_WORDS, NULL, NULL};
    const char *why = NULL;
    char *text;
    int w, h;
    mcrt_status st = mc_image_read_words(path, &words, &text, &w, &h, d);
    if (st != MCRT_OK)
        return st;
    if (mc_state_parse(text, &in->st, &why) == 0 &&
        (w != in->st.crop[2] - in->st.crop[0] || h != in->st.crop[3] - in->st.crop[1]))
        why = "an image whose size is not its state's crop";
    free(text);
    if (!why && mc_film_init(&in->film, w, h) != 0)
        st = mc_fail(d, MCRT_ERR_NOMEM, "%s: out of memory for a %dx%d film", path, w, h);
    else if (why)
        st = mc_fail(d, MCRT_ERR_INVALID, "%s: %s", path, why);
    else {
        in->film.pooled = in->st.pooled;
        mc_state_unpack(&in->film, words.data);
    }
    free(words.data);
    return st;
}

static int same_window(const int a[4], const int b[4]) { return memcmp(a, b, 4 * sizeof *a) == 0; }

static int overlap(const int a[4], const int b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* Check that the inputs are of one render and their windows tile their bounding box, into
 * box; the merged state into out. */
static mcrt_status check_inputs(const char *const *paths, const struct input *in, int n,
                                struct render_state *out, mc_diag *d)
{
    const char *why;
    int i, j, tiling = 1;
    long area = 0;
    *out = in[0].st;
    for (i = 0; i < n; i++) {
        const int *c = in[i].st.crop;
        int first = 1;
        if (!mc_state_same_render(&in[0].st, &in[i].st, &why))
            return mc_fail(d, MCRT_ERR_INVALID, "%s: %s than %s", paths[i], why, paths[0]);
        for (j = 0; j < i; j++) {
            if (same_window(in[j].st.crop, c))
                first = 0;
            else if (overlap(in[j].st.crop, c))
                return mc_fail(d, MCRT_ERR_INVALID,
                               "%s: its crop %d,%d,%d,%d overlaps the crop %d,%d,%d,%d of %s "
                               "(crops must be disjoint, or the same window)",
                               paths[i], c[0], c[1], c[2], c[3], in[j].st.crop[0],
                               in[j].st.crop[1], in[j].st.crop[2], in[j].st.crop[3], paths[j]);
        }
        if (first)
            area += (long)(c[2] - c[0]) * (c[3] - c[1]);
        else
            tiling = 0;
        if (in[i].st.seed != in[0].st.seed || in[i].st.first_pass != in[0].st.first_pass ||
            in[i].st.passes != in[0].st.passes || in[i].st.merged)
            tiling = 0;
        if (i > 0 && same_window(in[0].st.crop, c))
            out->passes += in[i].st.passes;
        out->crop[0] = c[0] < out->crop[0] ? c[0] : out->crop[0];
        out->crop[1] = c[1] < out->crop[1] ? c[1] : out->crop[1];
        out->crop[2] = c[2] > out->crop[2] ? c[2] : out->crop[2];
        out->crop[3] = c[3] > out->crop[3] ? c[3] : out->crop[3];
    }
    if (area != (long)(out->crop[2] - out->crop[0]) * (out->crop[3] - out->crop[1]))
        return mc_fail(d, MCRT_ERR_INVALID,
                       "%s: the crops leave pixels of the window %d,%d,%d,%d they span unrendered",
                       paths[0], out->crop[0], out->crop[1], out->crop[2], out->crop[3]);
    /* Crops of one render assemble into that render, which can go on; anything else cannot. */
    if (!tiling) {
        out->merged = 1;
        out->first_pass = 0;
    } else
        out->passes = in[0].st.passes;
    return MCRT_OK;
}

static mcrt_status merge(const char *const *paths, int n, const char *output, mcrt_stats *stats,
                         struct input *in, mc_diag *d)
{
    struct render_state ms;
    struct film f;
    struct image_layer beauty = {NULL, NULL};
    struct image_words words = {MC_STATE_NAME, MC_STATE_WORDS, NULL, NULL};
    char text[1024];
    float *rgb;
    uint64_t lo, hi;
    mcrt_status st;
    int i, w, h;
    for (i = 0; i < n; i++)
        if ((st = read_input(paths[i], &in[i], d)) != MCRT_OK)
            return st;
    if ((st = check_inputs(paths, in, n, &ms, d)) != MCRT_OK)
        return st;
    w = ms.crop[2] - ms.crop[0];
    h = ms.crop[3] - ms.crop[1];
    if (mc_film_init(&f, w, h) != 0)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %dx%d film", w, h);
    f.pooled = ms.pooled;
    for (i = 0; i < n; i++)
        mc_film_merge_at(&f, in[i].st.crop[0] - ms.crop[0], in[i].st.crop[1] - ms.crop[1],
                         &in[i].film);
    rgb = mc_malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    words.data = mc_malloc((size_t)w * (size_t)h * MC_STATE_WORDS * sizeof *words.data);
    if (!rgb || !words.data)
        st = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %dx%d image", w, h);
    else {
        mc_film_resolve(&f, rgb);
        mc_state_pack(&f, words.data);
        mc_state_format(&ms, text, sizeof text);
        words.text = text;
        beauty.rgb = rgb;
        st = mc_image_write_words(output, &beauty, 1, &words, w, h, d);
    }
    if (st == MCRT_OK) {
        mc_adaptive_count_range(&f, &lo, &hi);
        stats->width = w;
        stats->height = h;
        stats->passes = ms.passes;
        stats->spp = (int)((lo + hi) / 2);
        stats->spp_min = (int)lo;
        stats->spp_max = (int)hi;
        stats->est_relmse = stats->est_relmse_raw = mc_film_est_relmse(&f);
        stats->est_relmse_sd = NAN; /* no denoiser here (mcrt.h) */
    }
    free(rgb);
    free(words.data);
    mc_film_free(&f);
    return st;
}

mcrt_status mcrt_merge(const char *const *inputs, int n, const char *output, mcrt_stats *out,
                       size_t out_size, char *error, size_t error_size)
{
    struct input *in = NULL;
    mcrt_stats stats;
    mc_diag d;
    mcrt_status st;
    int i;
    memset(&stats, 0, sizeof stats);
    d.msg[0] = '\0';
    if (!inputs || n < 1 || !output)
        st = mc_fail(&d, MCRT_ERR_INVALID, "mcrt_merge: no %s", output ? "inputs" : "output");
    else if (!(in = mc_calloc((size_t)n, sizeof *in)))
        st = mc_fail(&d, MCRT_ERR_NOMEM, "out of memory");
    else
        st = merge(inputs, n, output, &stats, in, &d);
    for (i = 0; in && i < n; i++)
        mc_film_free(&in[i].film);
    free(in);
    if (out)
        mc_sized_write(out, out_size, &stats, sizeof stats);
    if (error && error_size)
        snprintf(error, error_size, "%s", st != MCRT_OK ? d.msg : "");
    return st;
}
