/* mitsuba.c: a scene as a Mitsuba 3 XML scene (format version 3.0.0, variant scalar_rgb), each
 * quantity given to the plugin that computes the same thing, or refused (the table is in mcrt(1),
 * `mcrt mitsuba`, with where the two differ). */
#include "export/mitsuba.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/file.h"
#include "export/export.h"

#define TARGET "Mitsuba 3"

/* The camera's clipping planes: Mitsuba's rays start at near_clip from the eye (mcrt's at the eye)
 * and end at far_clip (its default 10⁴ would cut large scenes). */
#define NEAR_CLIP 1e-4
#define FAR_CLIP 1e7

static mcrt_status refuse(const struct scene *s, mc_diag *d, int mark, const char *what,
                          const char *why)
{
    return mc_export_refuse(d, s, mark, TARGET, what, why);
}

/* The strategies of scene/integrators.h that sample materials only: they never see point lights,
 * which Mitsuba's path tracer always lights the scene with. */
static int bsdf_only(const struct scene *s)
{
    return s->integrator.method == INTEGRATOR_BSDF
           || (s->integrator.method == INTEGRATOR_PATH && s->integrator.strategy == STRATEGY_BSDF);
}

/* ---- what each kind becomes (the tables are defined below, after their writers) ---- */

typedef void mi_prim_fn(FILE *f, const struct prim *p);
/* By enum prim_kind: the writer of a shape's opening tag and geometry; triangles are gathered into
 * OBJ meshes instead (mesh 1). A kind with neither is refused. */
static const struct mi_shape {
    mi_prim_fn *put;
    int mesh;
} mi_shapes[PRIM_KIND_COUNT];
/* By enum light_kind: the writer of a light that has a block (area lights are written with their
 * shapes); a kind with none, other than area lights, is refused. */
typedef void mi_light_fn(FILE *f, const struct scene *s, const struct light *l);
static mi_light_fn *const mi_lights[LIGHT_KIND_COUNT];
/* ---- XML ---- */

/* Seven significant digits print a scene's decimal values as written (floats hold 7.2); adding 0
 * turns −0 into 0. */
static void put_triple(FILE *f, vec3 v, const char *sep)
{
    fprintf(f, "%.7g%s%.7g%s%.7g", v.x + 0.0f, sep, v.y + 0.0f, sep, v.z + 0.0f);
}

/* Three numbers as XML's vector attributes take them. */
static void put_vec(FILE *f, vec3 v) { put_triple(f, v, ", "); }

static void put_rgb(FILE *f, const char *name, vec3 c)
{
    fprintf(f, "<rgb name=\"%s\" value=\"", name);
    put_vec(f, c);
    fputs("\"/>", f);
}

static void put_float(FILE *f, const char *name, double x)
{
    fprintf(f, "<float name=\"%s\" value=\"%.7g\"/>", name, x);
}

/* A string as XML attribute text. */
static void put_text(FILE *f, const char *t)
{
    for (; *t; t++)
        switch (*t) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*t, f);
        }
}

/* A 4×4 affine map, row-major, whose columns are the images of x, y, z and the origin. */
static void put_to_world(FILE *f, vec3 x, vec3 y, vec3 z, vec3 o)
{
    fprintf(f, "<transform name=\"to_world\"><matrix value=\"%.7g %.7g %.7g %.7g %.7g %.7g %.7g "
               "%.7g %.7g %.7g %.7g %.7g 0 0 0 1\"/></transform>",
            x.x + 0.0f, y.x + 0.0f, z.x + 0.0f, o.x + 0.0f, x.y + 0.0f, y.y + 0.0f, z.y + 0.0f,
            o.y + 0.0f, x.z + 0.0f, y.z + 0.0f, z.z + 0.0f, o.z + 0.0f);
}

/* Mitsuba's path tracer counts the camera ray as one (max_depth 1 shows the emitters seen
 * directly, 2 is direct lighting): mcrt's bounces + 1. Every method is the path tracer's
 * estimate (direct is one bounce; bsdf, light and mis are strategies, sppm converges to it);
 * light_samples changes the noise, not the image. Russian roulette starts after rr_depth
 * bounces in both. */
static void put_integrator(FILE *f, const struct scene *s)
{
    const struct integrator_desc *it = &s->integrator;
    int depth = it->method == INTEGRATOR_DIRECT ? 2 : it->max_depth < 0 ? -1 : it->max_depth + 1;
    fprintf(f, "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"%d\"/>"
               "<integer name=\"rr_depth\" value=\"%d\"/></integrator>\n",
            depth, it->rr_depth);
}

/* Random → independent; stratified → stratified (jittered cells) when spp is a square, else
 * multijitter; Owen-scrambled Sobol → ldsampler (Mitsuba's scrambled (0,2) sequence) when spp is
 * a power of 4, else multijitter: Mitsuba rounds the others' counts up (stratified to a square,
 * ldsampler to a square power of two), which would change the noise. */
static void put_sampler(FILE *f, const struct film_desc *film)
{
    const char *type = "independent";
    int root = 1, square, power4;
    while ((long)(root + 1) * (root + 1) <= film->spp)
        root++;
    square = (long)root * root == film->spp;
    power4 = square && (root & (root - 1)) == 0;
    if (film->sampler == SAMPLER_STRATIFIED)
        type = square ? "stratified" : "multijitter";
    else if (film->sampler == SAMPLER_SOBOL)
        type = power4 ? "ldsampler" : "multijitter";
    fprintf(f, "    <sampler type=\"%s\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n",
            type, film->spp);
}

/* box: Mitsuba's box (radius ½: the pixel); tent 1 − |x| on [−1, 1]: tent of radius 1; mcrt's
 * Gaussian (σ = ½, cut off radially at 3σ): Mitsuba's gaussian of stddev ½, cut off per axis at
 * 4σ with its value there subtracted. Mitsuba weights each sample by the filter and divides by the
 * weights' sum, where mcrt draws offsets from the filter: the same image in the limit. */
static void put_filter(FILE *f, enum filter_kind k)
{
    switch (k) {
    case FILTER_TENT: fputs("<rfilter type=\"tent\"><float name=\"radius\" value=\"1\"/></rfilter>", f); break;
    case FILTER_GAUSSIAN: fputs("<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.5\"/></rfilter>", f); break;
    default: fputs("<rfilter type=\"box\"/>", f); break;
    }
}

/* perspective (a pinhole) or thinlens, fov along y as mcrt's; lookat builds the same frame
 * (right = forward × up), so the image is not mirrored. Mitsuba's thin lens focuses on the plane
 * at focus_distance along the view axis, as mcrt's. */
static void put_sensor(FILE *f, const struct scene *s)
{
    const struct camera_desc *c = &s->camera;
    vec3 view = v3_sub(c->look, c->eye);
    fprintf(f, "  <sensor type=\"%s\">\n    <string name=\"fov_axis\" value=\"y\"/>",
            c->lens_radius > 0.0f ? "thinlens" : "perspective");
    put_float(f, "fov", c->fov);
    put_float(f, "near_clip", NEAR_CLIP);
    put_float(f, "far_clip", FAR_CLIP);
    if (c->lens_radius > 0.0f) {
        put_float(f, "aperture_radius", c->lens_radius);
        put_float(f, "focus_distance", c->focus_distance > 0.0f ? c->focus_distance : v3_length(view));
    }
    fputs("\n    <transform name=\"to_world\"><lookat origin=\"", f);
    put_vec(f, c->eye);
    fputs("\" target=\"", f);
    put_vec(f, c->look);
    fputs("\" up=\"", f);
    put_vec(f, c->up);
    fputs("\"/></transform>\n", f);
    put_sampler(f, &s->film);
    fprintf(f, "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/><integer "
               "name=\"height\" value=\"%d\"/><string name=\"pixel_format\" value=\"rgb\"/>",
            s->film.width, s->film.height);
    put_filter(f, s->film.filter);
    fputs("</film>\n  </sensor>\n", f);
}

/* ---- materials: "m<index>", opaque ones wrapped in twosided (mcrt's reflect on both sides,
 * Mitsuba's are black from behind) ---- */

static void put_diffuse(FILE *f, const char *id, const struct material *m)
{
    fprintf(f, "<bsdf type=\"diffuse\"%s>", id);
    put_rgb(f, "reflectance", m->color);
    fputs("</bsdf>", f);
}

/* A conductor of "none" reflects everything; specular_reflectance multiplies it by the colour. */
static void put_mirror(FILE *f, const char *id, const struct material *m)
{
    fprintf(f, "<bsdf type=\"conductor\"%s><string name=\"material\" value=\"none\"/>", id);
    put_rgb(f, "specular_reflectance", m->color);
    fputs("</bsdf>", f);
}

/* GGX with visible-normal sampling, α as given; smooth below MC_BSDF_SMOOTH_ALPHA as in mcrt. */
static void put_rough(FILE *f, const char *id, const char *smooth, const char *rough,
                      const struct material *m)
{
    int r = m->alpha >= MC_BSDF_SMOOTH_ALPHA;
    fprintf(f, "<bsdf type=\"%s\"%s>", r ? rough : smooth, id);
    if (r) {
        fputs("<string name=\"distribution\" value=\"ggx\"/>", f);
        put_float(f, "alpha", m->alpha);
    }
}

/* The exact Fresnel equations with the tint on transmission only (specular_transmittance). Mitsuba's
 * roughdielectric has no multiple-scattering compensation: rough glass loses the energy mcrt's
 * adds back (Kulla and Conty 2017), visibly at large α. */
static void put_glass(FILE *f, const char *id, const struct material *m)
{
    put_rough(f, id, "dielectric", "roughdielectric", m);
    put_float(f, "int_ior", m->ior);
    put_float(f, "ext_ior", 1.0);
    put_rgb(f, "specular_transmittance", m->color);
    fputs("</bsdf>", f);
}

/* Complex Fresnel with eta and k per channel (a reflectance was turned into them by the parser). */
static void put_metal(FILE *f, const char *id, const struct material *m)
{
    put_rough(f, id, "conductor", "roughconductor", m);
    put_rgb(f, "eta", m->eta);
    put_rgb(f, "k", m->k);
    fputs("</bsdf>", f);
}

/* mcrt's plastic is Mitsuba's plastic with nonlinear true (bsdf/plastic.c): its diffuse term
 * ρ (1 − Fᵢ)(1 − Fₒ) / (π η² (1 − ρ F̄ᵢ)), the bounces under the coat darkening the base's colour;
 * nonlinear false divides by 1 − F̄ᵢ instead, 0.4-0.9% brighter on the blue plastic of
 * tests/crosscheck/emitters.mcrt. The base albedo is written capped as mcrt renders it. Rough: Mitsuba's roughplastic, whose diffuse term is scaled
 * by a precomputed internal-scattering table rather than mcrt's (1 − F)(1 − F) form. */
static void put_plastic(FILE *f, const char *id, const struct material *m)
{
    put_rough(f, id, "plastic", "roughplastic", m);
    put_rgb(f, "diffuse_reflectance", v3_min(m->color, v3s(MC_PLASTIC_MAX_ALBEDO)));
    put_float(f, "int_ior", m->ior < 1.0f ? 1.0f : m->ior);
    put_float(f, "ext_ior", 1.0);
    fputs("<boolean name=\"nonlinear\" value=\"true\"/></bsdf>", f);
}

/* The material kinds of materials.def with a Mitsuba form; any other kind is refused. */
static const struct mi_form {
    const struct mc_material_kind *kind;
    void (*put)(FILE *f, const char *id, const struct material *m);
} mi_forms[] = {
    {MC_MATERIAL_KIND(diffuse), put_diffuse},
    {MC_MATERIAL_KIND(mirror), put_mirror},
    {MC_MATERIAL_KIND(glass), put_glass},
    {MC_MATERIAL_KIND(metal), put_metal},
    {MC_MATERIAL_KIND(plastic), put_plastic},
};
static const size_t mi_form_count = sizeof mi_forms / sizeof mi_forms[0];

static const struct mi_form *mi_form(const struct material *m)
{
    size_t i;
    for (i = 0; i < mi_form_count; i++)
        if (mi_forms[i].kind == m->kind)
            return &mi_forms[i];
    return NULL;
}


static void put_material(FILE *f, int k, const struct material *m)
{
    char id[32];
    snprintf(id, sizeof id, " id=\"m%d\"", k);
    fputs("  ", f);
    if (m->kind == MC_MATERIAL_KIND(glass)) { /* a dielectric has two sides of its own */
        mi_form(m)->put(f, id, m);
        fputc('\n', f);
        return;
    }
    fprintf(f, "<bsdf type=\"twosided\"%s>", id);
    mi_form(m)->put(f, "", m);
    fputs("</bsdf>\n", f);
}

/* ---- lights ---- */

/* Radiant intensity in W/sr in both. */
static void put_point_light(FILE *f, const struct scene *s, const struct light *l)
{
    (void)s;
    fprintf(f, "  <emitter type=\"point\"><point name=\"position\" x=\"%.7g\" y=\"%.7g\" "
               "z=\"%.7g\"/>",
            l->position.x + 0.0f, l->position.y + 0.0f, l->position.z + 0.0f);
    put_rgb(f, "intensity", l->intensity);
    fputs("</emitter>\n", f);
}

/* The constant sky, or an image map. Mitsuba's map looks along −z at u = 0 and along +x at u = ¼
 * (u = atan2(x, −z)/2π, v = acos(y)/π), mcrt's along +z and −x there (light/envmap.h): the
 * half turn about y, then mcrt's orient frame. Mitsuba interpolates the pixels bilinearly, mcrt
 * keeps each constant: they differ within a pixel of the map's edges. */
static void put_environment(FILE *f, const struct scene *s, const struct light *l)
{
    const char *path;
    if (!l->image) {
        fputs("  <emitter type=\"constant\">", f);
        put_rgb(f, "radiance", l->intensity);
        fputs("</emitter>\n", f);
        return;
    }
    path = s->images[l->image - 1].path;
    fputs("  <emitter type=\"envmap\"><string name=\"filename\" value=\"", f);
    if (path[0] != '/') { /* Mitsuba reads it relative to the XML's folder, mcrt to its own */
        char cwd[4096];
        if (getcwd(cwd, sizeof cwd)) {
            put_text(f, cwd);
            fputc('/', f);
        }
    }
    put_text(f, path);
    fputs("\"/>", f);
    put_float(f, "scale", l->intensity.x);
    put_to_world(f, v3_neg(l->orient.t), l->orient.b, v3_neg(l->orient.n), v3s(0.0f));
    fputs("</emitter>\n", f);
}

static mi_light_fn *const mi_lights[LIGHT_KIND_COUNT] = {
    [LIGHT_POINT] = put_point_light, [LIGHT_ENVIRONMENT] = put_environment};

/* ---- shapes ---- */

static void put_sphere(FILE *f, const struct prim *p)
{
    fprintf(f, "  <shape type=\"sphere\"><point name=\"center\" x=\"%.7g\" y=\"%.7g\" z=\"%.7g\"/>",
            p->p[0].x + 0.0f, p->p[0].y + 0.0f, p->p[0].z + 0.0f);
    put_float(f, "radius", p->p[1].x);
}

/* Mitsuba's rectangle is [−1, 1]² in z = 0, facing +z: scaled by half the edges, about the centre;
 * its normal is the map's inverse transpose of z, along edge1 × edge2 as mcrt's front side. */
static void put_rectangle(FILE *f, const struct prim *p)
{
    vec3 e1 = v3_scale(p->p[1], 0.5f), e2 = v3_scale(p->p[2], 0.5f);
    fputs("  <shape type=\"rectangle\">", f);
    put_to_world(f, e1, e2, v3_normalize(v3_cross(e1, e2)), v3_add(p->p[0], v3_add(e1, e2)));
}

/* Mitsuba's disk is the unit disk in z = 0 facing +z: a right-handed frame about the normal,
 * scaled by the radius. */
static void put_disk(FILE *f, const struct prim *p)
{
    vec3 n = p->p[1], t, b;
    float r = p->p[2].x;
    v3_basis(n, &t, &b);
    b = v3_cross(n, t);
    fputs("  <shape type=\"disk\">", f);
    put_to_world(f, v3_scale(t, r), v3_scale(b, r), n, p->p[0]);
}

static const struct mi_shape mi_shapes[PRIM_KIND_COUNT] = {
    [PRIM_SPHERE] = {put_sphere, 0},
    [PRIM_QUAD] = {put_rectangle, 0},
    [PRIM_DISK] = {put_disk, 0},
    [PRIM_TRIANGLE] = {NULL, 1},
};

/* What follows every shape's geometry: its side, material and emission (Lambertian radiance on
 * the front side: Mitsuba's area emitter). */
static void put_shape_tail(FILE *f, const struct prim *p, int flip)
{
    if (flip)
        fputs("<boolean name=\"flip_normals\" value=\"true\"/>", f);
    fprintf(f, "<ref id=\"m%d\"/>", p->material);
    if (mc_export_is_emitter(p)) {
        fputs("<emitter type=\"area\">", f);
        put_rgb(f, "radiance", p->emit);
        fputs("</emitter>", f);
    }
    fputs("</shape>\n", f);
}

/* ---- triangle meshes: one OBJ file per material, emission, side and shading ---- */

static int smooth(const struct scene *s, const struct prim *p)
{
    return p->normals >= 0 && !v3_is_zero(s->normals[p->normals]);
}

/* Whether triangles p and q go into one mesh. */
static int same_mesh(const struct scene *s, const struct prim *p, const struct prim *q)
{
    return p->material == q->material && p->flags == q->flags && smooth(s, p) == smooth(s, q)
           && memcmp(&p->emit, &q->emit, sizeof p->emit) == 0;
}

/* The triangles like `first` as OBJ: flat ones with vertices only (Mitsuba then uses face
 * normals), smooth ones with their corners' normals. A flipped triangle is written wound the other
 * way (its normals reversed), so that Mitsuba's front side is mcrt's. */
static void put_obj(FILE *f, const struct scene *s, const struct prim *const *prims, size_t n,
                    const struct prim *first)
{
    static const int order[2][3] = {{0, 1, 2}, {0, 2, 1}};
    size_t i, count = 0;
    int c;
    fputs("# written by `mcrt mitsuba` (see mcrt(1))\n", f);
    for (i = 0; i < n; i++) {
        const struct prim *p = prims[i];
        const int *o = order[(p->flags & PRIM_FLIP) != 0];
        if (p->kind != PRIM_TRIANGLE || !same_mesh(s, p, first))
            continue;
        for (c = 0; c < 3; c++) {
            fputs("v ", f);
            put_triple(f, p->p[o[c]], " ");
            fputc('\n', f);
        }
        if (smooth(s, p))
            for (c = 0; c < 3; c++) {
                vec3 nv = s->normals[p->normals + o[c]];
                fputs("vn ", f);
                put_triple(f, (p->flags & PRIM_FLIP) ? v3_neg(nv) : nv, " ");
                fputc('\n', f);
            }
        if (smooth(s, p))
            fprintf(f, "f %lu//%lu %lu//%lu %lu//%lu\n", (unsigned long)(3 * count + 1),
                    (unsigned long)(3 * count + 1), (unsigned long)(3 * count + 2),
                    (unsigned long)(3 * count + 2), (unsigned long)(3 * count + 3),
                    (unsigned long)(3 * count + 3));
        else
            fprintf(f, "f %lu %lu %lu\n", (unsigned long)(3 * count + 1),
                    (unsigned long)(3 * count + 2), (unsigned long)(3 * count + 3));
        count++;
    }
}

/* The meshes: firsts[k] is the first triangle of mesh k in the sorted order. */
struct meshes {
    const struct prim **firsts;
    size_t count;
    char **paths;         /* mesh k's file, written */
    size_t path_len;      /* strlen of the XML path without ".xml" */
};

static void free_meshes(struct meshes *m, int remove_files)
{
    size_t k;
    for (k = 0; m->paths && k < m->count; k++) {
        if (m->paths[k] && remove_files)
            remove(m->paths[k]);
        free(m->paths[k]);
    }
    free(m->paths);
    free(m->firsts);
}

static mcrt_status nomem(mc_diag *d, const char *path)
{
    return mc_fail(d, MCRT_ERR_NOMEM, "cannot write '%s': out of memory", path);
}

/* Find the meshes among the sorted prims and write each to its file. */
static mcrt_status write_meshes(struct meshes *m, const struct scene *s,
                                const struct prim *const *prims, const char *path, mc_diag *d)
{
    size_t i, k, len = strlen(path);
    mcrt_status st = MCRT_OK;
    memset(m, 0, sizeof *m);
    if (len > 4 && strcmp(path + len - 4, ".xml") == 0)
        len -= 4;
    m->path_len = len;
    for (i = 0; i < s->prim_count; i++) {
        if (prims[i]->kind != PRIM_TRIANGLE)
            continue;
        for (k = 0; k < m->count && !same_mesh(s, m->firsts[k], prims[i]); k++)
            ;
        if (k < m->count)
            continue;
        if (!(m->count & (m->count - 1))) { /* 0, 1, 2, 4, ...: grow by doubling */
            const struct prim **g = mc_realloc(m->firsts, (m->count ? 2 * m->count : 1) * sizeof *g);
            if (!g)
                return nomem(d, path);
            m->firsts = g;
        }
        m->firsts[m->count++] = prims[i];
    }
    if (m->count && !(m->paths = mc_calloc(m->count, sizeof *m->paths)))
        return nomem(d, path);
    for (k = 0; k < m->count && st == MCRT_OK; k++) {
        struct mc_output out;
        if (!(m->paths[k] = mc_malloc(len + 32)))
            return nomem(d, path);
        sprintf(m->paths[k], "%.*s-mesh%lu.obj", (int)len, path, (unsigned long)k);
        if ((st = mc_output_open(&out, m->paths[k], d)) != MCRT_OK) {
            free(m->paths[k]);
            m->paths[k] = NULL;
            return st;
        }
        put_obj(out.f, s, prims, s->prim_count, m->firsts[k]);
        st = mc_output_close(&out, MCRT_OK, d);
        if (st != MCRT_OK) {
            free(m->paths[k]);
            m->paths[k] = NULL;
        }
    }
    return st;
}

/* The mesh shapes: each file by its name alone (Mitsuba resolves it in the XML's folder). */
static void put_mesh_shapes(FILE *f, const struct scene *s, const struct meshes *m)
{
    size_t k;
    for (k = 0; k < m->count; k++) {
        const char *name = strrchr(m->paths[k], '/');
        fputs("  <shape type=\"obj\"><string name=\"filename\" value=\"", f);
        put_text(f, name ? name + 1 : m->paths[k]);
        fputs("\"/>", f);
        if (!smooth(s, m->firsts[k]))
            fputs("<boolean name=\"face_normals\" value=\"true\"/>", f);
        put_shape_tail(f, m->firsts[k], 0);
    }
}

static void put_scene(FILE *f, const struct scene *s, const struct prim *const *prims,
                      const struct meshes *meshes)
{
    size_t i;
    fputs("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
          "<!-- A Mitsuba 3 scene (variant scalar_rgb) of an mcrt scene, written by `mcrt mitsuba` "
          "(see mcrt(1)). -->\n<scene version=\"3.0.0\">\n",
          f);
    put_integrator(f, s);
    put_sensor(f, s);
    for (i = 0; i < s->material_count; i++)
        put_material(f, (int)i, &s->materials[i]);
    for (i = 0; i < s->light_count; i++)
        if (mi_lights[s->lights[i].kind])
            mi_lights[s->lights[i].kind](f, s, &s->lights[i]);
    for (i = 0; i < s->prim_count; i++) {
        const struct prim *p = prims[i];
        if (mi_shapes[p->kind].put) {
            mi_shapes[p->kind].put(f, p);
            put_shape_tail(f, p, (p->flags & PRIM_FLIP) != 0);
        }
    }
    put_mesh_shapes(f, s, meshes);
    fputs("</scene>\n", f);
}

/* ---- what Mitsuba can reproduce ---- */

/* MCRT_OK, or MCRT_ERR_UNSUPPORTED naming the first construct Mitsuba 3 cannot render as mcrt
 * does, at its place in the scene text (the rules are listed in mcrt(1), `mcrt mitsuba`). */
static mcrt_status mi_check(const struct scene *s, mc_diag *d)
{
    size_t i;
    if (!v3_is_zero(s->camera.move))
        return refuse(s, d, MARK_CAMERA_MOVE, "a moving camera",
                      "Mitsuba 3 has no animated transforms (no motion blur)");
    for (i = 0; i < s->light_count; i++) {
        const struct light *l = &s->lights[i];
        if (l->kind != LIGHT_AREA && !mi_lights[l->kind]) {
            char what[64];
            snprintf(what, sizeof what, "a %s light", mc_light_names[l->kind]);
            return refuse(s, d, -1, what, "the kind has no Mitsuba mapping");
        }
        if (l->kind == LIGHT_POINT && bsdf_only(s))
            return refuse(s, d, MARK_INTEGRATOR, "the bsdf strategy with point lights",
                          "it never sees them, Mitsuba's path tracer always does");
        if (l->kind == LIGHT_ENVIRONMENT && l->image
            && (l->intensity.x != l->intensity.y || l->intensity.y != l->intensity.z))
            return refuse(s, d, MARK_ENVIRONMENT, "a tinted environment map",
                          "Mitsuba's envmap scales its image by one number");
    }
    for (i = 0; i < s->prim_count; i++) {
        const struct prim *p = &s->prims[i];
        const struct material *m = &s->materials[p->material];
        if (!mi_shapes[p->kind].put && !mi_shapes[p->kind].mesh)
            return refuse(s, d, -1, mc_shape_names[p->kind], "the shape has no Mitsuba mapping");
        if (p->motion)
            return refuse(s, d, MARK_SHAPE_MOVE, "a moving shape",
                          "Mitsuba 3 has no animated transforms (no motion blur)");
        if (mc_export_is_emitter(p) && (p->flags & PRIM_TWO_SIDED))
            return refuse(s, d, MARK_TWO_SIDED_EMITTER, "a two_sided emitter",
                          "Mitsuba's area emitters emit from their front side only");
        if (m->texture || m->roughness_texture)
            return refuse(s, d, MARK_TEXTURE, "a textured material",
                          "mcrt's texture coordinates of each shape are not Mitsuba's");
        if (!mi_form(m)) {
            char what[128], why[160];
            snprintf(what, sizeof what, "material '%s'", m->name);
            snprintf(why, sizeof why, "%s has no Mitsuba mapping", m->kind->ops->what);
            return refuse(s, d, -1, what, why);
        }
    }
    return MCRT_OK;
}

mcrt_status mc_mitsuba_save(const struct scene *s, const char *path, mc_diag *d)
{
    struct mc_output out;
    struct meshes meshes;
    const struct prim **prims;
    mcrt_status st = mi_check(s, d);
    if (st != MCRT_OK)
        return st;
    if (!(prims = mc_export_sorted_prims(s)))
        return nomem(d, path);
    st = write_meshes(&meshes, s, prims, path, d);
    if (st == MCRT_OK && (st = mc_output_open(&out, path, d)) == MCRT_OK) {
        put_scene(out.f, s, prims, &meshes);
        st = mc_output_close(&out, st, d);
    }
    free_meshes(&meshes, st != MCRT_OK);
    free(prims);
    return st;
}
