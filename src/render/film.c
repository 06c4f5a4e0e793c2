/* film.c: film allocation, resolve and the error estimates from the Welford sums (see film.h). */
#include "render/film.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

int mc_film_init(struct film *f, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
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

void mc_film_merge(struct film *dst, const struct film *src)
{
    size_t i, n = (size_t)dst->width * (size_t)dst->height;
    int c;
    for (i = 0; i < n; i++) {
        struct film_pixel *a = &dst->pixels[i];
        const struct film_pixel *b = &src->pixels[i];
        double na = (double)a->count, nb = (double)b->count, nt = na + nb;
        if (b->count == 0)
            continue;
        if (a->count == 0) {
            *a = *b;
            continue;
        }
        for (c = 0; c < 3; c++) {
            double delta = b->mean[c] - a->mean[c];
            a->mean[c] += delta * nb / nt;
            a->m2[c] += b->m2[c] + delta * delta * na * nb / nt;
        }
        a->count += b->count;
    }
}

void mc_film_clear(struct film *f)
{
    memset(f->pixels, 0, (size_t)f->width * (size_t)f->height * sizeof *f->pixels);
}

void mc_film_resolve(const struct film *f, float *rgb)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    for (i = 0; i < n; i++) {
        rgb[3 * i + 0] = (float)f->pixels[i].mean[0];
        rgb[3 * i + 1] = (float)f->pixels[i].mean[1];
        rgb[3 * i + 2] = (float)f->pixels[i].mean[2];
    }
}

/* s²/n for one channel of a pixel: M2/(n(n − 1)). */
static double mean_variance(const struct film_pixel *p, int c)
{
    double n = (double)p->count;
    return p->m2[c] / (n * (n - 1.0));
}

void mc_film_variance(const struct film *f, float *var)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    for (i = 0; i < n; i++)
        for (c = 0; c < 3; c++)
            var[3 * i + c] =
                f->pixels[i].count >= 2 ? (float)mean_variance(&f->pixels[i], c) : 0.0f;
}

double mc_film_est_relmse(const struct film *f)
{
    size_t i, used = 0, n = (size_t)f->width * (size_t)f->height;
    double sum = 0.0;
    int c;
    for (i = 0; i < n; i++) {
        const struct film_pixel *p = &f->pixels[i];
        if (p->count < 2)
            continue;
        for (c = 0; c < 3; c++)
            sum += mean_variance(p, c) / (p->mean[c] * p->mean[c] + 0.01);
        used++;
    }
    return used ? sum / (3.0 * (double)used) : NAN;
}
