/* film.c: film allocation, resolve and the error estimates from the halves' Welford sums (see
 * film.h). */
#include "render/film.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"

int mc_film_init(struct film *f, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
    f->pooled = 0;
    f->pixels = NULL;
    if (width <= 0 || height <= 0 || n / (size_t)width != (size_t)height)
        return -1;
    f->pixels = mc_calloc(n, sizeof *f->pixels);
    return f->pixels ? 0 : -1;
}

void mc_film_free(struct film *f)
{
    free(f->pixels);
    f->pixels = NULL;
}

uint64_t mc_film_half_seed(uint64_t seed, int h)
{
    /* The constant separates the halves' seeds from the passes' and the user's ("half"). */
    return h == 0 ? seed : mc_hash3(seed, (uint64_t)h, 0x68616c66ULL);
}

/* a += b (Chan, Golub and LeVeque 1979). */
static void merge_sums(struct film_sums *a, const struct film_sums *b)
{
    double na = (double)a->count, nb = (double)b->count, nt = na + nb;
    int c;
    if (b->count == 0)
        return;
    if (a->count == 0) {
        *a = *b;
        return;
    }
    for (c = 0; c < 3; c++) {
        double delta = b->mean[c] - a->mean[c];
        a->mean[c] += delta * nb / nt;
        a->m2[c] += b->m2[c] + delta * delta * na * nb / nt;
    }
    a->count += b->count;
}

void mc_film_merge(struct film *dst, const struct film *src) { mc_film_merge_at(dst, 0, 0, src); }

void mc_film_merge_at(struct film *dst, int x0, int y0, const struct film *src)
{
    int x, y;
    for (y = 0; y < src->height; y++)
        for (x = 0; x < src->width; x++) {
            struct film_pixel *p = &dst->pixels[(size_t)(y0 + y) * (size_t)dst->width +
                                                (size_t)(x0 + x)];
            const struct film_pixel *q = &src->pixels[(size_t)y * (size_t)src->width + (size_t)x];
            merge_sums(&p->half[0], &q->half[0]);
            merge_sums(&p->half[1], &q->half[1]);
        }
}

void mc_film_clear(struct film *f)
{
    memset(f->pixels, 0, (size_t)f->width * (size_t)f->height * sizeof *f->pixels);
}

struct film_sums mc_film_pixel_sums(const struct film_pixel *p)
{
    struct film_sums s = p->half[0];
    merge_sums(&s, &p->half[1]);
    return s;
}

int mc_film_pixel_variance(const struct film *f, const struct film_pixel *p, double var[3])
{
    double na = (double)p->half[0].count, nb = (double)p->half[1].count, n = na + nb;
    int c;
    if (f->pooled) {
        /* s²/n, s² = M2/(n − 1) the unbiased sample variance of independent samples. */
        struct film_sums s = mc_film_pixel_sums(p);
        if (s.count < 2)
            return 0;
        for (c = 0; c < 3; c++)
            var[c] = s.m2[c] / (n * (n - 1.0));
        return 1;
    }
    if (p->half[0].count == 0 || p->half[1].count == 0)
        return 0;
    /* (A − B)²·nA·nB/n² (film.h): (A − B)²/4 for equal halves. */
    for (c = 0; c < 3; c++) {
        double d = p->half[0].mean[c] - p->half[1].mean[c];
        var[c] = d * d * na * nb / (n * n);
    }
    return 1;
}

double mc_film_mean_squared(const struct film_pixel *p, int c)
{
    struct film_sums s = mc_film_pixel_sums(p);
    double m2 = s.mean[c] * s.mean[c], ab;
    if (!p->half[0].count || !p->half[1].count)
        return m2;
    ab = p->half[0].mean[c] * p->half[1].mean[c];
    return ab > 0.5 * m2 ? ab : 0.5 * m2;
}

void mc_film_resolve(const struct film *f, float *rgb)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    for (i = 0; i < n; i++) {
        struct film_sums s = mc_film_pixel_sums(&f->pixels[i]);
        for (c = 0; c < 3; c++)
            rgb[3 * i + c] = (float)s.mean[c];
    }
}

void mc_film_resolve_half(const struct film *f, int h, float *rgb)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    for (i = 0; i < n; i++)
        for (c = 0; c < 3; c++)
            rgb[3 * i + c] = (float)f->pixels[i].half[h].mean[c];
}

void mc_film_variance(const struct film *f, float *var)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    for (i = 0; i < n; i++) {
        double v[3];
        int known = mc_film_pixel_variance(f, &f->pixels[i], v);
        for (c = 0; c < 3; c++)
            var[3 * i + c] = known ? (float)v[c] : 0.0f;
    }
}

void mc_film_half_variance(const struct film *f, int h, float *var)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    for (i = 0; i < n; i++) {
        const struct film_sums *s = &f->pixels[i].half[h], *o = &f->pixels[i].half[!h];
        double k = (double)s->count, ko = (double)o->count;
        for (c = 0; c < 3; c++) {
            double d = s->mean[c] - o->mean[c];
            /* E[(A − B)²] = σ²/k + σ²/ko, so σ²/k is estimated by (A − B)²·ko/(k + ko). */
            var[3 * i + c] = s->count >= 2 ? (float)(s->m2[c] / (k * (k - 1.0)))
                             : s->count && o->count ? (float)(d * d * ko / (k + ko)) : 0.0f;
        }
    }
}

double mc_film_est_relmse(const struct film *f)
{
    size_t i, used = 0, n = (size_t)f->width * (size_t)f->height;
    double sum = 0.0;
    int c;
    for (i = 0; i < n; i++) {
        double v[3];
        if (!mc_film_pixel_variance(f, &f->pixels[i], v))
            continue;
        for (c = 0; c < 3; c++)
            sum += v[c] / (mc_film_mean_squared(&f->pixels[i], c) + MC_RELMSE_EPS);
        used++;
    }
    return used ? sum / (3.0 * (double)used) : NAN;
}
