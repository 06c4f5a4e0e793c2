/* test_parse.c: the scene-language parser and the OBJ reader: valid scenes into exact struct
 * values, every malformed fixture in tests/parse_errors/ to its exact message, and a fixed-seed
 * mutation loop that must never crash (run it under ASan+UBSan). Runs from the repository root. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/rng.h"
#include "file_util.h"
#include "mcrt.h"
#include "scene/obj.h"
#include "scene/scene.h"
#include "t.h"

#define ERR_DIR "tests/parse_errors"

/* Parse from an exactly sized heap copy with no terminating NUL, so that ASan reports any read
 * past the end. */
static mcrt_status parse_n(struct scene *s, const char *text, size_t len, const char *name,
                           const char *base_dir, mc_diag *d)
{
    char *copy = malloc(len ? len : 1);
    mcrt_status st;
    memcpy(copy, text, len);
    d->msg[0] = '\0';
    st = mc_scene_parse(s, copy, len, name, base_dir, d);
    free(copy);
    return st;
}

static mcrt_status parse(struct scene *s, const char *text, const char *base_dir, mc_diag *d)
{
    return parse_n(s, text, strlen(text), "t.mcrt", base_dir, d);
}

static int near3(vec3 a, float x, float y, float z)
{
    /* Parsed decimal values: float rounding of the input, far below 1e-6 for these magnitudes;
     * transformed values add a few float operations of rounding. */
    return fabsf(a.x - x) <= 1e-5f && fabsf(a.y - y) <= 1e-5f && fabsf(a.z - z) <= 1e-5f;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        printf("FAIL cannot write %s\n", path);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

/* ---- Valid scenes ---- */

static void test_minimal(void)
{
    struct scene s;
    mc_diag d;
    mc_scene_init(&s);
    T_CHECK(parse(&s, "sphere { }", NULL, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(s.prim_count == 1, "%zu prims", s.prim_count);
    if (s.prim_count == 1) {
        const struct prim *p = &s.prims[0];
        T_CHECK(p->kind == PRIM_SPHERE && p->material == 0 && p->light == -1 && p->normals == -1
                    && p->flags == 0,
                "kind %d material %d", p->kind, p->material);
        T_CHECK(near3(p->p[0], 0, 0, 0) && p->p[1].x == 1.0f && v3_is_zero(p->emit), "defaults");
    }
    T_CHECK(s.film.width == 512 && s.film.height == 512 && s.film.spp == 16
                && s.film.sampler == SAMPLER_SOBOL,
            "film defaults kept");
    T_CHECK(s.integrator.max_depth == -1 && s.integrator.rr_depth == 5, "integrator defaults");
    T_CHECK(s.light_count == 0, "no lights");
    mc_scene_free(&s);
}

static const char full_scene[] =
    "# every block and key\n"
    "film { width 320 height 240 spp 64 sampler random filter box }\n"
    "camera { eye 1 2 3 look 0 1 0 up 0 0 1 fov 55.5 }\n"
    "integrator { method direct max_depth 7 rr_depth 3 }\n"
    "material white { diffuse 0.75 }\n"
    "material red { diffuse 0.7 0.1 0.05 }\n"
    "material chrome { mirror 0.9 0.8 0.7 }\n"
    "material glass { glass ior 1.33 tint 0.9 1 0.95 }\n"
    "material plain_glass { glass }\n"
    "sphere { center 1 -2 3 radius 0.5 material red emit 1 2 3 two_sided flip }\n"
    "quad { corner 0 0 0 edge1 1 0 0 edge2 0 0 -1 material chrome }\n"
    "triangle { v0 0 0 0 v1 0 1 0 v2 0 0 1 material glass two_sided }\n"
    "point_light { position 0 10 0 intensity 100 }\n"
    "point_light { }\n"
    "environment { radiance 0.1 0.2 0.3 }\n";

static void test_full(void)
{
    struct scene s;
    mc_diag d;
    const struct prim *p;
    const struct material *m;
    mc_scene_init(&s);
    T_CHECK(parse(&s, full_scene, NULL, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(s.film.width == 320 && s.film.height == 240 && s.film.spp == 64
                && s.film.sampler == SAMPLER_RANDOM && s.film.filter == FILTER_BOX,
            "film");
    T_CHECK(near3(s.camera.eye, 1, 2, 3) && near3(s.camera.look, 0, 1, 0)
                && near3(s.camera.up, 0, 0, 1) && s.camera.fov == 55.5f,
            "camera");
    T_CHECK(s.integrator.method == INTEGRATOR_DIRECT && s.integrator.max_depth == 7
                && s.integrator.rr_depth == 3,
            "integrator");
    T_CHECK(s.material_count == 6, "%zu materials", s.material_count);
    if (s.material_count == 6) {
        m = s.materials;
        T_CHECK(m[0].kind == MC_MATERIAL_KIND(diffuse) && m[0].name[0] == '\0' && near3(m[0].color, .8f, .8f, .8f),
                "default material");
        T_CHECK(!strcmp(m[1].name, "white") && m[1].kind == MC_MATERIAL_KIND(diffuse)
                    && near3(m[1].color, .75f, .75f, .75f),
                "white");
        T_CHECK(!strcmp(m[2].name, "red") && near3(m[2].color, .7f, .1f, .05f), "red");
        T_CHECK(m[3].kind == MC_MATERIAL_KIND(mirror) && near3(m[3].color, .9f, .8f, .7f), "chrome");
        T_CHECK(m[4].kind == MC_MATERIAL_KIND(glass) && m[4].ior == 1.33f && near3(m[4].color, .9f, 1, .95f),
                "glass");
        T_CHECK(m[5].kind == MC_MATERIAL_KIND(glass) && m[5].ior == 1.5f && near3(m[5].color, 1, 1, 1),
                "glass defaults");
    }
    T_CHECK(s.prim_count == 3, "%zu prims", s.prim_count);
    if (s.prim_count == 3) {
        p = &s.prims[0];
        T_CHECK(p->kind == PRIM_SPHERE && near3(p->p[0], 1, -2, 3) && p->p[1].x == 0.5f
                    && p->material == 2 && near3(p->emit, 1, 2, 3)
                    && p->flags == (PRIM_TWO_SIDED | PRIM_FLIP) && p->light == -1,
                "sphere");
        p = &s.prims[1];
        T_CHECK(p->kind == PRIM_QUAD && near3(p->p[0], 0, 0, 0) && near3(p->p[1], 1, 0, 0)
                    && near3(p->p[2], 0, 0, -1) && p->material == 3 && p->flags == 0
                    && v3_is_zero(p->emit),
                "quad");
        p = &s.prims[2];
        T_CHECK(p->kind == PRIM_TRIANGLE && near3(p->p[1], 0, 1, 0) && near3(p->p[2], 0, 0, 1)
                    && p->material == 4 && p->flags == PRIM_TWO_SIDED && p->normals == -1,
                "triangle");
    }
    T_CHECK(s.light_count == 3, "%zu lights", s.light_count);
    if (s.light_count == 3) {
        T_CHECK(s.lights[0].kind == LIGHT_POINT && near3(s.lights[0].position, 0, 10, 0)
                    && near3(s.lights[0].intensity, 100, 100, 100),
                "point light");
        T_CHECK(near3(s.lights[1].position, 0, 0, 0) && near3(s.lights[1].intensity, 1, 1, 1),
                "point light defaults");
        T_CHECK(s.lights[2].kind == LIGHT_ENVIRONMENT && near3(s.lights[2].intensity, .1f, .2f, .3f),
                "environment");
    }
    mc_scene_free(&s);
}

/* Comments, tabs, CRLF, no final newline, keys on one line or many, exponents, signs, hex. */
static void test_layout(void)
{
    static const char text[] =
        "\xef\xbb\xbf# a byte order mark, then comments everywhere\r\n"
        "quad#comment right after a word\r\n"
        "{\tcorner\t-1e0 +2.5E-1 .5 # comment inside\r\n"
        "\r\n"
        "  edge1 0x1p1 0 0   edge2\n0\n3\n0\n"
        "}material z{diffuse 1e-1}sphere{material z radius 1e-45}# no newline at the end";
    struct scene s;
    mc_diag d;
    mc_scene_init(&s);
    T_CHECK(parse(&s, text, NULL, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(s.prim_count == 2, "%zu prims", s.prim_count);
    if (s.prim_count == 2) {
        T_CHECK(near3(s.prims[0].p[0], -1, .25f, .5f) && near3(s.prims[0].p[1], 2, 0, 0)
                    && near3(s.prims[0].p[2], 0, 3, 0),
                "quad values");
        /* 1e-45 rounds to the smallest float subnormal: positive, so a valid radius. */
        T_CHECK(s.prims[1].p[1].x > 0.0f && s.prims[1].material == 1, "tiny radius %g",
                (double)s.prims[1].p[1].x);
    }
    mc_scene_free(&s);
}

/* Materials may be referenced before they are defined. */
static void test_material_order(void)
{
    struct scene s;
    mc_diag d;
    mc_scene_init(&s);
    T_CHECK(parse(&s, "sphere { material b }\nsphere { }\nmaterial a { mirror 1 }\n"
                      "material b { diffuse 0.2 }\ntriangle { material a }\n",
                  NULL, &d) == MCRT_OK,
            "%s", d.msg);
    T_CHECK(s.prim_count == 3 && s.prims[0].material == 2 && s.prims[1].material == 0
                && s.prims[2].material == 1,
            "material indices");
    mc_scene_free(&s);
}

/* ---- Meshes ---- */

static char tmpdir[64];

static void tmp_path(char *buf, size_t size, const char *file)
{
    snprintf(buf, size, "%s/%s", tmpdir, file);
}

/* Load one mesh block into a fresh scene; returns the status. */
static mcrt_status load_mesh(struct scene *s, const char *block, mc_diag *d)
{
    mc_scene_init(s);
    return parse(s, block, tmpdir, d);
}

static void test_mesh_transform(void)
{
    struct scene s;
    mc_diag d;
    char path[128];
    const float r5 = 1.0f / sqrtf(5.0f);
    tmp_path(path, sizeof path, "xf.obj");
    write_file(path, "v 1 0 0\nv 0 1 0\nv 0 0 0\nvn 1 1 0\nvn 1 1 0\nvn 1 1 0\nf 1//1 2//2 3//3\n");
    /* (1,0,0) -> scale (1,0,0) -> rotate 90 about z (0,1,0) -> translate (1,1,0), and so on;
     * the normal (1,1,0) maps by the inverse transpose: diag(1, 1/2, 1) gives (2,1,0)/sqrt5,
     * then the rotation gives (-1,2,0)/sqrt5. */
    T_CHECK(load_mesh(&s, "mesh { file \"xf.obj\" scale 1 2 1 rotate 0 0 1 90 translate 1 0 0 "
                          "material m emit 2 two_sided }\nmaterial m { mirror 0.5 }",
                      &d) == MCRT_OK,
            "%s", d.msg);
    T_CHECK(s.prim_count == 1, "%zu prims", s.prim_count);
    if (s.prim_count == 1) {
        const struct prim *p = &s.prims[0];
        T_CHECK(near3(p->p[0], 1, 1, 0) && near3(p->p[1], -1, 0, 0) && near3(p->p[2], 1, 0, 0),
                "vertices (%g %g %g) (%g %g %g) (%g %g %g)", (double)p->p[0].x, (double)p->p[0].y,
                (double)p->p[0].z, (double)p->p[1].x, (double)p->p[1].y, (double)p->p[1].z,
                (double)p->p[2].x, (double)p->p[2].y, (double)p->p[2].z);
        T_CHECK(p->normals == 0 && s.normal_count == 3 && near3(s.normals[0], -r5, 2 * r5, 0)
                    && near3(s.normals[2], -r5, 2 * r5, 0),
                "normal (%g %g %g)", (double)s.normals[0].x, (double)s.normals[0].y,
                (double)s.normals[0].z);
        T_CHECK(p->material == 1 && near3(p->emit, 2, 2, 2) && p->flags == PRIM_TWO_SIDED
                    && p->light == -1 && p->kind == PRIM_TRIANGLE,
                "mesh attributes");
    }
    mc_scene_free(&s);
}

/* The keys of distributed effects: values as given, zero motion is no motion, one motion shared by
 * a mesh's triangles and spinning about its bounding-box centre. */
static void test_distributed_keys(void)
{
    struct scene s;
    mc_diag d;
    char path[128];
    tmp_path(path, sizeof path, "spin.obj");
    write_file(path, "v 0 0 0\nv 2 0 0\nv 0 4 0\nv 2 4 6\nf 1 2 3\nf 2 4 3\n");
    T_CHECK(load_mesh(&s, "film { sampler sobol filter gaussian }\n"
                          "camera { lens_radius 0.25 focus_distance 7 shutter 0.5 2 move 1 0 0 }\n"
                          "integrator { light_samples 3 }\n"
                          "disk { center 1 2 3 normal 0 -2 0 radius 0.5 emit 4 }\n"
                          "sphere { move 0 0 0 }\n"
                          "quad { move 0 1 0 }\n"
                          "mesh { file \"spin.obj\" spin 0 2 0 90 move 0 0 1 }\n"
                          "mesh { file \"spin.obj\" spin 0 1 0 0 }\n",
                      &d) == MCRT_OK,
            "%s", d.msg);
    T_CHECK(s.film.sampler == SAMPLER_SOBOL && s.film.filter == FILTER_GAUSSIAN, "film keys");
    T_CHECK(s.camera.lens_radius == 0.25f && s.camera.focus_distance == 7.0f
                && s.camera.shutter[0] == 0.5f && s.camera.shutter[1] == 2.0f
                && near3(s.camera.move, 1, 0, 0),
            "camera keys");
    T_CHECK(s.integrator.light_samples == 3, "light_samples %d", s.integrator.light_samples);
    T_CHECK(s.prim_count == 7 && s.motion_count == 2, "%zu prims, %zu motions", s.prim_count,
            s.motion_count);
    if (s.prim_count == 7 && s.motion_count == 2) {
        const struct motion *spin = &s.motions[1];
        T_CHECK(s.prims[0].kind == PRIM_DISK && near3(s.prims[0].p[0], 1, 2, 3)
                    && near3(s.prims[0].p[1], 0, -1, 0) && s.prims[0].p[2].x == 0.5f,
                "disk: centre, unit normal, radius");
        T_CHECK(s.prims[1].motion == 0, "'move 0 0 0' is static");
        T_CHECK(s.prims[2].motion == 1 && near3(s.motions[0].move, 0, 1, 0)
                    && s.motions[0].omega == 0.0f,
                "moving quad");
        T_CHECK(s.prims[3].motion == 2 && s.prims[4].motion == 2, "one motion per mesh");
        T_CHECK(near3(spin->center, 1, 2, 3) && near3(spin->axis, 0, 1, 0)
                    && fabsf(spin->omega - 1.5707963f) < 1e-6f && near3(spin->move, 0, 0, 1),
                "spin about the box centre: (%g %g %g)", (double)spin->center.x,
                (double)spin->center.y, (double)spin->center.z);
        T_CHECK(s.prims[5].motion == 0 && s.prims[6].motion == 0, "'spin' by 0 degrees is static");
    }
    mc_scene_free(&s);
}

/* A mirroring transform keeps the front side where the winding and the normals put it. */
static void test_mesh_mirror(void)
{
    struct scene s;
    mc_diag d;
    char path[128];
    tmp_path(path, sizeof path, "up.obj");
    write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    T_CHECK(load_mesh(&s, "mesh { file \"up.obj\" scale -1 1 1 }", &d) == MCRT_OK, "%s", d.msg);
    if (s.prim_count == 1 && s.normal_count == 3) {
        const struct prim *p = &s.prims[0];
        vec3 ng = v3_cross(v3_sub(p->p[1], p->p[0]), v3_sub(p->p[2], p->p[0]));
        T_CHECK(ng.z > 0.0f && near3(s.normals[0], 0, 0, 1), "front side kept: ng.z %g",
                (double)ng.z);
        T_CHECK(near3(p->p[0], 0, 0, 0) && near3(p->p[1], 0, 1, 0) && near3(p->p[2], -1, 0, 0),
                "winding reversed");
    } else {
        T_CHECK(0, "%zu prims, %zu normals", s.prim_count, s.normal_count);
    }
    mc_scene_free(&s);
}

/* Negative indices, fans, vt forms, ignored statements, the shading-normal rules and the texture
 * coordinates of faces whose corners all have a vt. */
static void test_mesh_faces(void)
{
    struct scene s;
    mc_diag d;
    char path[128];
    tmp_path(path, sizeof path, "x.mtl");
    write_file(path, "newmtl red\nKd 0.5\n");
    tmp_path(path, sizeof path, "faces.obj");
    write_file(path,
               "# header\r\nmtllib x.mtl\r\no thing\r\ng group\r\ns 1\r\nusemtl red\r\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
               "f -4 -3 -2 -1\n"                      /* quad: 2 triangles */
               "v 2 0 0 0.5 0.5 0.5\nv 3 0 0\nv 3 1 0\nv 2.5 2 0\nv 2 1 0\n"
               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
               "\tf  5/1 6/2 7/3 8/4 9/5  \n"          /* pentagon: 3 triangles */
               "vn 0 0 2\nvn 0 0 0\n"
               "f 1/1/1 2/2/1 3/3/1\n"                /* smooth: normalised (0,0,1) */
               "vt 0.25\nvt 0.5 0.75 1 # w ignored\n"
               "f 1/-2 2/-1 3\n"                      /* a corner without vt: own uv */
               "f 1//1 2//1 3\n"                      /* one corner without vn: flat */
               "f 1//1 2//2 3//1\n"                   /* a zero vn: flat */
               "l 1 2\np 1\n"
               "f 1 2 3 # a comment after the corners\n");
    T_CHECK(load_mesh(&s, "mesh { file \"faces.obj\" }", &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(s.prim_count == 10, "%zu prims", s.prim_count);
    if (s.prim_count == 10 && s.uvs) {
        T_CHECK(near3(s.prims[0].p[0], 0, 0, 0) && near3(s.prims[0].p[1], 1, 0, 0)
                    && near3(s.prims[0].p[2], 1, 1, 0) && near3(s.prims[1].p[1], 1, 1, 0)
                    && near3(s.prims[1].p[2], 0, 1, 0),
                "quad fan");
        T_CHECK(near3(s.prims[4].p[0], 2, 0, 0) && near3(s.prims[4].p[1], 2.5f, 2, 0)
                    && near3(s.prims[4].p[2], 2, 1, 0),
                "pentagon fan");
        /* The pentagon's fan (0, k, k+1): textured, flat (zero normals), slots 0, 3, 6. */
        T_CHECK(s.prims[2].normals == 0 && s.prims[3].normals == 3 && s.prims[4].normals == 6
                    && v3_is_zero(s.normals[0]) && v3_is_zero(s.normals[8]),
                "textured flat faces");
        T_CHECK(s.uvs[0].x == 0 && s.uvs[0].y == 0 && s.uvs[1].x == 1 && s.uvs[1].y == 0
                    && s.uvs[7].x == 0 && s.uvs[7].y == 1 && s.uvs[8].x == 0.5f
                    && s.uvs[8].y == 0.5f,
                "pentagon texture coordinates");
        T_CHECK(s.prims[5].normals == 9 && s.normal_count == 12 && near3(s.normals[10], 0, 0, 1)
                    && s.uvs[11].x == 1 && s.uvs[11].y == 1,
                "smooth textured face");
        T_CHECK(s.prims[6].normals == -1 && s.prims[7].normals == -1, "flat faces");
        T_CHECK(s.prims[9].normals == -1, "a face with a corner lacking vt has its own uv");
    } else {
        T_CHECK(0, "%zu prims, uvs %p", s.prim_count, (void *)s.uvs);
    }
    mc_scene_free(&s);
    /* vt with u alone (v = 0), and the earlier corners' own coordinates filled in when the first
     * textured face comes after untextured smooth ones. */
    write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0.25\nvt 0.5 0.75 1\n"
                     "f 1//1 2//1 3//1\nf 1/1 2/2 3/1\n");
    T_CHECK(load_mesh(&s, "mesh { file \"faces.obj\" }", &d) == MCRT_OK, "%s", d.msg);
    if (s.prim_count == 2 && s.normal_count == 6 && s.uvs) {
        T_CHECK(s.uvs[0].x == 0 && s.uvs[0].y == 0 && s.uvs[1].x == 1 && s.uvs[1].y == 0
                    && s.uvs[2].x == 0 && s.uvs[2].y == 1,
                "own uv backfilled");
        T_CHECK(s.uvs[3].x == 0.25f && s.uvs[3].y == 0 && s.uvs[4].x == 0.5f
                    && s.uvs[4].y == 0.75f && s.uvs[5].x == 0.25f,
                "vt u alone, vt u v w");
        T_CHECK(v3_is_zero(s.normals[3]) && near3(s.normals[0], 0, 0, 1), "normals");
    } else {
        T_CHECK(0, "%zu prims, %zu normals, uvs %p", s.prim_count, s.normal_count, (void *)s.uvs);
    }
    mc_scene_free(&s);
}

/* mc_obj_load directly: degenerate faces are dropped and counted; absolute paths. */
static void test_obj_stats(void)
{
    struct scene s;
    mc_diag d;
    char path[128];
    struct obj_mesh m;
    struct obj_stats st;
    static const float identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    tmp_path(path, sizeof path, "degen.obj");
    write_file(path, "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 4\nf 1 2 4\n");
    mc_scene_init(&s);
    memset(&m, 0, sizeof m);
    m.path = path;
    m.origin = "here:1:1";
    memcpy(m.xform, identity, sizeof identity);
    m.proto.material = 0;
    T_CHECK(mc_obj_load(&s, &m, &st, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(st.triangles == 1 && st.degenerate == 2 && s.prim_count == 1, "%zu kept, %zu dropped",
            st.triangles, st.degenerate);

    /* A file over 1 GiB is refused before it is read (a sparse file: no disk space used). */
    {
        char big[128], expect[300];
        tmp_path(big, sizeof big, "huge.obj");
        write_file(big, "");
        if (truncate(big, ((off_t)1 << 30) + 1) == 0) {
            m.path = big;
            snprintf(expect, sizeof expect,
                     "here:1:1: cannot read '%s': larger than the limit of 1024 MiB", big);
            T_CHECK(mc_obj_load(&s, &m, &st, &d) == MCRT_ERR_IO && !strcmp(d.msg, expect), "%s",
                    d.msg);
        } else {
            T_SKIP("the 1 GiB limit: cannot make a sparse file in %s", tmpdir);
        }
    }

    /* An absolute path ignores base_dir. */
    {
        char text[256];
        snprintf(text, sizeof text, "mesh { file \"%s\" }", path);
        mc_scene_free(&s);
        mc_scene_init(&s);
        T_CHECK(parse(&s, text, "/nonexistent", &d) == MCRT_OK && s.prim_count == 1, "%s", d.msg);
        mc_scene_free(&s);
    }
}

/* A large grid: throughput of the reader (the note gives the time; the check is the count). */
static void test_obj_large(void)
{
    enum { N = 256 }; /* N x N quads = 131072 triangles */
    struct scene s;
    mc_diag d;
    char path[128];
    FILE *f;
    int i, j;
    clock_t t0;
    double secs;
    tmp_path(path, sizeof path, "grid.obj");
    f = fopen(path, "wb");
    if (!f) {
        T_CHECK(0, "cannot write %s", path);
        return;
    }
    for (j = 0; j <= N; j++)
        for (i = 0; i <= N; i++)
            fprintf(f, "v %.6f %.6f 0\n", i / (double)N, j / (double)N);
    for (j = 0; j < N; j++)
        for (i = 0; i < N; i++) {
            int a = j * (N + 1) + i + 1;
            fprintf(f, "f %d %d %d %d\n", a, a + 1, a + N + 2, a + N + 1);
        }
    fclose(f);
    t0 = clock();
    T_CHECK(load_mesh(&s, "mesh { file \"grid.obj\" }", &d) == MCRT_OK, "%s", d.msg);
    secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    T_CHECK(s.prim_count == 2u * N * N, "%zu triangles", s.prim_count);
    T_NOTE("OBJ grid of %d triangles loaded in %.3f s (%.2f M triangles/s)", 2 * N * N, secs,
           2.0 * N * N / secs / 1e6);
    mc_scene_free(&s);
}

/* ---- Malformed input ---- */

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Each tests/parse_errors/NAME.mcrt starts with "# expect: MESSAGE", the exact message of its
 * error (the file name as given, relative to the repository root). I/O failures must have the I/O
 * status, everything else the parse status. */
static void test_error_files(void)
{
    DIR *dir = opendir(ERR_DIR);
    struct dirent *e;
    char *names[512];
    int n = 0, i;
    if (!dir) {
        T_CHECK(0, "cannot open %s (run from the repository root)", ERR_DIR);
        return;
    }
    while ((e = readdir(dir)) && n < 512) {
        size_t l = strlen(e->d_name);
        if (l > 5 && !strcmp(e->d_name + l - 5, ".mcrt"))
            names[n++] = strdup(e->d_name);
    }
    closedir(dir);
    qsort(names, (size_t)n, sizeof *names, cmp_names);
    T_CHECK(n >= 60, "only %d error fixtures", n);
    for (i = 0; i < n; i++) {
        char path[300], expect[512];
        size_t len, el;
        char *text, *nl;
        struct scene s;
        mc_diag d;
        mcrt_status st;
        int io;
        snprintf(path, sizeof path, "%s/%s", ERR_DIR, names[i]);
        text = t_read_file(path, &len);
        if (!text || strncmp(text, "# expect: ", 10) != 0 || !(nl = strchr(text, '\n'))) {
            T_CHECK(0, "%s: no '# expect: ' line", path);
            free(text);
            continue;
        }
        el = (size_t)(nl - text) - 10;
        memcpy(expect, text + 10, el < sizeof expect ? el : sizeof expect - 1);
        expect[el < sizeof expect ? el : sizeof expect - 1] = '\0';
        mc_scene_init(&s);
        st = parse_n(&s, text, len, path, ERR_DIR, &d);
        if (st == MCRT_OK) {
            /* Found only when the scene's images are read or it is prepared: loaded as the
             * library's users load it. */
            mcrt_scene *ms = mcrt_scene_new();
            st = ms ? mcrt_scene_load_file(ms, path) : MCRT_ERR_NOMEM;
            snprintf(d.msg, sizeof d.msg, "%s", ms ? mcrt_scene_error(ms) : "out of memory");
            mcrt_scene_free(ms);
        }
        io = strstr(expect, ": cannot open '") || strstr(expect, ": cannot read '");
        T_CHECK(st == (io ? MCRT_ERR_IO : MCRT_ERR_PARSE) && !strcmp(d.msg, expect),
                "%s: status %d\n  got:    %s\n  expect: %s", names[i], (int)st, d.msg, expect);
        mc_scene_free(&s);
        free(text);
        free(names[i]);
    }
}

/* Inputs that a text file cannot hold well: no bytes, NUL bytes, an end inside a token. */
static void test_error_strings(void)
{
    static const struct {
        const char *text;
        size_t len;
        const char *expect;
    } cases[] = {
        {"", 0, "t.mcrt:1:1: empty scene: a scene needs at least one block, such as 'sphere { }'"},
        {"\n\n  ", 4, "t.mcrt:3:3: empty scene: a scene needs at least one block, such as 'sphere { }'"},
        {"sphere { }\0", 11, "t.mcrt:1:11: unexpected byte 0x00"},
        {"sphere { } # \0 in a comment", 27, "t.mcrt:1:14: unexpected byte 0x00 in a comment"},
        {"mesh { file \"a\0b\" }", 19, "t.mcrt:1:15: unexpected byte 0x00 in a string"},
        {"sphere { radius 1", 17,
         "t.mcrt:1:18: unexpected end of file: block 'sphere' opened at 1:1 is not closed"},
        {"sphere { center 1 2", 19,
         "t.mcrt:1:20: unexpected end of file: block 'sphere' opened at 1:1 is not closed"},
        {"sphere { material", 17,
         "t.mcrt:1:18: unexpected end of file: block 'sphere' opened at 1:1 is not closed"},
        {"sphere", 6, "t.mcrt:1:7: expected '{' after 'sphere', found end of file"},
        {"material", 8, "t.mcrt:1:9: expected a name after 'material', found end of file"},
        {"sphere { radius 1e", 18, "t.mcrt:1:17: malformed number '1e'"},
        {"mesh { file \"abc", 16,
         "t.mcrt:1:13: string not closed (a string ends with '\"' on the same line)"},
        {"sphere { radius 2 } }", 21,
         "t.mcrt:1:21: expected a block such as 'sphere { }', found '}'"},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct scene s;
        mc_diag d;
        mcrt_status st;
        mc_scene_init(&s);
        st = parse_n(&s, cases[i].text, cases[i].len, "t.mcrt", NULL, &d);
        T_CHECK(st == MCRT_ERR_PARSE && !strcmp(d.msg, cases[i].expect),
                "case %zu: status %d\n  got:    %s\n  expect: %s", i, (int)st, d.msg,
                cases[i].expect);
        mc_scene_free(&s);
    }
}

/* ---- Robustness ---- */

/* Whether msg is "PREFIX:LINE:COL: something" for one of the two prefixes. */
static int well_formed(const char *msg, const char *name, const char *dir)
{
    int line = 0, col = 0, n = 0;
    size_t l = strlen(name), dl = strlen(dir);
    if (!strncmp(msg, name, l) && msg[l] == ':')
        msg += l;
    else if (!strncmp(msg, dir, dl) && msg[dl] == '/' && (msg = strstr(msg, ".obj:")))
        msg += 4;
    else
        return 0;
    return sscanf(msg, ":%d:%d: %n", &line, &col, &n) == 2 && n > 0 && line >= 1 && col >= 1
        && msg[n] != '\0';
}

/* Random truncations, byte changes, token insertions, deletions and duplications of a valid
 * scene (PCG32, fixed seed): the parser must return OK or a well-formed message, never crash or
 * leak (ASan and LeakSanitizer watch the rest). */
static void test_mutations(void)
{
    static const char *const tokens[] = {"{", "}", "\"", "#", "sphere", "material", "mesh",
                                         "film", "1e999", "nan", "-inf", "0", "-1", "1.0.0",
                                         "\n", "\t", "two_sided", "file \"tri.obj\"", "\"..\"",
                                         "\xff", "1e-999", "0x1p200", "emit 1 2 3", "scale 0"};
    char base[2048], *buf;
    size_t base_len, cap = 4096;
    int iter, ok = 0, failed = 0, bad = 0;
    pcg32 rng;
    char path[128];
    tmp_path(path, sizeof path, "tri.obj");
    write_file(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    snprintf(base, sizeof base, "%smesh { file \"tri.obj\" scale 2 rotate 1 0 0 30 material red "
             "flip }\n", full_scene);
    base_len = strlen(base);
    buf = malloc(cap);
    pcg32_seed(&rng, 20240601u, 7u);
    for (iter = 0; iter < 4000; iter++) {
        size_t len = base_len;
        int k, edits = 1 + (int)(pcg32_next(&rng) % 4);
        struct scene s;
        mc_diag d;
        mcrt_status st;
        memcpy(buf, base, base_len);
        for (k = 0; k < edits; k++) {
            size_t at = len ? pcg32_next(&rng) % (len + 1) : 0;
            switch (pcg32_next(&rng) % 5) {
            case 0: /* truncate */
                len = at;
                break;
            case 1: /* change a byte to any value */
                if (at < len)
                    buf[at] = (char)(pcg32_next(&rng) & 0xff);
                break;
            case 2: { /* insert a token */
                const char *t = tokens[pcg32_next(&rng) % (sizeof tokens / sizeof tokens[0])];
                size_t tl = strlen(t);
                if (len + tl < cap) {
                    memmove(buf + at + tl, buf + at, len - at);
                    memcpy(buf + at, t, tl);
                    len += tl;
                }
                break;
            }
            case 3: { /* delete up to 16 bytes */
                size_t n = pcg32_next(&rng) % 17;
                if (n > len - at)
                    n = len - at;
                memmove(buf + at, buf + at + n, len - at - n);
                len -= n;
                break;
            }
            default: { /* copy up to 64 bytes from elsewhere to here */
                size_t from = pcg32_next(&rng) % (len + 1), n = pcg32_next(&rng) % 65;
                char tmp[64];
                if (n > len - from)
                    n = len - from;
                if (len + n < cap) {
                    memcpy(tmp, buf + from, n);
                    memmove(buf + at + n, buf + at, len - at);
                    memcpy(buf + at, tmp, n);
                    len += n;
                }
                break;
            }
            }
        }
        mc_scene_init(&s);
        st = parse_n(&s, buf, len, "t.mcrt", tmpdir, &d);
        if (st == MCRT_OK) {
            ok++;
        } else if ((st == MCRT_ERR_PARSE || st == MCRT_ERR_IO) && well_formed(d.msg, "t.mcrt", tmpdir)) {
            failed++;
        } else if (bad++ < 5) {
            T_CHECK(0, "mutation %d: status %d, message '%s'", iter, (int)st, d.msg);
        }
        mc_scene_free(&s);
    }
    free(buf);
    T_CHECK(bad == 0, "%d malformed outcomes", bad);
    T_CHECK(ok > 0 && failed > 0, "both outcomes occur: %d ok, %d errors", ok, failed);
    T_NOTE("4000 mutated scenes: %d parsed, %d rejected with a well-formed message", ok, failed);
}

static void remove_tmpdir(void)
{
    DIR *dir = opendir(tmpdir);
    struct dirent *e;
    char path[512];
    if (!dir)
        return;
    while ((e = readdir(dir)))
        if (e->d_name[0] != '.') {
            snprintf(path, sizeof path, "%s/%s", tmpdir, e->d_name);
            unlink(path);
        }
    closedir(dir);
    rmdir(tmpdir);
}

int main(void)
{
    strcpy(tmpdir, "/tmp/mcrt_parse_XXXXXX");
    if (!mkdtemp(tmpdir)) {
        printf("FAIL cannot create a temporary directory\n");
        return 1;
    }
    test_minimal();
    test_full();
    test_layout();
    test_material_order();
    test_mesh_transform();
    test_distributed_keys();
    test_mesh_mirror();
    test_mesh_faces();
    test_obj_stats();
    test_obj_large();
    test_error_files();
    test_error_strings();
    test_mutations();
    remove_tmpdir();
    return t_done();
}
