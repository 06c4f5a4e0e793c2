/* texture.h: textures, values that vary over a surface with its texture coordinates (u, v)
 * (mc_scene_uv; man/mcrt.5 "Texture coordinates"): a material's colour and a glossy material's
 * roughness may take one (man/mcrt.5 "texture"). The kinds are the lines of MC_TEXTURES, which the
 * parser, mcrt_names ("texture"), the manual's check and the tests read.
 *
 * Every kind looks up (s, t) = (u·scale_u + offset_u, v·scale_v + offset_v):
 *   image    the image repeated over the unit square: s to the right, t up (t = 0 at the image's
 *            bottom row, as OBJ's vt); texel (x, y) (row y from the top) is centred at
 *            ((x + ½)/w, 1 − (y + ½)/h), and between centres the value is the bilinear blend of the
 *            four nearest texels, wrapping across the edges (pbrt-v4 Image::Bilerp, WrapMode
 *            Repeat). The image is linear RGB, PNG decoded from sRGB by its reader (io/).
 *   checker  `even` where ⌊s⌋ + ⌊t⌋ is even, `odd` where it is odd (POV-Ray's `checker`). */
#ifndef MCRT_TEXTURE_H
#define MCRT_TEXTURE_H

#include <stddef.h>

#include "core/diag.h"
#include "core/names.h"
#include "core/vec.h"

#define MC_TEXTURES(X) X(TEXTURE_IMAGE, image) X(TEXTURE_CHECKER, checker)
enum texture_kind { MC_TEXTURES(MC_NAMES_ENUM) };
#define TEXTURE_KIND_COUNT (0 MC_TEXTURES(MC_NAMES_COUNT))
/* The kinds' names (the texture block's keywords), NULL at [TEXTURE_KIND_COUNT]. */
extern const char *const mc_texture_names[TEXTURE_KIND_COUNT + 1];

struct texture {
    char name[64];
    enum texture_kind kind;
    vec2 scale, offset;      /* (s, t) = (u, v)·scale + offset: (1, 1) and (0, 0) by default */
    vec3 even, odd;          /* checker: the colours of its two sets of squares */
    int image;               /* image: 1 + the scene's image index (scene.h) */
    const float *rgb;        /* image: its w·h·3 texels, rows top to bottom (the scene image's,
                                set by mc_scene_prepare) */
    int w, h;
};

/* The texture's value at texture coordinates uv. */
vec3 mc_texture_eval(const struct texture *t, vec2 uv);
/* The bilinear, repeating lookup of image rgb (w·h·3, rows top to bottom) at (s, t), t up. */
vec3 mc_texture_bilinear(const float *rgb, int w, int h, float s, float t);
/* Check an image texture's texels: reflectances and roughnesses, each in [0, 1]; otherwise
 * "ORIGIN: texture 'NAME': pixel (x, y) has a negative value" (or a NaN value, a value above 1) (MCRT_ERR_PARSE: bad input). */
mcrt_status mc_texture_check(const struct texture *t, const char *origin, mc_diag *d);

#endif
