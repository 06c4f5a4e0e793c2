/* test_texture.c: textures (scene/texture.h): the bilinear lookup's exact values at and between
 * texel centres, its wrapping and orientation, the checker's squares, scale and offset; an image
 * texture read from a PNG is decoded from sRGB; the scene language's texture block and material
 * keys; the textures feature bit; the albedo AOV of a textured surface; and a textured furnace:
 * a diffuse quad under a white sky, whose every pixel is the texture's bilinear value at the
 * pixel's centre (closed form), within a bound derived from the pixel's sampling noise. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/image.h"
#include "render/aov.h"
#include "render_util.h"
#include "scene/features.h"
#include "scene/scene.h"
#include "t.h"

/* A 3x2 image: texel (x, y), row y from the top, holds (x + 10 y, 100 + x, 0.5) / 200. */
#define IW 3
#define IH 2
static void fill_image(float *rgb)
{
    int x, y;
    for (y = 0; y < IH; y++)
        for (x = 0; x < IW; x++) {
            float *p = rgb + 3 * (y * IW + x);
            p[0] = (float)(x + 10 * y) / 200.0f;
            p[1] = (float)(100 + x) / 200.0f;
            p[2] = 0.5f / 200.0f;
        }
}

static double texel_r(int x, int y) { return (double)(((x % IW) + IW) % IW + 10 * (((y % IH) + IH) % IH)) / 200.0; }

static void test_bilinear(void)
{
    float rgb[IW * IH * 3];
    int x, y;
    fill_image(rgb);
    /* At each texel's centre ((x + ½)/w, 1 − (y + ½)/h): the texel itself. */
    for (y = 0; y < IH; y++)
        for (x = 0; x < IW; x++) {
            vec3 v = mc_texture_bilinear(rgb, IW, IH, (x + 0.5f) / IW, 1.0f - (y + 0.5f) / IH);
            T_NEAR(v.x, texel_r(x, y), 1e-7, "texel (%d, %d) red at its centre", x, y);
            T_NEAR(v.y, (100.0 + x) / 200.0, 1e-7, "texel (%d, %d) green", x, y);
        }
    /* Halfway between the centres of (0, 0) and (1, 0): their mean; a quarter of the way from
     * (1, 0) towards (1, 1) (down): 3/4 and 1/4. */
    T_NEAR(mc_texture_bilinear(rgb, IW, IH, 1.0f / IW, 0.75f).x, 0.5 * (texel_r(0, 0) + texel_r(1, 0)),
           1e-7, "between two centres");
    T_NEAR(mc_texture_bilinear(rgb, IW, IH, 1.5f / IW, 0.75f - 0.25f / IH).x,
           0.75 * texel_r(1, 0) + 0.25 * texel_r(1, 1), 1e-7, "a quarter of the way down");
    /* The centre of the four texels (1,0), (2,0), (1,1), (2,1). */
    T_NEAR(mc_texture_bilinear(rgb, IW, IH, 2.0f / IW, 0.5f).x,
           0.25 * (texel_r(1, 0) + texel_r(2, 0) + texel_r(1, 1) + texel_r(2, 1)), 1e-7,
           "the middle of four texels");
    /* Wrapping: s = 0 lies between the last column's centre and the first's; t = 1 and t = 0
     * between the bottom row's and the top row's. */
    T_NEAR(mc_texture_bilinear(rgb, IW, IH, 0.0f, 0.75f).x, 0.5 * (texel_r(2, 0) + texel_r(0, 0)), 1e-7,
           "wrap across s = 0");
    T_NEAR(mc_texture_bilinear(rgb, IW, IH, 0.5f / IW, 0.0f).x, 0.5 * (texel_r(0, 1) + texel_r(0, 0)),
           1e-7, "wrap across t = 0");
    /* Any whole number of periods away: the same value. */
    {
        float s = 0.37f, t = 0.81f;
        vec3 a = mc_texture_bilinear(rgb, IW, IH, s, t), b = mc_texture_bilinear(rgb, IW, IH, s - 2.0f, t + 3.0f);
        T_NEAR(a.x, b.x, 1e-6, "periodic in s and t");
        T_NEAR(a.y, b.y, 1e-6, "periodic in s and t");
    }
}

static void test_checker(void)
{
    struct texture t;
    memset(&t, 0, sizeof t);
    t.kind = TEXTURE_CHECKER;
    t.even = v3(0.1f, 0.2f, 0.3f);
    t.odd = v3s(0.9f);
    t.scale = v2(4.0f, 2.0f);
    t.offset = v2(0.0f, 0.0f);
    /* (s, t) = (4u, 2v): u = 0.1, v = 0.1 is square (0, 0): even; u = 0.3: (1, 0), odd. */
    T_CHECK(mc_texture_eval(&t, v2(0.1f, 0.1f)).x == 0.1f, "square (0, 0) is even");
    T_CHECK(mc_texture_eval(&t, v2(0.3f, 0.1f)).x == 0.9f, "square (1, 0) is odd");
    T_CHECK(mc_texture_eval(&t, v2(0.3f, 0.6f)).x == 0.1f, "square (1, 1) is even");
    T_CHECK(mc_texture_eval(&t, v2(-0.1f, 0.1f)).x == 0.9f, "square (-1, 0) is odd");
    t.offset = v2(1.0f, 0.0f);
    T_CHECK(mc_texture_eval(&t, v2(0.1f, 0.1f)).x == 0.9f, "an offset of one square swaps them");
}

/* A scratch folder for image files. */
static char scratch[64];
static const char *at(char *buf, const char *name)
{
    snprintf(buf, 256, "%s/%s", scratch, name);
    return buf;
}

/* Parse text (images named relative to the scratch folder), read its images as the API layer
 * does, and prepare; 0 on success, with the message in d otherwise. */
static int load(struct scene *s, const char *text, mc_diag *d)
{
    size_t i;
    mc_scene_init(s);
    if (mc_scene_parse(s, text, strlen(text), "t.mcrt", scratch, d) != MCRT_OK)
        return -1;
    for (i = 0; i < s->image_count; i++) {
        struct image im;
        if (mc_image_read(s->images[i].path, &im, d) != MCRT_OK)
            return -1;
        mc_scene_set_image(s, i, im.rgb, im.width, im.height);
    }
    return mc_scene_prepare(s, d) == MCRT_OK ? 0 : -1;
}

/* The sRGB curve's decoding and encoding as published (IEC 61966-2-1), in double. */
static double srgb_decode(double e) { return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4); }
static double srgb_encode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1 / 2.4) - 0.055; }

static void test_image_texture(void)
{
    float rgb[IW * IH * 3];
    char p[256], text[512];
    struct scene s;
    mc_diag d;
    int x, y;
    fill_image(rgb);
    T_CHECK(mc_image_write(at(p, "t.pfm"), rgb, IW, IH, &d) == MCRT_OK, "%s", d.msg);
    snprintf(text, sizeof text,
             "texture img { image \"t.pfm\" scale 2 1 offset 0.25 0 }\n"
             "material m { diffuse 0.5 texture img }\nsphere { material m }\n");
    if (load(&s, text, &d) != 0) {
        T_CHECK(0, "%s", d.msg);
        mc_scene_free(&s);
        return;
    }
    T_CHECK(s.texture_count == 1 && s.textures[0].w == IW && s.textures[0].h == IH, "one 3x2 texture");
    T_CHECK(s.materials[1].texture == 1 && s.materials[1].color.x == 0.5f, "the material's texture and scale");
    T_CHECK(mc_scene_features(&s) & FEATURE_TEXTURES, "the textures feature");
    /* (s, t) = (2u + 0.25, v): u = (0.5/3 − 0.25)/2 + 1 lands on texel (0, 0)'s centre. */
    for (y = 0; y < IH; y++)
        for (x = 0; x < IW; x++) {
            float u = (float)(((x + 0.5) / IW - 0.25) / 2.0 + 1.0), v = 1.0f - (y + 0.5f) / IH;
            T_NEAR(mc_texture_eval(&s.textures[0], v2(u, v)).x, texel_r(x, y), 1e-6,
                   "scaled and offset, texel (%d, %d)", x, y);
        }
    mc_scene_free(&s);

    /* A PNG: 8-bit sRGB, decoded to linear on reading. The bytes written for each linear value
     * follow the published curve. */
    if (!mc_image_supported("png")) {
        T_SKIP("PNG textures: built without libpng");
        return;
    }
    T_CHECK(mc_image_write(at(p, "t.png"), rgb, IW, IH, &d) == MCRT_OK, "%s", d.msg);
    if (load(&s, "texture img { image \"t.png\" }\nmaterial m { diffuse texture img }\nsphere { material m }\n",
             &d) != 0) {
        T_CHECK(0, "%s", d.msg);
        mc_scene_free(&s);
        return;
    }
    for (x = 0; x < IW * IH * 3; x++) {
        double byte = floor(srgb_encode(rgb[x]) * 255.0 + 0.5);
        T_NEAR(s.textures[0].rgb[x], srgb_decode(byte / 255.0), 1e-6, "PNG sample %d (byte %.0f)", x, byte);
    }
    mc_scene_free(&s);
}

static void test_scene_language(void)
{
    struct scene s;
    mc_diag d;
    int k;
    T_CHECK(load(&s, "material m { plastic 0.5 roughness 0.5 texture c roughness_texture c }\n"
                     "texture c { checker 0.2 0.4 0.6 1 1 1 }\nsphere { material m }\n", &d) == 0,
            "%s", d.msg);
    T_CHECK(s.materials[1].texture == 1 && s.materials[1].roughness_texture == 1,
            "textures resolved when defined after the material");
    T_NEAR(s.materials[1].alpha, 0.25, 1e-7, "roughness 0.5 scales the roughness texture: alpha = r^2 at 1");
    T_CHECK(s.textures[0].even.z == 0.6f && s.textures[0].odd.x == 1.0f, "checker colours");
    T_CHECK(mc_material_lobes(&s.materials[1]) == (MC_LOBE_SPECULAR | MC_LOBE_GLOSSY),
            "a roughness texture makes both lobes possible");
    /* The BSDF at a hit on the checker's even square: (0.2, 0.4, 0.6) x 0.5, alpha 0.25 x mean². */
    {
        struct ray r;
        struct hit h;
        struct bsdf b;
        float mean = (0.2f + 0.4f + 0.6f) / 3.0f;
        r.o = v3(0.0f, -0.3f, -5.0f); /* u = 1/2 + small: square (0, 0) of the unscaled checker */
        r.d = v3(0.0f, 0.0f, 1.0f);
        r.tmax = INFINITY;
        r.time = 0.0f;
        h.t = r.tmax;
        T_CHECK(mc_scene_intersect(&s, &r, &h), "the ray hits the sphere");
        mc_scene_bsdf(&s, &r, &h, &b);
        T_NEAR(b.color.y, 0.2, 1e-6, "textured colour");
        T_NEAR(b.alpha, 0.25 * mean * mean, 1e-6, "textured alpha");
        /* The albedo layer (and so the denoiser's albedo feature) records the textured colour. */
        {
            struct aov_pixel px;
            memset(&px, 0, sizeof px);
            mc_aov_record(&px, 0, &s, &r);
            T_NEAR(px.half[0].albedo[1], 0.2, 1e-6, "the albedo AOV's green: the checker's 0.4 x 0.5");
            T_NEAR(px.half[0].albedo[2], 0.3, 1e-6, "the albedo AOV's blue: 0.6 x 0.5");
        }
    }
    mc_scene_free(&s);
    /* mcrt info names each texture and its memory. */
    {
        static const char text[] = "texture c { checker 0 1 }\nmaterial m { diffuse texture c }\n"
                                   "sphere { material m }\n";
        mcrt_scene *ms = mcrt_scene_new();
        const char *info = ms && mcrt_scene_load_string(ms, text, strlen(text), "t") == MCRT_OK
                               ? mcrt_scene_info(ms) : "";
        T_CHECK(strstr(info, "textures") && strstr(info, "\ntexture c: checker, "), "info: %s", info);
        mcrt_scene_free(ms);
    }
    /* An untextured scene has no textures feature; an OBJ material's map is the same call. */
    T_CHECK(load(&s, "sphere { }\n", &d) == 0, "%s", d.msg);
    T_CHECK(!(mc_scene_features(&s) & FEATURE_TEXTURES), "no textures, no feature");
    k = mc_scene_image_texture(&s, "a", "x.png", "m.mtl:3:8");
    T_CHECK(k == 0 && mc_scene_image_texture(&s, "b", "x.png", "m.mtl:9:8") == k
                && s.image_count == 1 && !strcmp(s.images[0].origin, "m.mtl:3:8"),
            "the same file twice is one texture");
    mc_scene_free(&s);
}

/* The textured furnace. A diffuse quad under the white sky, filling the view exactly, with an
 * albedo map of w x h texels: every bounce off it escapes (a plane cannot see itself), so the
 * radiance leaving a point is its albedo ρ(u, v) exactly (∫ ρ/π · 1 · cos dω = ρ), and by BSDF
 * sampling alone every sample carries ρ(u, v) at its point without noise. The film is 2k texels
 * per texel across, so that the bilinear cells' edges (the texel centres) lie on pixel edges:
 * inside a pixel ρ is one bilinear function, whose mean over the pixel is its value at the
 * pixel's centre. The samples' mean deviates from that mean only by the sampling of ρ across
 * the pixel: by Popoviciu's inequality its standard deviation is at most (max − min)/(2√n) over
 * the pixel's corners (a bilinear function's extremes on a rectangle are at its corners). */
#define FW 4
#define FH 4
#define FK 4 /* pixels per half texel */
static double furnace_rho(const float *tex, double u, double v, int c)
{
    /* An independent bilinear lookup, in double, for u, v in [0, 1]. */
    double x = u * FW - 0.5, y = (1.0 - v) * FH - 0.5, x0 = floor(x), y0 = floor(y), ax = x - x0, ay = y - y0;
    int i0 = ((int)x0 + FW) % FW, j0 = ((int)y0 + FH) % FH, i1 = (i0 + 1) % FW, j1 = (j0 + 1) % FH;
#define T(i, j) ((double)tex[3 * ((j) * FW + (i)) + c])
    return (1 - ay) * ((1 - ax) * T(i0, j0) + ax * T(i1, j0)) + ay * ((1 - ax) * T(i0, j1) + ax * T(i1, j1));
#undef T
}

static void test_furnace(void)
{
    enum { W = 2 * FK * FW, H = 2 * FK * FH, SPP = 64 };
    float tex[FW * FH * 3];
    char p[256], text[768];
    struct t_render_opts o;
    double half = 5.0 * tan(20.0 * 3.14159265358979323846 / 180.0), worst = 0.0, sum = 0.0, var = 0.0;
    int i, j, c, pass, bad = 0;
    mc_diag d;
    for (i = 0; i < FW * FH * 3; i++) /* texels far apart, from 0.05 to 0.95 */
        tex[i] = 0.05f + 0.9f * (float)((i * 7) % 11) / 10.0f;
    T_CHECK(mc_image_write(at(p, "albedo.pfm"), tex, FW, FH, &d) == MCRT_OK, "%s", d.msg);
    snprintf(text, sizeof text,
             "film { width %d height %d spp %d }\n"
             "integrator { strategy bsdf }\n"
             "texture albedo { image \"%s\" }\n"
             "material m { diffuse texture albedo }\n"
             "quad { corner %.9g %.9g 0 edge1 %.9g 0 0 edge2 0 %.9g 0 material m }\n",
             W, H, SPP, at(p, "albedo.pfm"), -half, -half, 2 * half, 2 * half);
    for (pass = 0; pass < 2; pass++) {
        int w, h;
        float *img;
        memset(&o, 0, sizeof o);
        o.threads = 2;
        o.all_features = pass; /* the textured kernel, then the general one */
        img = t_render(text, &o, &w, &h, NULL);
        if (!img || w != W || h != H) {
            T_CHECK(0, "render failed");
            free(img);
            return;
        }
        for (j = 0; j < H; j++)
            for (i = 0; i < W; i++)
                for (c = 0; c < 3; c++) {
                    double u0 = (double)i / W, u1 = (i + 1.0) / W, v0 = 1.0 - (j + 1.0) / H, v1 = 1.0 - (double)j / H;
                    double want = furnace_rho(tex, 0.5 * (u0 + u1), 0.5 * (v0 + v1), c);
                    double k[4], lo, hi, sigma, z;
                    int q;
                    /* The corners, nudged inside so that each is taken from the pixel's own cell. */
                    k[0] = furnace_rho(tex, u0 + 1e-9, v0 + 1e-9, c);
                    k[1] = furnace_rho(tex, u1 - 1e-9, v0 + 1e-9, c);
                    k[2] = furnace_rho(tex, u0 + 1e-9, v1 - 1e-9, c);
                    k[3] = furnace_rho(tex, u1 - 1e-9, v1 - 1e-9, c);
                    lo = hi = k[0];
                    for (q = 1; q < 4; q++) {
                        lo = fmin(lo, k[q]);
                        hi = fmax(hi, k[q]);
                    }
                    /* Plus float rounding of the render (1e-5 of the value at most). */
                    sigma = (hi - lo) / (2.0 * sqrt((double)SPP)) + 1e-5;
                    z = (img[3 * (j * W + i) + c] - want) / sigma;
                    worst = fmax(worst, fabs(z));
                    bad += fabs(z) > 5.0;
                    sum += img[3 * (j * W + i) + c] - want;
                    var += sigma * sigma;
                }
        free(img);
    }
    /* 5σ per value: a chance of 6e-7 each (Gaussian), under 0.01 over the 2·3·W·H values; the bound
     * on σ only errs high. The mean error against its own bound. */
    T_CHECK(bad == 0, "%d of %d pixel values beyond 5 sigma of the closed form (worst %.2f sigma)", bad,
            2 * 3 * W * H, worst);
    T_CHECK(fabs(sum) <= 5.0 * sqrt(var), "mean error %.3g beyond 5 sigma (%.3g)", sum / (6.0 * W * H),
            5.0 * sqrt(var) / (6.0 * W * H));
    T_NOTE("textured furnace %dx%d, %d spp: worst |z| %.2f (sigma bounded by the texel range)", W, H,
           SPP, worst);
}

int main(void)
{
    snprintf(scratch, sizeof scratch, "/tmp/mcrt_test_texture_%d", (int)getpid());
    if (mkdir(scratch, 0700) != 0) {
        printf("FAIL cannot make %s\n", scratch);
        return 1;
    }
    test_bilinear();
    test_checker();
    test_image_texture();
    test_scene_language();
    test_furnace();
    {
        char p[256];
        unlink(at(p, "t.pfm"));
        unlink(at(p, "t.png"));
        unlink(at(p, "albedo.pfm"));
        rmdir(scratch);
    }
    return t_done();
}
