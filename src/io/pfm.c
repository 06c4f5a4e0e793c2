/* pfm.c: Portable Float Map (Debevec's HDRShop format): "PF" RGB or "Pf" grey, a text header, then
 * raw 32-bit floats, rows bottom to top; a negative scale means little-endian. Always built. */
#include "io/formats.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"

/* Read one whitespace-delimited header token of at most size-1 characters. The single whitespace
 * character ending it is consumed, which for the last token (the scale) is exactly the separator
 * the format puts before the pixel data. Returns 0 at EOF or for an over-long token. */
static int read_token(FILE *f, char *buf, size_t size)
{
    size_t n = 0;
    int c;
    do
        c = getc(f);
    while (c != EOF && isspace(c));
    while (c != EOF && !isspace(c)) {
        if (n + 1 >= size)
            return 0;
        buf[n++] = (char)c;
        c = getc(f);
    }
    buf[n] = '\0';
    return n > 0;
}

/* A dimension: a whole decimal number in [1, INT_MAX], nothing else. */
static int parse_dim(const char *s, long *out)
{
    char *end;
    long v;
    if (!isdigit((unsigned char)s[0]))
        return 0;
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno || *end || v < 1 || v > INT_MAX)
        return 0;
    *out = v;
    return 1;
}

static mcrt_status pfm_read(FILE *f, struct image *im, mc_diag *d)
{
    char magic[8], ws[24], hs[24], ss[48], *end;
    long w, h, x, y;
    int channels, little;
    double scale;
    size_t rowbytes;
    unsigned char *row;
    struct stat sb;
    long here;
    mcrt_status st;

    if (!read_token(f, magic, sizeof magic) || magic[0] != 'P' ||
        (magic[1] != 'F' && magic[1] != 'f') || magic[2])
        return mc_fail(d, MCRT_ERR_IO, "not a PFM file (it must start with PF or Pf)");
    channels = magic[1] == 'F' ? 3 : 1;
    if (!read_token(f, ws, sizeof ws) || !parse_dim(ws, &w) || !read_token(f, hs, sizeof hs) ||
        !parse_dim(hs, &h))
        return mc_fail(d, MCRT_ERR_IO, "bad PFM header: expected a width and a height");
    if (!read_token(f, ss, sizeof ss))
        return mc_fail(d, MCRT_ERR_IO, "bad PFM header: expected a scale");
    scale = strtod(ss, &end);
    if (*end || !isfinite(scale) || scale == 0.0)
        return mc_fail(d, MCRT_ERR_IO, "bad PFM header: scale '%s' is not a nonzero number", ss);
    /* The scale's magnitude is meant as a unit (e.g. watts per value) and is not applied here:
     * pixels are read as the radiance values they hold. Only its sign matters: the byte order. */
    little = scale < 0.0;

    if ((st = mc_image_check_size(w, h, d)) != MCRT_OK)
        return st;
    /* A short file is refused before allocating what its header claims. */
    rowbytes = (size_t)w * (size_t)channels * 4;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && (here = ftell(f)) >= 0 &&
        (double)(sb.st_size - here) < (double)rowbytes * (double)h)
        return mc_fail(d, MCRT_ERR_IO, "truncated pixel data (%ld bytes for %ldx%ld pixels)",
                       (long)(sb.st_size - here), w, h);
    if ((st = mc_image_alloc(im, w, h, d)) != MCRT_OK)
        return st;
    row = mc_malloc(rowbytes);
    if (!row) {
        mc_image_free(im);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %ld-pixel row", w);
    }
    for (y = h - 1; y >= 0; y--) { /* the file's first row is the bottom one */
        float *dst = im->rgb + (size_t)y * (size_t)w * 3;
        if (fread(row, 1, rowbytes, f) != rowbytes) {
            free(row);
            mc_image_free(im);
            return mc_fail(d, MCRT_ERR_IO, "truncated pixel data (%ld of %ld rows present)",
                           h - 1 - y, h);
        }
        for (x = 0; x < w * channels; x++) {
            const unsigned char *b = row + 4 * x;
            uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                                      (uint32_t)b[3] << 24
                                : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 |
                                      (uint32_t)b[0] << 24;
            float v;
            memcpy(&v, &u, sizeof v);
            if (channels == 3)
                dst[x] = v;
            else
                dst[3 * x] = dst[3 * x + 1] = dst[3 * x + 2] = v;
        }
    }
    free(row);
    return MCRT_OK;
}

static mcrt_status pfm_write(FILE *f, const float *rgb, int w, int h, mc_diag *d)
{
    size_t rowbytes = (size_t)w * 3 * 4, i;
    unsigned char *row = mc_malloc(rowbytes);
    int y, ok;
    if (!row)
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for a %d-pixel row", w);
    /* Scale -1: little-endian, written byte by byte so the file is the same on any host. */
    ok = fprintf(f, "PF\n%d %d\n-1.0\n", w, h) > 0;
    for (y = h - 1; ok && y >= 0; y--) {
        const float *src = rgb + (size_t)y * (size_t)w * 3;
        for (i = 0; i < (size_t)w * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], sizeof u);
            row[4 * i] = (unsigned char)u;
            row[4 * i + 1] = (unsigned char)(u >> 8);
            row[4 * i + 2] = (unsigned char)(u >> 16);
            row[4 * i + 3] = (unsigned char)(u >> 24);
        }
        ok = fwrite(row, 1, rowbytes, f) == rowbytes;
    }
    free(row);
    if (!ok)
        return mc_fail(d, MCRT_ERR_IO, "%s", strerror(errno));
    return MCRT_OK;
}

const struct image_format mc_pfm_format = {"pfm", NULL, NULL, pfm_write, pfm_read};
