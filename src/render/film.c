/* film.c: film allocation and resolve (see film.h). */
#include "render/film.h"

#include <stdlib.h>

int mc_film_init(struct film *f, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
    f->pixels = NULL;
    if (width <= 0 || height <= 0 || n / (size_t)width != (size_t)height)
        return -1;
    f->pixels = calloc(n, sizeof *f->pixels);
    return f->pixels ? 0 : -1;
}

void mc_film_free(struct film *f)
{
    free(f->pixels);
    f->pixels = NULL;
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
