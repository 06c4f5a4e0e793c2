/* pov.c: a scene in POV-Ray 3.7 SDL, with every quantity mapped as measured in
 * shared/research/povray-mapping.md (section 1 and the snippets of section 6), or refused. */
#include "export/pov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/file.h"
#include "export/export.h"

/* fade_distance of every light: POV-Ray's attenuation 2/(1 + (d/FD)²) is the inverse square law
 * times 2·FD² up to a relative FD²/d² (mapping note: 1e-3 gives ≤ 4.7e-4 at d = 1). */
#define FD 0.001
/* Radiosity bounces for an unlimited path depth: POV-Ray's cap; the truncated indirect fraction is
 * ρ^k (mapping note, section 3), 0.7^20 = 8e-4 for the brightest wall of a Cornell box. */
#define MAX_RECURSION 20
/* max_trace_level for an unlimited path depth (mcrt ends such paths by unbiased Russian roulette,
 * POV-Ray needs a cap): after 64 bounces even two facing mirrors of reflectance 0.9 carry
 * 0.9^64 ≈ 1e-3. */
#define MAX_TRACE 64
/* Lens samples per pixel, N×N fixed (mapping note: N ≥ 100 fills the lens disc; fewer and
 * POV-Ray's variance test stops early). */
#define BLUR_SAMPLES 100

static const double PI = 3.14159265358979323846;

/* ---- what POV-Ray can reproduce ---- */

/* Diffuse interreflection is part of the image: a path integrator allowing a second bounce
 * (direct stops after one). */
static int has_gi(const struct scene *s)
{
    const struct integrator_desc *it = &s->integrator;
    return it->method != INTEGRATOR_DIRECT && (it->max_depth < 0 || it->max_depth >= 2);
}

/* The methods that are the path tracer (integrators list, scene/integrators.h), whose image
 * POV-Ray's radiosity and lights reproduce; an integrator added to the list is refused until it
 * is mapped here. */
static int path_traced(const struct scene *s)
{
    enum integrator_kind k = s->integrator.method;
    return k == INTEGRATOR_PATH || k == INTEGRATOR_DIRECT || k == INTEGRATOR_MIS
           || k == INTEGRATOR_BSDF || k == INTEGRATOR_LIGHT;
}

/* Whether an emitting shape makes every camera sample cast N×N shadow rays. */
static int has_area_light(const struct scene *s)
{
    size_t i;
    for (i = 0; i < s->prim_count; i++)
        if (mc_export_is_emitter(&s->prims[i]))
            return 1;
    return 0;
}

/* What POV-Ray shows of each shape, by enum prim_kind (defined below, after its writers). */
struct pov_shape {
    void (*object)(FILE *f, const struct prim *p); /* the object up to its texture */
    /* As an emitter: the light it is mapped to; NULL: an emitting one is refused. */
    void (*light)(FILE *f, const struct scene *s, const struct prim *p);
    int interior; /* a material with an interior (glass) on it has a verified inside */
};
static const struct pov_shape pov_shapes[PRIM_KIND_COUNT];
/* The writer of each kind of light, by enum light_kind (defined below); area lights are written
 * with their shapes (pov_shapes), the environment is refused, and so is any kind without one. */
typedef void pov_light_fn(FILE *f, const struct light *l);
static pov_light_fn *const pov_lights[LIGHT_KIND_COUNT];

/* A refusal at the scene's first use of construct mark (enum scene_mark), or at none (-1). */
static mcrt_status refuse(const struct scene *s, mc_diag *d, int mark, const char *what,
                          const char *why)
{
    return mc_export_refuse(d, s, mark, "POV-Ray", what, why);
}

/* ---- materials ---- */

/* The declarations of material k: texture Tk, and for a form with an interior also interior Ik. */
static void put_diffuse(FILE *f, const struct scene *s, int k, const struct material *m);
static void put_mirror(FILE *f, const struct scene *s, int k, const struct material *m);
static void put_glass(FILE *f, const struct scene *s, int k, const struct material *m);

/* Why POV-Ray cannot reproduce this glass, or NULL. */
static const char *glass_refusal(const struct material *m)
{
    if (m->alpha >= MC_BSDF_SMOOTH_ALPHA) /* below this mcrt renders the smooth surface (mcrt.5) */
        return "rough glass (POV-Ray has no verified microfacet model)";
    if (m->color.x != 1.0f || m->color.y != 1.0f || m->color.z != 1.0f)
        return "tinted glass (POV-Ray's filter colour is not verified)";
    return NULL;
}

/* The material kinds with a verified POV-Ray form (mapping note); the export refuses every other
 * kind of the material table. interior: the form has an inside, verified on spheres only. */
static const struct pov_form {
    const struct mc_material_kind *kind;
    const char *(*refusal)(const struct material *m); /* NULL: every parameter set maps */
    void (*put)(FILE *f, const struct scene *s, int k, const struct material *m);
    int interior;
} pov_forms[] = {
    {MC_MATERIAL_KIND(diffuse), NULL, put_diffuse, 0},
    {MC_MATERIAL_KIND(mirror), NULL, put_mirror, 0},
    {MC_MATERIAL_KIND(glass), glass_refusal, put_glass, 1},
};

static const struct pov_form *pov_form(const struct material *m)
{
    size_t i;
    for (i = 0; i < sizeof pov_forms / sizeof pov_forms[0]; i++)
        if (pov_forms[i].kind == m->kind)
            return &pov_forms[i];
    return NULL;
}

static mcrt_status check_material(const struct scene *s, const struct material *m, mc_diag *d)
{
    const struct pov_form *form = pov_form(m);
    const char *why;
    char what[128], unmapped[160];
    snprintf(what, sizeof what, "material '%s'", m->name[0] ? m->name : "(default)");
    if (!form) {
        snprintf(unmapped, sizeof unmapped, "%s (POV-Ray has no verified model of it)", m->kind->ops->what);
        return refuse(s, d, -1, what, unmapped);
    }
    if (form->refusal && (why = form->refusal(m)) != NULL)
        return refuse(s, d, -1, what, why);
    return MCRT_OK;
}

/* ---- textures ---- */

/* The POV-Ray image type of an image texture's file, by its suffix, or NULL. */
static const char *pov_image_type(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (dot && (!strcmp(dot, ".png") || !strcmp(dot, ".PNG")))
        return "png";
    if (dot && (!strcmp(dot, ".exr") || !strcmp(dot, ".EXR")))
        return "exr";
    return NULL;
}

/* Why POV-Ray cannot reproduce material m's textures on primitive p, or NULL. Only a diffuse
 * colour on a quad is mapped: there (u, v) is affine in the point, as POV-Ray's planar pattern
 * space carried onto the quad by a matrix (put_texture_transform). */
static const char *texture_refusal(const struct scene *s, const struct prim *p, const struct material *m)
{
    const struct texture *t = m->texture ? &s->textures[m->texture - 1] : NULL;
    if (!t)
        return NULL;
    if (m->kind != MC_MATERIAL_KIND(diffuse))
        return "only a diffuse colour is mapped (POV-Ray's reflection takes no pattern)";
    if (p->kind != PRIM_QUAD)
        return "only a quad's texture coordinates are mapped";
    if (t->kind == TEXTURE_IMAGE && !pov_image_type(s->images[t->image - 1].path))
        return "only PNG and EXR images are mapped (POV-Ray reads no PFM)";
    if (t->kind == TEXTURE_IMAGE && !(m->color.x == 1.0f && m->color.y == 1.0f && m->color.z == 1.0f))
        return "an image scaled by a colour is not mapped (POV-Ray's image_map takes no factor)";
    return NULL;
}

static mcrt_status check_emitter(const struct scene *s, const struct prim *p, mc_diag *d)
{
    const struct material *m = &s->materials[p->material];
    vec3 c = m->color;
    char what[64];
    snprintf(what, sizeof what, "an emitting %s", mc_shape_names[p->kind]);
    if (!pov_shapes[p->kind].light)
        return refuse(s, d, -1, what, "only quads (spotlight-lobed area lights) and spheres (circular "
                               "area lights) are mapped");
    if (p->flags & PRIM_TWO_SIDED)
        return refuse(s, d, MARK_TWO_SIDED_EMITTER, "a two_sided emitter", "POV-Ray's area-light lobe is one-sided");
    if (p->kind == PRIM_SPHERE && (p->flags & PRIM_FLIP))
        return refuse(s, d, -1, "an inward-emitting (flipped) sphere", "it is not a sphere light");
    /* The visible emitter shows emission + diffuse reflection; POV-Ray multiplies emission by the
     * pigment, so a channel of albedo 0 under a nonzero albedo in another has no exact form. */
    if (m->kind != MC_MATERIAL_KIND(diffuse))
        return refuse(s, d, -1, "an emitter with a non-diffuse material",
                      "the visible emitter is mapped as emission over a Lambertian pigment");
    if (!v3_is_zero(c) && (c.x == 0.0f || c.y == 0.0f || c.z == 0.0f))
        return refuse(s, d, -1, "an emitter whose albedo is zero in some channels only",
                      "POV-Ray's emission is scaled by the pigment");
    return MCRT_OK;
}

/* Whether a prepared scene can be exported faithfully: MCRT_OK, or MCRT_ERR_UNSUPPORTED with a
 * message naming the first feature POV-Ray cannot reproduce (the rules are listed in mcrt(1),
 * `mcrt pov`). */
static mcrt_status pov_check(const struct scene *s, mc_diag *d)
{
    size_t i;
    int specular = 0;
    mcrt_status st;
    const char *why;
    if (s->env_light >= 0) /* given, or the default sky of a scene without lights */
        return refuse(s, d, MARK_ENVIRONMENT, "the environment light", "a constant sky has no verified POV-Ray mapping");
    if (s->integrator.max_depth == 0)
        return refuse(s, d, MARK_INTEGRATOR, "max_depth 0", "POV-Ray always lights the surfaces it sees");
    if (!path_traced(s))
        return refuse(s, d, MARK_INTEGRATOR, "this integrator method", "only the path tracer's have a mapping");
    for (i = 0; i < s->light_count; i++)
        if (s->lights[i].kind != LIGHT_AREA && !pov_lights[s->lights[i].kind]) {
            char what[64];
            snprintf(what, sizeof what, "a %s light", mc_light_names[s->lights[i].kind]);
            return refuse(s, d, -1, what, "the kind has no POV-Ray mapping");
        }
    for (i = 0; i < s->prim_count; i++) {
        const struct prim *p = &s->prims[i];
        const struct material *m = &s->materials[p->material];
        if (!pov_shapes[p->kind].object)
            return refuse(s, d, -1, mc_shape_names[p->kind], "the shape has no POV-Ray mapping");
        if ((st = check_material(s, m, d)) != MCRT_OK)
            return st;
        if ((why = texture_refusal(s, p, m)) != NULL) {
            char what[128];
            snprintf(what, sizeof what, "the texture of material '%s'", m->name);
            return refuse(s, d, MARK_TEXTURE, what, why);
        }
        if (p->normals >= 0 && !v3_is_zero(s->normals[p->normals]))
            return refuse(s, d, -1, "smooth-shaded triangles", "interpolated normals are not verified");
        if (p->motion && s->motions[p->motion - 1].omega != 0.0f)
            return refuse(s, d, -1, "spin", "only translations are exported as clock motion");
        if (pov_form(m)->interior && !pov_shapes[p->kind].interior) {
            char what[96];
            snprintf(what, sizeof what, "%s on a %s", m->kind->name, mc_shape_names[p->kind]);
            return refuse(s, d, -1, what, "only spheres have a verified inside");
        }
        if (mc_export_is_emitter(p) && (st = check_emitter(s, p, d)) != MCRT_OK)
            return st;
        specular |= (mc_material_lobes(m) & MC_LOBE_SPECULAR) != 0;
    }
    /* With area lights, mcrt finds light -> specular -> diffuse paths (a diffuse bounce that
     * hits an emitter through a mirror or glass), which POV-Ray lacks (no caustics); and it shows
     * an emitter seen after the last allowed bounce, which POV-Ray does not trace (its trace level
     * counts rays, so it matches mcrt's depth for shading, not for emission one ray further).
     * Point lights are invisible and reach nothing through a specular surface in either. */
    if (specular && has_area_light(s))
        return refuse(s, d, -1, "a mirror or glass with area lights",
                      "POV-Ray lacks light -> specular -> diffuse paths (caustics) "
                      "and emitters one ray past the depth limit");
    return MCRT_OK;
}

/* ---- writing SDL ---- */

/* Seven significant digits print a scene's decimal values as written (floats hold 7.2); adding
 * 0 turns −0 into 0. */
static void put_vec(FILE *f, vec3 v)
{
    fprintf(f, "<%.7g, %.7g, %.7g>", v.x + 0.0f, v.y + 0.0f, v.z + 0.0f);
}

static void put_rgb(FILE *f, vec3 c, double scale)
{
    fprintf(f, "rgb <%.7g, %.7g, %.7g>", c.x * scale, c.y * scale, c.z * scale);
}

/* " translate MC_T*<v>" for a moving primitive: its place at time 0 plus time·velocity. */
static void put_motion(FILE *f, const struct scene *s, const struct prim *p)
{
    if (!p->motion)
        return;
    fputs(" translate MC_T*", f);
    put_vec(f, s->motions[p->motion - 1].move);
}

/* The antialiasing flags: a box filter over exactly the pixel by a (2^(n−1)+1)² trapezoid grid
 * (mapping note, "Box pixel filter": against the exact coverage of a hard edge, R5 misses by
 * 0.0036 max, R4 by 0.013, R3 by 0.044). R5 for every case: 289 samples per pixel, under area
 * lights each casting N² = 256 shadow rays (about 2 CPU-min at 128×96: references are made once).
 * Motion blur averages K clock frames at (i + 1/2)/K, each at R5 too. */
static void put_flags(FILE *f, const struct scene *s)
{
    fprintf(f, "// povray +W%d +H%d +FE +A0.0 +AM2 +R5 -J", s->film.width, s->film.height);
    if (mc_export_moves(s))
        fprintf(f, " +KFI1 +KFF%d +KI%.7g +KF%.7g", MC_POV_FRAMES, 0.5 / MC_POV_FRAMES,
                1.0 - 0.5 / MC_POV_FRAMES);
    fputc('\n', f);
}

static void put_globals(FILE *f, const struct scene *s)
{
    const struct integrator_desc *it = &s->integrator;
    int depth = it->method == INTEGRATOR_DIRECT ? 1 : it->max_depth < 0 ? MAX_TRACE : it->max_depth;
    /* A POV-Ray trace level is one ray: level 1 is the camera ray, each specular bounce adds one,
     * so mcrt's bounce limit is the trace limit. adc_bailout 0 keeps faint specular chains. */
    fprintf(f, "global_settings {\n  assumed_gamma 1.0\n  max_trace_level %d\n  adc_bailout 0\n",
            depth < MAX_TRACE ? depth : MAX_TRACE);
    if (has_gi(s)) {
        int k = it->max_depth < 0 || it->max_depth - 1 > MAX_RECURSION ? MAX_RECURSION
                                                                         : it->max_depth - 1;
        /* The finest measured settings (mapping note, section 3): 0.00% mean, 0.19% max in a
         * closed sphere; the note's default row (count 200, error_bound 0.5) was 1.2% too bright
         * in the gi-box case and 1.75% in the Cornell box, these 0.15%. */
        fprintf(f, "  radiosity {\n    count 800 nearest_count 20 error_bound 0.1 "
                   "recursion_limit %d\n    pretrace_start 0.08 pretrace_end 0.005 "
                   "low_error_factor 0.5 gray_threshold 0\n    brightness 1 minimum_reuse 0.015 "
                   "adc_bailout 0.0001 always_sample off normal off media off\n  }\n",
                k);
    }
    fputs("}\n", f);
}

/* The camera frame of mcrt.5 (CONVENTIONS) given as explicit direction, right and up vectors:
 * POV-Ray casts direction + (x/W − 1/2)·right + (1/2 − y/H)·up, which is mcrt's film map when
 * direction = f/(2 tan(fov/2)), right = r·W/H and up = u. With explicit vectors no handedness
 * enters (it would only through look_at, rotate and sky), so coordinates are copied unchanged. */
static void put_camera(FILE *f, const struct scene *s)
{
    const struct camera_desc *c = &s->camera;
    vec3 view = v3_sub(c->look, c->eye);
    vec3 fw = v3_normalize(view);
    vec3 r = v3_normalize(v3_cross(fw, c->up));
    vec3 u = v3_cross(r, fw);
    double tan_half = tan(0.5 * c->fov * PI / 180.0);
    int m = !v3_is_zero(c->move);
    fputs("camera {\n  perspective\n  location ", f);
    put_vec(f, c->eye);
    if (m) {
        fputs(" + MC_T*", f);
        put_vec(f, c->move);
    }
    fputs("\n  direction ", f);
    put_vec(f, v3_scale(fw, (float)(0.5 / tan_half)));
    fputs("\n  right ", f);
    put_vec(f, v3_scale(r, (float)s->film.width / (float)s->film.height));
    fputs("\n  up ", f);
    put_vec(f, u);
    fputc('\n', f);
    if (c->lens_radius > 0.0f) {
        float focus = c->focus_distance > 0.0f ? c->focus_distance : v3_length(view);
        /* POV-Ray's lens radius is aperture/4 (mapping note, thin-lens row); the focus plane is
         * at depth `focus` along the view axis, as in mcrt. */
        fprintf(f, "  aperture %.7g\n  focal_point ", 4.0 * c->lens_radius);
        put_vec(f, v3_madd(c->eye, fw, focus));
        if (m) {
            fputs(" + MC_T*", f);
            put_vec(f, c->move);
        }
        fprintf(f, "\n  blur_samples %d, %d\n  confidence 0.9999\n  variance 0\n", BLUR_SAMPLES,
                BLUR_SAMPLES);
    }
    fputs("}\n", f);
}

/* "#declare Tk = texture { pigment { ", under a comment naming the material. */
static void put_texture_head(FILE *f, int k, const struct material *m)
{
    fprintf(f, "// material '%s'\n#declare T%d = texture { pigment { ", m->name, k);
}

/* A texture as a POV-Ray pigment in its pattern space (s, t) = (u·scale + offset), z = 1/2,
 * which put_texture_transform carries onto each quad: a checker (POV-Ray's `checker`, colour 1
 * where ⌊x⌋ + ⌊y⌋ + ⌊z⌋ is even: z = 1/2 keeps ⌊z⌋ = 0, away from its jump at 0), or an image
 * map (planar: the image over the unit square of x, y, its bottom row at y = 0, repeated;
 * `interpolate 2` is bilinear; a PNG decoded from sRGB as mcrt does). */
static void put_pattern(FILE *f, const struct scene *s, const struct material *m)
{
    const struct texture *t = &s->textures[m->texture - 1];
    if (t->kind == TEXTURE_CHECKER) {
        fputs("checker ", f);
        put_rgb(f, v3_mul(m->color, t->even), 1.0);
        fputs(", ", f);
        put_rgb(f, v3_mul(m->color, t->odd), 1.0);
    } else {
        const char *path = s->images[t->image - 1].path, *type = pov_image_type(path);
        fprintf(f, "image_map { %s \"%s\"%s interpolate 2 }", type, path,
                strcmp(type, "png") == 0 ? " gamma srgb" : "");
    }
}

static void put_diffuse(FILE *f, const struct scene *s, int k, const struct material *m)
{
    put_texture_head(f, k, m);
    if (m->texture)
        put_pattern(f, s, m);
    else
        put_rgb(f, m->color, 1.0);
    fputs(" } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }\n", f);
}

/* Constant reflectance at every angle (mapping note, mirror rows). */
static void put_mirror(FILE *f, const struct scene *s, int k, const struct material *m)
{
    (void)s;
    put_texture_head(f, k, m);
    fputs("rgb 0 } finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { ", f);
    put_rgb(f, m->color, 1.0);
    fputs(" } } }\n", f);
}

/* Unpolarised Fresnel, TIR included (mapping note, dielectric rows); checked smooth and clear. */
static void put_glass(FILE *f, const struct scene *s, int k, const struct material *m)
{
    (void)s;
    put_texture_head(f, k, m);
    fprintf(f, "rgbf 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { 0, 1 "
               "fresnel on } conserve_energy } }\n#declare I%d = interior { ior %.7g }\n",
            k, m->ior);
}

/* The visible part of an emitter: emission Le over its albedo ρ (emission is scaled by the
 * pigment, so it is Le/ρ over pigment ρ, or Le over white with no diffuse reflection when ρ = 0).
 * no_radiosity: the light_source already delivers its direct light. */
static void put_emitter_finish(FILE *f, const struct scene *s, const struct prim *p)
{
    vec3 a = s->materials[p->material].color, e = p->emit;
    if (v3_is_zero(a)) {
        fputs("pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission ", f);
        put_rgb(f, e, 1.0);
    } else {
        fputs("pigment { ", f);
        put_rgb(f, a, 1.0);
        fputs(" } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 emission ", f);
        put_rgb(f, v3(e.x / a.x, e.y / a.y, e.z / a.z), 1.0);
    }
    fputs(" } no_radiosity", f);
}

static vec3 quad_normal(const struct prim *p)
{
    vec3 n = v3_normalize(v3_cross(p->p[1], p->p[2]));
    return (p->flags & PRIM_FLIP) ? v3_neg(n) : n;
}

static void put_polygon(FILE *f, vec3 o, vec3 e1, vec3 e2)
{
    fputs("polygon { 5, ", f);
    put_vec(f, o);
    fputs(", ", f);
    put_vec(f, v3_add(o, e1));
    fputs(", ", f);
    put_vec(f, v3_add(v3_add(o, e1), e2));
    fputs(", ", f);
    put_vec(f, v3_add(o, e2));
    fputs(", ", f);
    put_vec(f, o);
}

/* A one-sided Lambertian quad of radiance Le: N×N grid sub-lights spanning the quad (axes scaled
 * by (N−1)/N since the grid includes its end points), each given the cos lobe of a Lambertian
 * emitter by a spotlight with radius = falloff = 90° and tightness 1; total intensity Le·A along
 * the normal, with the 1/π of the receiving BRDF folded in: Le·A/(2π·FD²) (mapping note 6.5). */
static void put_quad_light(FILE *f, const struct scene *s, const struct prim *p)
{
    vec3 e1 = p->p[1], e2 = p->p[2];
    vec3 centre = v3_add(p->p[0], v3_scale(v3_add(e1, e2), 0.5f));
    double area = v3_length(v3_cross(e1, e2));
    float g = (float)(MC_POV_GRID - 1) / MC_POV_GRID;
    fputs("light_source { ", f);
    put_vec(f, centre);
    fputs(" color ", f);
    put_rgb(f, p->emit, area / (2.0 * PI * FD * FD));
    fprintf(f, "\n  fade_distance %g fade_power 2\n  spotlight point_at ", FD);
    put_vec(f, v3_add(centre, quad_normal(p)));
    fputs(" radius 90 falloff 90 tightness 1\n  area_light ", f);
    put_vec(f, v3_scale(e1, g));
    fputs(", ", f);
    put_vec(f, v3_scale(e2, g));
    fprintf(f, ", %d, %d jitter area_illumination on\n  looks_like { ", MC_POV_GRID, MC_POV_GRID);
    /* looks_like objects are placed relative to the light's location. */
    put_polygon(f, v3_scale(v3_add(e1, e2), -0.5f), e1, e2);
    fputc(' ', f);
    put_emitter_finish(f, s, p);
    fputs(" } }", f);
    put_motion(f, s, p);
    fputs(" }\n", f);
}

/* A sphere of radius R and radiance L is, seen from outside, exactly a point of intensity πR²L;
 * POV-Ray renders it as a disc of N×N isotropic points facing each shading point (circular
 * orient), biased by about −0.75 (R/d)² on axis (mapping note 6.4). Colour πR²L/(2π·FD²). */
static void put_sphere_light(FILE *f, const struct scene *s, const struct prim *p)
{
    double r = p->p[1].x, g = 2.0 * r * (MC_POV_GRID - 1) / MC_POV_GRID;
    fputs("light_source { ", f);
    put_vec(f, p->p[0]);
    fputs(" color ", f);
    put_rgb(f, p->emit, r * r / (2.0 * FD * FD));
    fprintf(f, "\n  fade_distance %g fade_power 2\n  area_light <%.7g, 0, 0>, <0, %.7g, 0>, %d, "
               "%d circular orient jitter area_illumination on\n  looks_like { sphere { 0, %.7g ",
            FD, g, g, MC_POV_GRID, MC_POV_GRID, r);
    put_emitter_finish(f, s, p);
    fputs(" } }", f);
    put_motion(f, s, p);
    fputs(" }\n", f);
}

/* An isotropic point of intensity I: colour I/(2π·FD²) with fade_power 2 (mapping note 6.1). */
static void put_point_light(FILE *f, const struct light *l)
{
    fputs("light_source { ", f);
    put_vec(f, l->position);
    fputs(" color ", f);
    put_rgb(f, l->intensity, 1.0 / (2.0 * PI * FD * FD));
    fprintf(f, " fade_distance %g fade_power 2 }\n", FD);
}

static pov_light_fn *const pov_lights[LIGHT_KIND_COUNT] = {[LIGHT_POINT] = put_point_light};

static void put_sphere(FILE *f, const struct prim *p)
{
    fputs("sphere { ", f);
    put_vec(f, p->p[0]);
    fprintf(f, ", %.7g ", p->p[1].x);
}

static void put_quad(FILE *f, const struct prim *p)
{
    put_polygon(f, p->p[0], p->p[1], p->p[2]);
    fputc(' ', f);
}

static void put_disk(FILE *f, const struct prim *p)
{
    fputs("disc { ", f);
    put_vec(f, p->p[0]);
    fputs(", ", f);
    put_vec(f, p->p[1]);
    fprintf(f, ", %.7g ", p->p[2].x);
}

static void put_triangle(FILE *f, const struct prim *p)
{
    fputs("triangle { ", f);
    put_vec(f, p->p[0]);
    fputs(", ", f);
    put_vec(f, p->p[1]);
    fputs(", ", f);
    put_vec(f, p->p[2]);
    fputc(' ', f);
}

static const struct pov_shape pov_shapes[PRIM_KIND_COUNT] = {
    [PRIM_TRIANGLE] = {put_triangle, NULL, 0},
    [PRIM_SPHERE] = {put_sphere, put_sphere_light, 1},
    [PRIM_QUAD] = {put_quad, put_quad_light, 0},
    [PRIM_DISK] = {put_disk, NULL, 0},
};

/* The pattern space of put_pattern onto quad p: (s, t, 1/2) to corner + u·edge1 + v·edge2 for
 * (u, v) = ((s, t) − offset)/scale, its z along the normal (POV-Ray's matrix maps (x, y, z) to
 * x·row1 + y·row2 + z·row3 + row4). */
static void put_texture_transform(FILE *f, const struct texture *t, const struct prim *p)
{
    vec3 e1 = p->p[1], e2 = p->p[2], n = v3_normalize(v3_cross(e1, e2)), o = p->p[0];
    fprintf(f, " translate <%.7g, %.7g, -0.5> scale <%.9g, %.9g, 1>", -t->offset.x + 0.0f,
            -t->offset.y + 0.0f, 1.0 / t->scale.x, 1.0 / t->scale.y);
    fprintf(f, " matrix <%.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g, %.7g>",
            e1.x + 0.0f, e1.y + 0.0f, e1.z + 0.0f, e2.x + 0.0f, e2.y + 0.0f, e2.z + 0.0f,
            n.x + 0.0f, n.y + 0.0f, n.z + 0.0f, o.x + 0.0f, o.y + 0.0f, o.z + 0.0f);
}

static void put_prim(FILE *f, const struct scene *s, const struct prim *p)
{
    const struct material *m = &s->materials[p->material];
    pov_shapes[p->kind].object(f, p);
    fprintf(f, "texture { T%d", p->material);
    if (m->texture)
        put_texture_transform(f, &s->textures[m->texture - 1], p);
    fputs(" }", f);
    if (pov_form(&s->materials[p->material])->interior)
        fprintf(f, " interior { I%d }", p->material);
    put_motion(f, s, p);
    fputs(" }\n", f);
}

/* The whole file; 0 when out of memory. */
static int put_scene(FILE *f, const struct scene *s)
{
    size_t i;
    unsigned char *used = mc_calloc(s->material_count, 1); /* materials declared so far */
    const struct prim **prims = mc_export_sorted_prims(s);
    if (!used || !prims) {
        free(used);
        free(prims);
        return 0;
    }
    fputs("// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).\n", f);
    put_flags(f, s);
    if (s->film.filter != FILTER_BOX)
        fputs("// The scene's pixel filter is not box: this reference is box-filtered.\n", f);
    fputs("#version 3.7;\n", f);
    put_globals(f, s);
    if (mc_export_moves(s))
        fprintf(f, "// Scene time: the shutter [%.7g, %.7g] spanned by the clock in [0, 1].\n"
                   "#declare MC_T = %.7g + clock*%.7g;\n",
                s->camera.shutter[0], s->camera.shutter[1], s->camera.shutter[0],
                s->camera.shutter[1] - s->camera.shutter[0]);
    put_camera(f, s);
    for (i = 0; i < s->prim_count; i++) {
        int k = prims[i]->material;
        if (mc_export_is_emitter(prims[i]) || used[k])
            continue;
        used[k] = 1;
        pov_form(&s->materials[k])->put(f, s, k, &s->materials[k]);
    }
    free(used);
    for (i = 0; i < s->light_count; i++)
        if (pov_lights[s->lights[i].kind])
            pov_lights[s->lights[i].kind](f, &s->lights[i]);
    for (i = 0; i < s->prim_count; i++) {
        const struct prim *p = prims[i];
        if (!mc_export_is_emitter(p))
            put_prim(f, s, p);
        else
            pov_shapes[p->kind].light(f, s, p);
    }
    free(prims);
    return 1;
}

mcrt_status mc_pov_save(const struct scene *s, const char *path, mc_diag *d)
{
    struct mc_output out;
    mcrt_status st = pov_check(s, d);
    if (st != MCRT_OK || (st = mc_output_open(&out, path, d)) != MCRT_OK)
        return st;
    if (!put_scene(out.f, s))
        st = mc_fail(d, MCRT_ERR_NOMEM, "cannot write '%s': out of memory", path);
    return mc_output_close(&out, st, d);
}
