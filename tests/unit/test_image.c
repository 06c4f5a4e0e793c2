/* test_image.c: image IO: the sRGB curve, exact float round trips (PFM, EXR), PNG within sRGB
 * quantisation, hand-built files of every kind the readers accept (built here byte by byte from
 * the format specs, independently of the code under test), damaged files refused without a crash
 * or a word on stderr, and crash-safe writing (temporary file + rename). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/rng.h"
#include "file_util.h"
#include "io/formats.h"
#include "t.h"

/* ---- scratch files ---- */

static char scratch[64]; /* a fresh folder for this run */

static const char *at(char *buf, const char *name)
{
    snprintf(buf, 256, "%.63s/%.180s", scratch, name);
    return buf;
}

static void put_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    T_CHECK(f && fwrite(data, 1, n, f) == n, "writing %s", path);
    if (f)
        fclose(f);
}

static int same_file(const char *path, const unsigned char *data, size_t n)
{
    size_t m;
    unsigned char *got = (unsigned char *)t_read_file(path, &m);
    int same = got && m == n && memcmp(got, data, n) == 0;
    free(got);
    return same;
}

static int count_temp_files(void)
{
    DIR *dp = opendir(scratch);
    struct dirent *e;
    int n = 0;
    while (dp && (e = readdir(dp)))
        n += strstr(e->d_name, ".tmp-") != NULL;
    if (dp)
        closedir(dp);
    return n;
}

static void remove_scratch(void)
{
    DIR *dp = opendir(scratch);
    struct dirent *e;
    char p[256];
    while (dp && (e = readdir(dp)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
            unlink(at(p, e->d_name));
    if (dp)
        closedir(dp);
    rmdir(scratch);
}

/* stderr goes to a file between quiet_begin and quiet_end, which returns how many bytes the code
 * under test printed there: the library must print nothing, even for broken files. */
static int saved_stderr = -1;
static void quiet_begin(void)
{
    char p[256];
    int fd = open(at(p, "stderr.txt"), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    fflush(stderr);
    saved_stderr = dup(2);
    dup2(fd, 2);
    close(fd);
}
static long quiet_end(void)
{
    char p[256];
    struct stat sb;
    fflush(stderr);
    dup2(saved_stderr, 2);
    close(saved_stderr);
    return stat(at(p, "stderr.txt"), &sb) == 0 ? (long)sb.st_size : -1;
}

/* A w x h image of uniform floats in [lo, hi). */
static float *random_image(pcg32 *g, int w, int h, float lo, float hi)
{
    size_t i, n = (size_t)w * (size_t)h * 3;
    float *rgb = malloc(n * sizeof *rgb);
    for (i = 0; i < n; i++)
        rgb[i] = lo + (hi - lo) * pcg32_float(g);
    return rgb;
}

/* Read path, expecting failure whose message names the file and contains want. */
static void expect_read_error(const char *path, const char *want)
{
    struct image im = {1, 1, NULL};
    mc_diag d = {""};
    char prefix[300];
    mcrt_status st = mc_image_read(path, &im, &d);
    snprintf(prefix, sizeof prefix, "cannot read '%s': ", path);
    T_CHECK(st != MCRT_OK && !im.rgb && !im.width, "%s: read should fail", path);
    T_CHECK(strncmp(d.msg, prefix, strlen(prefix)) == 0 && strstr(d.msg, want),
            "message '%s' should name the file and say '%s'", d.msg, want);
    mc_image_free(&im);
}

/* ---- the sRGB curve ---- */

static void test_srgb(void)
{
    int k;
    float prev = -1.0f;
    /* Reference values in double precision from the IEC 61966-2-1 formula; float powf is good to
     * a few ulps (< 1e-6 on [0, 1]). */
    T_NEAR(mc_srgb_encode(0.0f), 0.0, 0.0, "black");
    T_NEAR(mc_srgb_encode(1.0f), 1.0, 0.0, "white");
    T_NEAR(mc_srgb_encode(0.5f), 1.055 * pow(0.5, 1 / 2.4) - 0.055, 1e-6, "mid grey");
    T_NEAR(mc_srgb_encode(0.5f), 0.7353569831, 1e-6, "mid grey, published value");
    T_NEAR(mc_srgb_encode(0.18f), 0.4613561295, 1e-6, "18%% grey");
    T_NEAR(mc_srgb_encode(0.001f), 0.01292, 1e-7, "linear segment");
    /* The two pieces meet at the knee (to 1e-7: the standard's rounded constants). */
    T_NEAR(mc_srgb_encode(0.0031308f), 0.04045, 1e-6, "knee");
    T_NEAR(mc_srgb_encode(0.00313081f), 0.04045, 1e-6, "just above the knee");
    T_NEAR(mc_srgb_decode(0.04045f), 0.0031308, 1e-7, "knee, decoded");
    T_NEAR(mc_srgb_decode(0.5f), 0.2140411404, 1e-6, "decode 0.5");
    T_NEAR(mc_srgb_decode(1.0f), 1.0, 1e-7, "decode 1");
    T_CHECK(mc_srgb_encode(-0.5f) == 0.0f && mc_srgb_encode(NAN) == 0.0f, "negative and NaN -> 0");
    T_CHECK(mc_srgb_encode(2.0f) == 1.0f && mc_srgb_encode(INFINITY) == 1.0f, "above 1 -> 1");
    for (k = 0; k <= 255; k++) {
        float s = (float)k / 255.0f, e = mc_srgb_encode(mc_srgb_decode(s));
        T_CHECK(fabsf(e - s) <= 1e-6f, "encode(decode(%d/255)) = %.9g", k, e);
        T_CHECK(e > prev, "monotonic at %d", k);
        prev = e;
    }
}

/* ---- PFM ---- */

static void put_u32(unsigned char *p, uint32_t u, int little)
{
    int i;
    for (i = 0; i < 4; i++)
        p[i] = (unsigned char)(u >> (little ? 8 * i : 24 - 8 * i));
}

static uint32_t float_bits(float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

static void test_pfm(void)
{
    pcg32 g;
    char p[256];
    const int w = 7, h = 5;
    float *rgb;
    struct image im = {0, 0, NULL};
    mc_diag d = {""};
    unsigned char *bytes, file[256];
    size_t n, i;
    const char *header = "PF\n7 5\n-1.0\n";
    int ok;

    pcg32_seed(&g, 11, 1);
    rgb = random_image(&g, w, h, -100.0f, 1000.0f);
    rgb[0] = -0.0f; /* values a float format must keep bit for bit */
    rgb[1] = INFINITY;
    rgb[2] = NAN;
    rgb[3] = 1e-40f; /* subnormal */
    rgb[4] = 3.4e38f;
    T_CHECK(mc_image_write(at(p, "a.pfm"), rgb, w, h, &d) == MCRT_OK, "write: %s", d.msg);
    T_CHECK(mc_image_read(p, &im, &d) == MCRT_OK, "read: %s", d.msg);
    T_CHECK(im.width == w && im.height == h, "size %dx%d", im.width, im.height);
    T_CHECK(im.rgb && memcmp(im.rgb, rgb, sizeof(float) * 3 * w * h) == 0, "PFM round trip is exact");
    mc_image_free(&im);

    /* The layout: the exact header, then little-endian floats, bottom row first. */
    bytes = (unsigned char *)t_read_file(p, &n);
    T_CHECK(bytes && n == strlen(header) + (size_t)w * h * 12, "file size %zu", n);
    T_CHECK(bytes && memcmp(bytes, header, strlen(header)) == 0, "header");
    if (bytes) {
        const unsigned char *px = bytes + strlen(header);
        uint32_t u = (uint32_t)px[0] | (uint32_t)px[1] << 8 | (uint32_t)px[2] << 16 |
                     (uint32_t)px[3] << 24;
        T_CHECK(u == float_bits(rgb[(size_t)(h - 1) * w * 3]), "first value is bottom-left red");
    }
    free(bytes);
    free(rgb);

    /* Big-endian (positive scale) RGB, 2x1. */
    {
        static const float v[6] = {1.5f, -2.0f, 0.25f, 3.0f, 4.0f, 5.0f};
        n = (size_t)sprintf((char *)file, "PF\n2 1\n1.0\n");
        for (i = 0; i < 6; i++, n += 4)
            put_u32(file + n, float_bits(v[i]), 0);
        put_file(at(p, "be.pfm"), file, n);
        ok = mc_image_read(p, &im, &d) == MCRT_OK;
        T_CHECK(ok && im.width == 2 && im.height == 1 && memcmp(im.rgb, v, sizeof v) == 0,
                "big-endian PFM: %s", d.msg);
        mc_image_free(&im);
    }
    /* Grey "Pf", 2x2, little-endian: becomes R = G = B, and the file's first row is the bottom. */
    {
        static const float v[4] = {1.0f, 2.0f, 3.0f, 4.0f}; /* file order: bottom row, top row */
        n = (size_t)sprintf((char *)file, "Pf 2 2 -1\n");
        for (i = 0; i < 4; i++, n += 4)
            put_u32(file + n, float_bits(v[i]), 1);
        put_file(at(p, "grey.pfm"), file, n);
        ok = mc_image_read(p, &im, &d) == MCRT_OK;
        T_CHECK(ok && im.width == 2 && im.height == 2, "grey PFM: %s", d.msg);
        if (ok)
            T_CHECK(im.rgb[0] == 3.0f && im.rgb[1] == 3.0f && im.rgb[2] == 3.0f &&
                        im.rgb[3] == 4.0f && im.rgb[6] == 1.0f && im.rgb[11] == 2.0f,
                    "grey values replicated and flipped: %g %g %g", im.rgb[0], im.rgb[3], im.rgb[6]);
        mc_image_free(&im);
    }
    /* Damage. */
    {
        static const struct {
            const char *text, *want;
        } bad[] = {
            {"", "not a PFM"},
            {"P6\n1 1\n255\n", "not a PFM"},
            {"PFX\n1 1\n-1\n", "not a PFM"},
            {"PF\n0 1\n-1\n", "width and a height"},
            {"PF\n-3 1\n-1\n", "width and a height"},
            {"PF\n12x 1\n-1\n", "width and a height"},
            {"PF\n99999999999999999999 1\n-1\n", "width and a height"},
            {"PF\n3\n", "width and a height"},
            {"PF\n1 1\n0\n", "scale"},
            {"PF\n1 1\nnan\n", "scale"},
            {"PF\n1 1\n-1x\n", "scale"},
            {"PF\n100000 100000\n-1\n", "out of range"},
            {"PF\n16385 16385\n-1\n", "out of range"}, /* just over 2^28 pixels */
            {"PF\n2 2\n-1\n01234567890123456789", "truncated"},
        };
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            put_file(at(p, "bad.pfm"), bad[i].text, strlen(bad[i].text));
            expect_read_error(p, bad[i].want);
        }
    }
}

/* ---- PNG ---- */

struct buf {
    unsigned char d[4096];
    size_t n;
};

static void put_be32(struct buf *b, uint32_t u)
{
    put_u32(b->d + b->n, u, 0);
    b->n += 4;
}
static void put_mem(struct buf *b, const void *p, size_t n)
{
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static uint32_t crc32_png(const unsigned char *p, size_t n) /* PNG spec, annex D */
{
    uint32_t c = 0xffffffffu;
    size_t i;
    int k;
    for (i = 0; i < n; i++)
        for (c ^= p[i], k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
    return c ^ 0xffffffffu;
}

static void png_chunk(struct buf *b, const char *type, const unsigned char *data, size_t n)
{
    size_t start;
    put_be32(b, (uint32_t)n);
    start = b->n;
    put_mem(b, type, 4);
    if (n)
        put_mem(b, data, n);
    put_be32(b, crc32_png(b->d + start, n + 4));
}

/* A PNG from raw scanlines (each starting with filter byte 0), deflated as one stored block.
 * plte/gamma are optional (NULL / 0). */
static void build_png(struct buf *b, int w, int h, int depth, int color, int interlace,
                      const unsigned char *raw, size_t rawlen, const unsigned char *plte,
                      size_t plte_len, uint32_t gamma)
{
    static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    unsigned char ihdr[13], z[1024];
    uint32_t a = 1, s = 0;
    size_t i, zn = 0;
    put_u32(ihdr, (uint32_t)w, 0);
    put_u32(ihdr + 4, (uint32_t)h, 0);
    ihdr[8] = (unsigned char)depth;
    ihdr[9] = (unsigned char)color;
    ihdr[10] = ihdr[11] = 0;
    ihdr[12] = (unsigned char)interlace;
    b->n = 0;
    put_mem(b, sig, 8);
    png_chunk(b, "IHDR", ihdr, 13);
    if (gamma) {
        unsigned char g4[4];
        put_u32(g4, gamma, 0);
        png_chunk(b, "gAMA", g4, 4);
    }
    if (plte)
        png_chunk(b, "PLTE", plte, plte_len);
    /* zlib (RFC 1950) around one stored deflate block (RFC 1951, 3.2.4), then Adler-32. */
    z[zn++] = 0x78;
    z[zn++] = 0x01;
    z[zn++] = 0x01;
    z[zn++] = (unsigned char)rawlen;
    z[zn++] = (unsigned char)(rawlen >> 8);
    z[zn++] = (unsigned char)~rawlen;
    z[zn++] = (unsigned char)(~rawlen >> 8);
    memcpy(z + zn, raw, rawlen);
    zn += rawlen;
    for (i = 0; i < rawlen; i++) {
        a = (a + raw[i]) % 65521u;
        s = (s + a) % 65521u;
    }
    put_u32(z + zn, s << 16 | a, 0);
    zn += 4;
    png_chunk(b, "IDAT", z, zn);
    png_chunk(b, "IEND", NULL, 0);
}

/* Read a hand-built PNG and compare all pixels with want (linear RGB) to tol. */
static void check_png(const char *name, const struct buf *b, int w, int h, const float *want,
                      double tol)
{
    char p[256];
    struct image im = {0, 0, NULL};
    mc_diag d = {""};
    int i, ok;
    put_file(at(p, name), b->d, b->n);
    ok = mc_image_read(p, &im, &d) == MCRT_OK;
    T_CHECK(ok && im.width == w && im.height == h, "%s: %s", name, d.msg);
    for (i = 0; ok && i < w * h * 3; i++)
        T_CHECK(fabs(im.rgb[i] - want[i]) <= tol, "%s value %d: %.9g, want %.9g", name, i, im.rgb[i],
                want[i]);
    mc_image_free(&im);
}

static size_t chunk_length(const unsigned char *p)
{
    return (size_t)p[0] << 24 | (size_t)p[1] << 16 | (size_t)p[2] << 8 | p[3];
}

static float dec8(int v)
{
    return mc_srgb_decode((float)v / 255.0f);
}

static void test_png(void)
{
    pcg32 g;
    char p[256];
    struct image im = {0, 0, NULL};
    mc_diag d = {""};
    struct buf b;
    unsigned char *bytes;
    size_t n, i;
    float *rgb, ramp[256 * 3];
    const int w = 13, h = 9;
    int ok, k;
    /* Every value in the file is one of the 8-bit sRGB levels, so after decoding twice a value's
     * encode is within half a level (1/510) of the encode of the clamped input, plus float error
     * (1e-6 from the sRGB check above). */
    const float half_level = 0.5f / 255.0f + 1e-6f;

    if (!mc_image_supported("png")) {
        T_SKIP("the PNG tests: built without libpng");
        return;
    }
    pcg32_seed(&g, 12, 1);
    rgb = random_image(&g, w, h, -0.2f, 1.3f);
    rgb[5] = NAN;
    T_CHECK(mc_image_write(at(p, "a.png"), rgb, w, h, &d) == MCRT_OK, "write: %s", d.msg);
    ok = mc_image_read(p, &im, &d) == MCRT_OK;
    T_CHECK(ok && im.width == w && im.height == h, "read: %s", d.msg);
    for (i = 0; ok && i < (size_t)w * h * 3; i++) {
        float e = mc_srgb_encode(im.rgb[i]), want = mc_srgb_encode(rgb[i]);
        T_CHECK(fabsf(e - want) <= half_level, "pixel value %zu: %g read back as %g", i, rgb[i],
                im.rgb[i]);
    }
    mc_image_free(&im);
    free(rgb);

    /* The sRGB chunk is there (with gAMA and cHRM for older readers), before IDAT. */
    bytes = (unsigned char *)t_read_file(p, &n);
    for (k = 0, i = 8; bytes && i + 8 <= n; i += 12 + chunk_length(bytes + i)) {
        const unsigned char *type = bytes + i + 4;
        if (!memcmp(type, "IDAT", 4))
            break;
        if (!memcmp(type, "sRGB", 4))
            k |= 1;
        if (!memcmp(type, "gAMA", 4))
            k |= 2;
        if (!memcmp(type, "cHRM", 4))
            k |= 4;
    }
    T_CHECK(k == 7, "sRGB, gAMA and cHRM chunks before IDAT (mask %d)", k);

    /* Truncated (half of the file) and not a PNG at all. */
    if (bytes) {
        put_file(at(p, "cut.png"), bytes, n / 2);
        quiet_begin();
        expect_read_error(p, "truncated");
        T_CHECK(quiet_end() == 0, "libpng printed nothing");
        bytes[20] ^= 0x55; /* inside IHDR: its CRC no longer matches */
        put_file(at(p, "crc.png"), bytes, n);
        expect_read_error(p, "CRC");
    }
    free(bytes);
    put_file(at(p, "text.png"), "hello, world\n", 13);
    expect_read_error(p, "not a PNG");

    /* Each 8-bit sRGB level written comes back as exactly that level decoded: no off-by-one in
     * the rounding, no double gamma. Linear 0.5 is level 188 (0.7354 * 255 = 187.5). */
    for (k = 0; k < 256; k++)
        ramp[3 * k] = ramp[3 * k + 1] = ramp[3 * k + 2] = dec8(k);
    ramp[3 * 100] = 0.5f;
    ok = mc_image_write(at(p, "ramp.png"), ramp, 256, 1, &d) == MCRT_OK &&
         mc_image_read(p, &im, &d) == MCRT_OK;
    T_CHECK(ok, "ramp: %s", d.msg);
    for (k = 0; ok && k < 256; k++)
        T_CHECK(fabsf(im.rgb[3 * k] - (k == 100 ? dec8(188) : dec8(k))) <= 1e-7f, "level %d: %.9g", k,
                im.rgb[3 * k]);
    mc_image_free(&im);

    /* Hand-built inputs. Expected values are the sRGB decode of the stored levels (no sRGB chunk
     * and no gAMA: sRGB is assumed), or a power law when a gAMA chunk is the only colour info. */
    {
        static const unsigned char raw[] = {0, 0, 128, 255};
        const float want[9] = {0, 0, 0, dec8(128), dec8(128), dec8(128), 1, 1, 1};
        build_png(&b, 3, 1, 8, 0, 0, raw, sizeof raw, NULL, 0, 0);
        check_png("grey8.png", &b, 3, 1, want, 1e-7);
    }
    {
        static const unsigned char raw[] = {0, 0x00, 0x00, 0x80, 0x00};
        float v = mc_srgb_decode(32768.0f / 65535.0f);
        const float want[6] = {0, 0, 0, v, v, v};
        build_png(&b, 2, 1, 16, 0, 0, raw, sizeof raw, NULL, 0, 0);
        check_png("grey16.png", &b, 2, 1, want, 1e-6);
    }
    {
        static const unsigned char raw[] = {0, 0xb0}; /* 8 one-bit pixels: 1 0 1 1 0 0 0 0 */
        float want[24];
        static const int bits[8] = {1, 0, 1, 1, 0, 0, 0, 0};
        for (k = 0; k < 24; k++)
            want[k] = (float)bits[k / 3];
        build_png(&b, 8, 1, 1, 0, 0, raw, sizeof raw, NULL, 0, 0);
        check_png("grey1.png", &b, 8, 1, want, 0.0);
    }
    {
        static const unsigned char raw[] = {0, 1, 0}, plte[] = {255, 0, 0, 0, 0, 255};
        static const float want[6] = {0, 0, 1, 1, 0, 0};
        build_png(&b, 2, 1, 8, 3, 0, raw, sizeof raw, plte, sizeof plte, 0);
        check_png("palette.png", &b, 2, 1, want, 0.0);
    }
    {
        static const unsigned char raw[] = {0, 255, 128, 0, 7}; /* RGBA: alpha is dropped */
        const float want[3] = {1, dec8(128), 0};
        build_png(&b, 1, 1, 8, 6, 0, raw, sizeof raw, NULL, 0, 0);
        check_png("rgba.png", &b, 1, 1, want, 1e-7);
    }
    {
        static const unsigned char raw[] = {0, 0x12, 0x34, 0x80, 0x00, 0xff, 0xff}; /* RGB16 */
        const float want[3] = {mc_srgb_decode(0x1234 / 65535.0f), mc_srgb_decode(0x8000 / 65535.0f), 1};
        build_png(&b, 1, 1, 16, 2, 0, raw, sizeof raw, NULL, 0, 0);
        check_png("rgb16.png", &b, 1, 1, want, 1e-6);
    }
    {
        /* gAMA 1.0 and no sRGB chunk: linear data, as POV-Ray writes with File_Gamma=1.0. */
        static const unsigned char raw[] = {0, 128, 64, 255};
        const float want[3] = {128 / 255.0f, 64 / 255.0f, 1};
        build_png(&b, 1, 1, 8, 2, 0, raw, sizeof raw, NULL, 0, 100000);
        check_png("linear.png", &b, 1, 1, want, 1e-6);
        /* gAMA 0.45455: a pure 2.2 power, not the sRGB curve. */
        build_png(&b, 1, 1, 8, 2, 0, raw, sizeof raw, NULL, 0, 45455);
        {
            const float want22[3] = {(float)pow(128 / 255.0, 1 / 0.45455), (float)pow(64 / 255.0, 1 / 0.45455), 1};
            check_png("gamma22.png", &b, 1, 1, want22, 1e-6);
        }
    }
    {
        /* 2x2 grey, Adam7 interlaced: pass 1 holds (0,0), pass 6 (1,0), pass 7 row 1. */
        static const unsigned char raw[] = {0, 0, 0, 255, 0, 128, 255};
        const float want[12] = {0, 0, 0, 1, 1, 1, dec8(128), dec8(128), dec8(128), 1, 1, 1};
        build_png(&b, 2, 2, 8, 0, 1, raw, sizeof raw, NULL, 0, 0);
        check_png("interlaced.png", &b, 2, 2, want, 1e-7);
    }
    {
        /* A header claiming 10^6 x 10^6 pixels is refused before any pixel memory is taken. */
        static const unsigned char raw[] = {0, 0};
        build_png(&b, 1000000, 1000000, 8, 0, 0, raw, sizeof raw, NULL, 0, 0);
        put_file(at(p, "huge.png"), b.d, b.n);
        expect_read_error(p, "out of range");
    }
}

/* ---- EXR ---- */

/* A float exactly representable as a normal half (or zero), as half bits. */
static uint16_t to_half(float v)
{
    uint32_t u = float_bits(v);
    uint32_t sign = (u >> 16) & 0x8000u, exp = (u >> 23) & 0xffu, mant = u & 0x7fffffu;
    if (exp == 0)
        return (uint16_t)sign;
    return (uint16_t)(sign | (exp - 127 + 15) << 10 | mant >> 13);
}

struct exr_chan {
    const char *name; /* in the order the file lists them: sorted by name */
    int type;         /* 0 uint, 1 half, 2 float */
};

static void put_le(unsigned char *out, size_t *n, uint64_t v, int bytes)
{
    int i;
    for (i = 0; i < bytes; i++)
        out[(*n)++] = (unsigned char)(v >> (8 * i));
}

static void exr_attr(unsigned char *out, size_t *n, const char *name, const char *type,
                     const void *data, size_t size)
{
    memcpy(out + *n, name, strlen(name) + 1);
    *n += strlen(name) + 1;
    memcpy(out + *n, type, strlen(type) + 1);
    *n += strlen(type) + 1;
    put_le(out, n, size, 4);
    memcpy(out + *n, data, size);
    *n += size;
}

/* An uncompressed single-part scanline EXR (OpenEXR file layout document): header, offset table,
 * one chunk per line. Channel c of pixel (x, y) is vals[(c * h + y) * w + x]. Returns its size. */
static size_t build_exr(unsigned char *out, const struct exr_chan *ch, int nch, int x0, int y0,
                        int w, int h, const float *vals)
{
    static const unsigned char magic[8] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    unsigned char attr[512], zero = 0;
    size_t n = 0, a = 0, table;
    int32_t box[4] = {x0, y0, x0 + w - 1, y0 + h - 1};
    float one = 1.0f, center[2] = {0, 0};
    int c, x, y;

    memcpy(out, magic, 8);
    n = 8;
    for (c = 0; c < nch; c++) {
        memcpy(attr + a, ch[c].name, strlen(ch[c].name) + 1);
        a += strlen(ch[c].name) + 1;
        put_le(attr, &a, (uint64_t)ch[c].type, 4);
        put_le(attr, &a, 0, 4); /* pLinear and reserved */
        put_le(attr, &a, 1, 4); /* x and y sampling */
        put_le(attr, &a, 1, 4);
    }
    attr[a++] = 0;
    exr_attr(out, &n, "channels", "chlist", attr, a);
    exr_attr(out, &n, "compression", "compression", &zero, 1);
    for (a = 0, c = 0; c < 4; c++)
        put_le(attr, &a, (uint32_t)box[c], 4);
    exr_attr(out, &n, "dataWindow", "box2i", attr, 16);
    exr_attr(out, &n, "displayWindow", "box2i", attr, 16);
    exr_attr(out, &n, "lineOrder", "lineOrder", &zero, 1);
    exr_attr(out, &n, "pixelAspectRatio", "float", &one, 4); /* little-endian hosts only */
    exr_attr(out, &n, "screenWindowCenter", "v2f", center, 8);
    exr_attr(out, &n, "screenWindowWidth", "float", &one, 4);
    out[n++] = 0;
    table = n;
    n += 8 * (size_t)h;
    for (y = 0; y < h; y++) {
        size_t size = 0, t = table + 8 * (size_t)y;
        for (c = 0; c < nch; c++)
            size += (size_t)w * (ch[c].type == 1 ? 2 : 4);
        put_le(out, &t, n, 8);
        put_le(out, &n, (uint32_t)(y0 + y), 4);
        put_le(out, &n, size, 4);
        for (c = 0; c < nch; c++)
            for (x = 0; x < w; x++) {
                float v = vals[((size_t)c * h + y) * w + x];
                if (ch[c].type == 1)
                    put_le(out, &n, to_half(v), 2);
                else
                    put_le(out, &n, ch[c].type == 2 ? float_bits(v) : (uint32_t)v, 4);
            }
    }
    return n;
}

/* Walk the attributes of an EXR header; returns a pointer to the value of attribute name. */
static const unsigned char *exr_find_attr(const unsigned char *f, size_t n, const char *name,
                                          uint32_t *size)
{
    size_t i = 8;
    while (i < n && f[i]) {
        const char *an = (const char *)f + i;
        size_t tl;
        i += strlen(an) + 1;
        tl = strlen((const char *)f + i);
        i += tl + 1;
        *size = (uint32_t)f[i] | (uint32_t)f[i + 1] << 8 | (uint32_t)f[i + 2] << 16 |
                (uint32_t)f[i + 3] << 24;
        i += 4;
        if (!strcmp(an, name))
            return f + i;
        i += *size;
    }
    return NULL;
}

/* Run OpenEXR's own tools on path, where installed (Debian package openexr): exrheader parses
 * the header, exrmaketiled decodes every pixel with the C++ library, which has its own decoder. */
static void check_with_tools(const char *path)
{
    static const char *const tools[2] = {"exrheader", "exrmaketiled"};
    char cmd[600];
    int i;
    for (i = 0; i < 2; i++) {
        snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tools[i]);
        if (system(cmd) != 0) {
            T_SKIP("%s accepts our EXR: not installed (apt-get install openexr)", tools[i]);
            continue;
        }
        snprintf(cmd, sizeof cmd, "%s '%s'%s%s%s >/dev/null 2>&1", tools[i], path, i ? " '" : "",
                 i ? path : "", i ? ".tiled.exr'" : "");
        T_CHECK(system(cmd) == 0, "%s accepts our EXR", tools[i]);
    }
}

static void read_exr_case(const char *name, const struct exr_chan *ch, int nch, int x0, int y0,
                          int w, int h, const float *vals, const float *want)
{
    static unsigned char file[8192];
    char p[256];
    struct image im = {0, 0, NULL};
    mc_diag d = {""};
    int ok;
    put_file(at(p, name), file, build_exr(file, ch, nch, x0, y0, w, h, vals));
    ok = mc_image_read(p, &im, &d) == MCRT_OK;
    T_CHECK(ok && im.width == w && im.height == h, "%s: %s", name, d.msg);
    T_CHECK(ok && memcmp(im.rgb, want, sizeof(float) * 3 * (size_t)(w * h)) == 0, "%s: values", name);
    mc_image_free(&im);
}

static void test_exr(void)
{
    pcg32 g;
    char p[256];
    struct image im = {0, 0, NULL};
    mc_diag d = {""};
    const int w = 37, h = 23; /* 23 lines: the last 16-line ZIP chunk is partial */
    float *rgb;
    unsigned char *bytes;
    size_t n;
    uint32_t size;
    int ok;

    if (!mc_image_supported("exr")) {
        T_SKIP("the EXR tests: built without OpenEXR");
        return;
    }
    pcg32_seed(&g, 13, 1);
    rgb = random_image(&g, w, h, -10.0f, 1e4f);
    rgb[0] = -0.0f;
    rgb[1] = INFINITY;
    rgb[2] = NAN;
    rgb[3] = 1e-40f;
    rgb[4] = 3.4e38f;
    T_CHECK(mc_image_write(at(p, "a.exr"), rgb, w, h, &d) == MCRT_OK, "write: %s", d.msg);
    ok = mc_image_read(p, &im, &d) == MCRT_OK;
    T_CHECK(ok && im.width == w && im.height == h, "read: %s", d.msg);
    T_CHECK(ok && memcmp(im.rgb, rgb, sizeof(float) * 3 * w * h) == 0, "EXR round trip is exact");
    mc_image_free(&im);
    free(rgb);

    /* Chunks that deflate to about their raw size: every value is random bits (exponent below
     * 2) with a chance that rises from 0.935 to 0.945 down the image, else 1. A chunk whose
     * deflate output is exactly as long as its raw bytes must be stored raw (readers take that
     * size as raw); OpenEXRCore 3.1.5 stored the deflate output, and 9 of these 256 chunks
     * (zlib 1.2.13) read back as garbage before exr.c replaced them. */
    {
        const int cw = 64, chunks = 256;
        size_t per = (size_t)cw * 16 * 3, k;
        float *noisy = malloc(per * (size_t)chunks * sizeof *noisy);
        char q[256];
        int c;
        pcg32_seed(&g, 1, 1);
        for (c = 0; c < chunks; c++)
            for (k = 0; k < per; k++) {
                uint32_t u = pcg32_float(&g) < 0.935 + 0.01 * c / chunks
                                 ? pcg32_next(&g) & 0x3fffffffu : 0x3f800000u;
                memcpy(&noisy[(size_t)c * per + k], &u, sizeof u);
            }
        T_CHECK(mc_image_write(at(q, "chunks.exr"), noisy, cw, 16 * chunks, &d) == MCRT_OK,
                "write: %s", d.msg);
        ok = mc_image_read(q, &im, &d) == MCRT_OK;
        for (c = 0, n = 0; ok && c < chunks; c++)
            n += memcmp(im.rgb + (size_t)c * per, noisy + (size_t)c * per, per * sizeof *noisy) != 0;
        T_CHECK(ok && n == 0, "chunks that deflate to their raw size round-trip: %lu of %d differ",
                (unsigned long)n, chunks);
        mc_image_free(&im);
        free(noisy);
    }

    /* Our header, read by hand: float B, G, R; ZIP; data window (0,0)-(w-1,h-1). */
    bytes = (unsigned char *)t_read_file(p, &n);
    T_CHECK(bytes && n > 8 && !memcmp(bytes, "\x76\x2f\x31\x01", 4) && bytes[4] == 2 && !bytes[5],
            "EXR magic, version 2, single-part scanline");
    if (bytes) {
        const unsigned char *v = exr_find_attr(bytes, n, "channels", &size);
        static const unsigned char want_ch[] = {'B', 0, 2, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0,
                                                'G', 0, 2, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0,
                                                'R', 0, 2, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0};
        static const unsigned char want_dw[] = {0, 0, 0, 0, 0, 0, 0, 0, 36, 0, 0, 0, 22, 0, 0, 0};
        T_CHECK(v && size == sizeof want_ch && !memcmp(v, want_ch, size), "channels B, G, R as FLOAT");
        v = exr_find_attr(bytes, n, "compression", &size);
        T_CHECK(v && size == 1 && v[0] == 3, "ZIP compression");
        v = exr_find_attr(bytes, n, "dataWindow", &size);
        T_CHECK(v && size == 16 && !memcmp(v, want_dw, 16), "data window");
        check_with_tools(p);

        quiet_begin();
        put_file(at(p, "cut.exr"), bytes, n / 2);
        expect_read_error(p, "");
        put_file(at(p, "header-only.exr"), bytes, 40);
        expect_read_error(p, "");
        put_file(at(p, "text.exr"), "hello, world\n", 13);
        expect_read_error(p, "");
        T_CHECK(quiet_end() == 0, "OpenEXR printed nothing");
    }
    free(bytes);

    /* Hand-built files. */
    {
        /* Half R, G, B (listed B, G, R), 3x2. Values exactly representable as halves. */
        static const struct exr_chan ch[3] = {{"B", 1}, {"G", 1}, {"R", 1}};
        static const float vals[18] = {/* B */ 0.5f, 1, 2, -1, 65504, 0.00006103515625f,
                                       /* G */ 3, 4, 5, 6, 7, 8,
                                       /* R */ 0.25f, 0.125f, 10, 11, 12, 13};
        static const float want[18] = {0.25f, 3, 0.5f, 0.125f, 4, 1, 10, 5, 2,
                                       11, 6, -1, 12, 7, 65504, 13, 8, 0.00006103515625f};
        read_exr_case("half.exr", ch, 3, 0, 0, 3, 2, vals, want);
        /* The same at a data window origin of (5, -3): the window is the image. */
        read_exr_case("window.exr", ch, 3, 5, -3, 3, 2, vals, want);
    }
    {
        /* No plain R, G, B: the first layer with all three ("diffuse", not "spec"); A is ignored. */
        static const struct exr_chan ch[7] = {{"A", 1},         {"diffuse.B", 2}, {"diffuse.G", 2},
                                              {"diffuse.R", 2}, {"spec.B", 2},    {"spec.G", 2},
                                              {"spec.R", 2}};
        static const float vals[7] = {9, 3, 2, 1, 6, 5, 4};
        static const float want[3] = {1, 2, 3};
        read_exr_case("layers.exr", ch, 7, 0, 0, 1, 1, vals, want);
    }
    {
        /* Plain R, G, B win over a layer that sorts earlier. */
        static const struct exr_chan ch[6] = {{"B", 2},   {"G", 2},   {"R", 2},
                                              {"a.B", 2}, {"a.G", 2}, {"a.R", 2}};
        static const float vals[6] = {3, 2, 1, 6, 5, 4};
        static const float want[3] = {1, 2, 3};
        read_exr_case("plain.exr", ch, 6, 0, 0, 1, 1, vals, want);
    }
    {
        static unsigned char file[2048];
        static const struct exr_chan grey[1] = {{"Y", 1}};
        static const struct exr_chan uints[3] = {{"B", 0}, {"G", 0}, {"R", 0}};
        static const float vals[3] = {1, 2, 3};
        put_file(at(p, "grey.exr"), file, build_exr(file, grey, 1, 0, 0, 1, 1, vals));
        expect_read_error(p, "no R, G, B channels");
        put_file(at(p, "uint.exr"), file, build_exr(file, uints, 3, 0, 0, 1, 1, vals));
        expect_read_error(p, "not full-resolution half or float");
    }
}

/* ---- writing: dispatch, errors, temporary files ---- */

static void test_write(void)
{
    pcg32 g;
    char p[256], q[256];
    mc_diag d = {""};
    float *small, *big;
    unsigned char *old;
    size_t oldn;
    struct image im = {0, 0, NULL};
    struct stat sb;
    struct rlimit saved, lim;
    static const char *const suffixes[3] = {"pfm", "png", "exr"};
    int i;

    pcg32_seed(&g, 14, 1);
    small = random_image(&g, 4, 3, 0.0f, 1.0f);
    big = random_image(&g, 64, 64, 0.0f, 1.0f);

    T_CHECK(mc_image_supported("pfm") && mc_image_supported(".pfm") && mc_image_supported("PFM"),
            "PFM is always built");
    T_CHECK(!mc_image_supported("jpg") && !mc_image_supported("") && !mc_image_supported(NULL),
            "jpg, empty and NULL are not");
    T_NOTE("built in: png %d, exr %d", mc_image_supported("png"), mc_image_supported("exr"));

    /* New files get the umask's permissions, not mkstemp's 0600. */
    umask(022);
    T_CHECK(mc_image_write(at(p, "keep.pfm"), small, 4, 3, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(stat(p, &sb) == 0 && (sb.st_mode & 0777) == 0644, "mode %o", (unsigned)(sb.st_mode & 0777));
    old = (unsigned char *)t_read_file(p, &oldn);

    /* Refusals before anything is created. */
    put_file(at(q, "keep.jpg"), "old", 3);
    T_CHECK(mc_image_write(q, small, 4, 3, &d) == MCRT_ERR_UNSUPPORTED, "jpg refused");
    T_CHECK(strstr(d.msg, "unknown image format '.jpg' (use .png, .exr or .pfm)") && strstr(d.msg, q),
            "message: %s", d.msg);
    T_CHECK(same_file(q, (const unsigned char *)"old", 3), "keep.jpg untouched");
    T_CHECK(mc_image_write(at(q, "noext"), small, 4, 3, &d) == MCRT_ERR_UNSUPPORTED &&
                strstr(d.msg, "no image suffix"),
            "no suffix: %s", d.msg);
    T_CHECK(mc_image_write(at(q, "dir.x/noext"), small, 4, 3, &d) == MCRT_ERR_UNSUPPORTED,
            "a dot in a folder name is not a suffix");
    T_CHECK(mc_image_write(p, small, 0, 3, &d) == MCRT_ERR_INVALID, "zero width refused");
    T_CHECK(mc_image_write(p, NULL, 4, 3, &d) == MCRT_ERR_INVALID, "no pixels refused");
    T_CHECK(mc_image_write(at(q, "missing/x.pfm"), small, 4, 3, &d) == MCRT_ERR_IO &&
                strstr(d.msg, q) && strstr(d.msg, strerror(ENOENT)),
            "missing folder: %s", d.msg);
    for (i = 0; i < 3; i++)
        if (!mc_image_supported(suffixes[i])) {
            char name[16];
            snprintf(name, sizeof name, "x.%s", suffixes[i]);
            T_CHECK(mc_image_write(at(q, name), small, 4, 3, &d) == MCRT_ERR_UNSUPPORTED &&
                        strstr(d.msg, "this mcrt was built without") && strstr(d.msg, "and rebuild"),
                    "format not built: %s", d.msg);
        }

    /* A write that fails half way (here: the file size limit, as a full disk would) leaves the
     * old file as it was and no temporary file behind, in every format. */
    getrlimit(RLIMIT_FSIZE, &saved);
    lim = saved;
    lim.rlim_cur = 4096; /* a 64x64 image takes more in any format: 48 KiB PFM, ~12 KiB PNG */
    signal(SIGXFSZ, SIG_IGN);
    for (i = 0; i < 3; i++) {
        char name[16];
        unsigned char *prev;
        size_t prevn;
        if (!mc_image_supported(suffixes[i])) {
            T_SKIP("a failed .%s write leaves the old file: built without it", suffixes[i]);
            continue;
        }
        snprintf(name, sizeof name, "keep.%s", suffixes[i]);
        at(q, name);
        if (i > 0)
            T_CHECK(mc_image_write(q, small, 4, 3, &d) == MCRT_OK, "%s: %s", name, d.msg);
        prev = (unsigned char *)t_read_file(q, &prevn);
        setrlimit(RLIMIT_FSIZE, &lim);
        T_CHECK(mc_image_write(q, big, 64, 64, &d) == MCRT_ERR_IO, "%s: over the size limit", name);
        setrlimit(RLIMIT_FSIZE, &saved);
        T_CHECK(strstr(d.msg, q) && strstr(d.msg, strerror(EFBIG)), "%s: message: %s", name, d.msg);
        T_CHECK(prev && same_file(q, prev, prevn), "%s untouched by the failed write", name);
        free(prev);
    }
    signal(SIGXFSZ, SIG_DFL);
    T_CHECK(count_temp_files() == 0, "no temporary files left (%d)", count_temp_files());

    /* A successful write replaces the file. */
    T_CHECK(same_file(p, old, oldn), "keep.pfm as first written");
    T_CHECK(mc_image_write(p, big, 64, 64, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(mc_image_read(p, &im, &d) == MCRT_OK && im.width == 64 &&
                !memcmp(im.rgb, big, sizeof(float) * 3 * 64 * 64),
            "replaced: %s", d.msg);
    mc_image_free(&im);
    T_CHECK(count_temp_files() == 0, "no temporary files left");
    free(old);

    /* Reading: a missing file, an unknown suffix. */
    expect_read_error(at(q, "nothing.pfm"), strerror(ENOENT));
    T_CHECK(mc_image_read(at(q, "keep.jpg"), &im, &d) == MCRT_ERR_UNSUPPORTED && !im.rgb,
            "reading .jpg: %s", d.msg);
    mc_image_free(NULL);
    free(small);
    free(big);
}

int main(void)
{
    snprintf(scratch, sizeof scratch, "/tmp/mcrt-test-image-XXXXXX");
    if (!mkdtemp(scratch)) {
        perror("mkdtemp");
        return 1;
    }
    test_srgb();
    test_pfm();
    test_png();
    test_exr();
    test_write();
    remove_scratch();
    return t_done();
}
