/* test_mtl.c: OBJ materials. The MTL mapping (man/mcrt.5 "OBJ materials") on one material of
 * each kind, the Ns -> alpha formula, the scene's material and emit overriding the file's, the
 * warnings (once each), and two renders with a closed form: a closed cube of black walls emitting
 * Ke, seen from inside, is Ke in every pixel exactly; walls of albedo rho emitting Ke give
 * Ke / (1 - rho) everywhere (the enclosure's radiance L = Ke + rho L), within the noise; a
 * map_Kd image multiplies Kd, exactly, on a face under the white sky; Pr, Pm and map_Pr. And the numbers OBJ and MTL
 * files share (wavefront.c) are strtod's bit for bit, its fast path included. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/image.h"
#include "render_util.h"
#include "scene/mtl.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "scene/wavefront.h"
#include "t.h"

static char tmpdir[64];

static void write_in_tmp(const char *file, const char *text)
{
    char path[160];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", tmpdir, file);
    if (!(f = fopen(path, "wb"))) {
        printf("FAIL cannot write %s\n", path);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

static const struct mtl_entry *entry(const struct mtl_library *lib, const char *name)
{
    int i = mc_mtl_find(lib, name, strlen(name));
    T_CHECK(i >= 0, "no material '%s'", name);
    return i >= 0 ? &lib->e[i] : NULL;
}

static int near3(vec3 a, float x, float y, float z)
{
    return fabsf(a.x - x) < 1e-6f && fabsf(a.y - y) < 1e-6f && fabsf(a.z - z) < 1e-6f;
}

static void test_mapping(void)
{
    struct mtl_library lib;
    struct scene s;
    mc_diag d;
    char path[160];
    const struct mtl_entry *e;
    write_in_tmp("kinds.mtl",
                 "# one of each kind\n"
                 "newmtl matte\nKa 0.2 0.2 0.2\nKd 0.5 0.25 0.125\nKs 0.5\nillum 1\n"
                 "newmtl shiny\nKd 0.5\nKs 0.04\nNs 98\nNi 1.0\nillum 2\n"
                 "newmtl coat\nKd 0.3\nKs 0.5\nNi 1.6\n"
                 "newmtl copper  # name ends before the comment\n"
                 "Kd 0 0 0\nKs 0.9 0.6 0.3\nillum 3\n"
                 "newmtl water\nKd 0.5\nNi 1.33\nTf 0.9 1 1\nillum 7\n"
                 "newmtl veil\nd 0.5\n"
                 "newmtl lamp\nKe 2 3 4\n"
                 "\tnewmtl two words \n Kd 1\n"
                 "newmtl pbr\nKd 0.6 0.5 0.4\nPr 0.5\nPm 0\n"
                 "newmtl pbrmetal\nKd 0.9 0.6 0.3\nPr 0.3\nPm 1\nmap_Pr rough.png\n");
    snprintf(path, sizeof path, "%s/kinds.mtl", tmpdir);
    memset(&lib, 0, sizeof lib);
    mc_scene_init(&s);
    T_CHECK(mc_mtl_load(&lib, path, "t.obj:1:8", &s, &d) == MCRT_OK, "%s", d.msg);
    T_CHECK(lib.n == 10, "%zu materials", lib.n);
    T_CHECK(s.warnings == NULL, "Ka is ignored quietly: %s", s.warnings);
    if (lib.n == 10) {
        e = entry(&lib, "matte");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(diffuse) && near3(e->m.color, 0.5f, 0.25f, 0.125f),
                "illum 1 is diffuse Kd, whatever Ks");
        e = entry(&lib, "shiny");
        /* Ns 98: alpha = sqrt(2 / (98 + 2)) = sqrt(0.02); Ni 1 means the default coat. */
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(plastic) && near3(e->m.color, 0.5f, 0.5f, 0.5f)
                    && fabsf(e->m.alpha - sqrtf(0.02f)) < 1e-6f && e->m.ior == 1.5f,
                "Kd and Ks: plastic, alpha %g ior %g", e ? (double)e->m.alpha : 0.0,
                e ? (double)e->m.ior : 0.0);
        e = entry(&lib, "coat");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(plastic) && e->m.ior == 1.6f && e->m.alpha == 0.0f,
                "Ni above 1 is the coat's index; no Ns is smooth");
        e = entry(&lib, "copper");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(metal) && near3(e->m.color, 0.9f, 0.6f, 0.3f)
                    && e->m.eta.x > 0.0f && e->m.k.x > 0.0f,
                "black Kd and Ks: metal of reflectance Ks, with eta and k derived");
        e = entry(&lib, "water");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(glass) && fabsf(e->m.ior - 1.33f) < 1e-6f
                    && near3(e->m.color, 0.9f, 1.0f, 1.0f),
                "illum 7: glass of index Ni, tint Tf");
        e = entry(&lib, "veil");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(glass) && e->m.ior == 1.5f
                    && near3(e->m.color, 1, 1, 1),
                "d below 1: glass");
        e = entry(&lib, "lamp");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(diffuse) && near3(e->m.color, 0, 0, 0)
                    && near3(e->emit, 2, 3, 4),
                "Ke alone: a black emitter");
        e = entry(&lib, "pbr");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(plastic) && e->m.alpha == 0.25f
                    && near3(e->m.color, 0.6f, 0.5f, 0.4f) && !e->maps[MTL_MAP_PR].path,
                "Pr without Ks: plastic of alpha Pr^2");
        e = entry(&lib, "pbrmetal");
        T_CHECK(e && e->m.kind == MC_MATERIAL_KIND(metal) && fabsf(e->m.alpha - 0.09f) < 1e-7f
                    && near3(e->m.color, 0.9f, 0.6f, 0.3f) && e->maps[MTL_MAP_PR].path
                    && strstr(e->maps[MTL_MAP_PR].path, "/rough.png")
                    && strstr(e->maps[MTL_MAP_PR].origin, "kinds.mtl:40:8"),
                "Pm 1: metal of reflectance Kd, alpha Pr^2, map_Pr beside the file (%s)",
                e && e->maps[MTL_MAP_PR].origin ? e->maps[MTL_MAP_PR].origin : "none");
        e = entry(&lib, "two words");
        T_CHECK(e && near3(e->m.color, 1, 1, 1) && !strcmp(e->m.name, "kinds.mtl:two words"),
                "a name with a blank; the scene's name '%s'", e ? e->m.name : "");
    }
    mc_mtl_free(&lib);
    mc_scene_free(&s);
}

/* An OBJ with a material per half and the first library's statements that mcrt ignores. */
static void write_two_halves(void)
{
    write_in_tmp("halves.mtl", "newmtl red\nKd 0.8 0.1 0.1\nbump b.png\nbump c.png\nmap_Ks s.png\n"
                               "newmtl glow\nKd 0\nKe 5\n");
    write_in_tmp("halves.obj", "mtllib halves.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                               "usemtl red\nf 1 2 3\nusemtl glow\nf 1 2 3\nusemtl red\nf 1 2 3\n");
}

static mcrt_scene *load(const char *text)
{
    mcrt_scene *s = mcrt_scene_new();
    char *full = malloc(strlen(text) + 4 * sizeof tmpdir);
    const char *p;
    char *o = full;
    /* "@" stands for the folder of the test's files. */
    for (p = text; *p; p++)
        o = *p == '@' ? o + sprintf(o, "%s", tmpdir) : (*o = *p, o + 1);
    *o = '\0';
    if (s && mcrt_scene_load_string(s, full, strlen(full), "t.mcrt") != MCRT_OK) {
        printf("FAIL load: %s\n", mcrt_scene_error(s));
        t_failed++;
        mcrt_scene_free(s);
        s = NULL;
    }
    free(full);
    return s;
}

static void test_faces_and_overrides(void)
{
    static const char warned[] =
        "/halves.mtl:3:1: warning: 'bump' is ignored: mcrt has no bump, normal or displacement maps "
        "(later ones in this file are not reported)\n";
    mcrt_scene *s;
    const char *w;
    write_two_halves();
    /* Two meshes of one file: each reads the library, and its warnings are said once. */
    s = load("mesh { file \"@/halves.obj\" }\nmesh { file \"@/halves.obj\" }");
    if (s) {
        const char *second;
        w = mcrt_scene_warnings(s);
        second = strchr(w, '\n');
        T_CHECK(strstr(w, warned) == w + strlen(tmpdir) && second && strstr(second + 1, "'map_Ks'")
                    && strchr(second + 1, '\n') && !strchr(strchr(second + 1, '\n') + 1, '\n'),
                "two warnings, once each:\n%s", w);
        mcrt_scene_free(s);
    }
    /* The faces: before any usemtl the mesh's own (default) material; then each usemtl's, with
     * its Ke. Through the internal parser, to see the primitives. */
    {
        struct scene sc;
        mc_diag d;
        char text[256];
        int n = snprintf(text, sizeof text, "mesh { file \"%s/halves.obj\" }\n"
                                            "mesh { file \"%s/halves.obj\" emit 1 }\n"
                                            "mesh { file \"%s/none.obj\" material m }\n"
                                            "material m { mirror 0.5 }\n", tmpdir, tmpdir, tmpdir);
        write_in_tmp("none.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
        mc_scene_init(&sc);
        T_CHECK(mc_scene_parse(&sc, text, (size_t)n, "t.mcrt", NULL, &d) == MCRT_OK, "%s", d.msg);
        if (sc.prim_count == 9) {
            const struct prim *p = sc.prims;
            const struct material *m = sc.materials;
            T_CHECK(p[0].material == 0 && v3_is_zero(p[0].emit), "before usemtl: the mesh's own");
            T_CHECK(!strcmp(m[p[1].material].name, "halves.mtl:red") && v3_is_zero(p[1].emit)
                        && !strcmp(m[p[2].material].name, "halves.mtl:glow") && near3(p[2].emit, 5, 5, 5)
                        && p[3].material == p[1].material,
                    "usemtl: material and Ke, one scene material per MTL material");
            T_CHECK(p[6].material == p[2].material + 2 && near3(p[6].emit, 1, 1, 1)
                        && near3(p[5].emit, 1, 1, 1),
                    "the scene's emit replaces Ke (the materials stay)");
            T_CHECK(!strcmp(m[p[8].material].name, "m"),
                    "the scene's material: the MTL files are not read");
        } else {
            T_CHECK(0, "%zu primitives", sc.prim_count);
        }
        mc_scene_free(&sc);
    }
}

/* The inside of the cube [-1, 1]^3, every face's front side inward, all of material box. */
static void write_box(const char *mtl)
{
    write_in_tmp("box.mtl", mtl);
    write_in_tmp("box.obj", "mtllib box.mtl\n"
                            "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                            "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                            "usemtl box\n"
                            "f 1 2 3 4\nf 5 8 7 6\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\n");
}

static float *render_box(int spp, int *w, int *h)
{
    char text[512];
    struct t_render_opts o = {0, 2, 0, 7, NULL, NULL};
    o.spp = spp;
    snprintf(text, sizeof text,
             "film { width 32 height 32 }\ncamera { eye 0.2 -0.3 0.1 look 1 0.5 -1 fov 100 }\n"
             "mesh { file \"%s/box.obj\" }\n", tmpdir);
    return t_render(text, &o, w, h, NULL);
}

static void test_emitting_box(void)
{
    int w = 0, h = 0;
    size_t i, n;
    float *px;
    double sum = 0.0, sum2 = 0.0, mean, sd;
    /* Black walls: the camera ray's first hit is all there is, exactly Ke. */
    write_box("newmtl box\nKd 0\nKe 1.5 0.75 0.25\n");
    px = render_box(4, &w, &h);
    if (px) {
        double worst = 0.0;
        static const float ke[3] = {1.5f, 0.75f, 0.25f};
        for (i = 0; i < (size_t)w * (size_t)h * 3; i++)
            worst = fmax(worst, fabs(px[i] - ke[i % 3]) / ke[i % 3]);
        T_CHECK(worst < 1e-6, "black emitting box: every pixel Ke, worst relative error %g", worst);
        free(px);
    } else {
        T_CHECK(0, "the black box did not render");
    }
    /* Walls of albedo 0.5 emitting 1: L = 1 / (1 - 0.5) = 2 everywhere. Each pixel's estimate (the
     * mean of its channels, which share their paths) is
     * independent of the others', so their mean's standard error is their spread over sqrt(n);
     * the mean must be within 4 of those (a false failure 6e-5 of the time). */
    write_box("newmtl box\nKd 0.5\nKe 1\n");
    px = render_box(16, &w, &h);
    if (px) {
        n = (size_t)w * (size_t)h;
        for (i = 0; i < n; i++) {
            double v = ((double)px[3 * i] + px[3 * i + 1] + px[3 * i + 2]) / 3.0;
            sum += v;
            sum2 += v * v;
        }
        mean = sum / (double)n;
        sd = sqrt(fmax(sum2 / (double)n - mean * mean, 0.0) / (double)(n - 1));
        T_CHECK(sd > 0.0 && fabs(mean - 2.0) < 4.0 * sd, "grey emitting box: mean %.5f, standard error %.5f",
                mean, sd);
        T_NOTE("grey emitting box: mean %.5f against 2, standard error %.5f", mean, sd);
        free(px);
    } else {
        T_CHECK(0, "the grey box did not render");
    }
}

/* map_Kd: an image texture times Kd. Two quads side by side filling the view under the default
 * white sky (radiance 1), traced by BSDF sampling alone: a diffuse surface of albedo rho then
 * returns rho in every sample exactly (its weight f cos / pdf is rho, and the bounce meets the
 * sky), so the left half is Kd x the 1x1 image's colour and the right half its own Kd. */
static void test_map_kd(void)
{
    static const float texel[3] = {0.3f, 0.5f, 0.7f};
    char path[160], text[512];
    mc_diag d;
    mcrt_scene *sc;
    int w = 0, h = 0, x, y, c, bad = 0;
    float *px;
    struct t_render_opts o = {4, 2, 0, 3, NULL, NULL};
    snprintf(path, sizeof path, "%s/texel.pfm", tmpdir);
    T_CHECK(mc_image_write(path, texel, 1, 1, &d) == MCRT_OK, "%s", d.msg);
    write_in_tmp("tex.mtl", "newmtl a\nKd 0.5\nmap_Kd -s 2 2 1 -clamp on -bm 1 texel.pfm\n"
                            "newmtl b\nKd 0.2 0.4 0.6\n"
                            "newmtl unused\nKd 1\nmap_Kd -o 0.5 other.pfm\n"
                            "newmtl gone\nmap_Kd missing.pfm\n");
    write_in_tmp("tex.obj", "mtllib tex.mtl\nv -2 -2 0\nv 0 -2 0\nv 0 2 0\nv -2 2 0\nv 2 -2 0\nv 2 2 0\n"
                            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                            "usemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 2 5 6 3\n");
    /* unused's map_Kd names a file that is absent, but no face uses it: its image is not read. */
    snprintf(text, sizeof text, "film { width 8 height 8 }\nintegrator { strategy bsdf }\n"
                                "mesh { file \"%s/tex.obj\" }\n", tmpdir);
    px = t_render(text, &o, &w, &h, NULL);
    if (px && w == 8 && h == 8) {
        for (y = 0; y < 8; y++)
            for (x = 0; x < 8; x++)
                for (c = 0; c < 3; c++) {
                    double want = x < 4 ? 0.5 * texel[c] : 0.2 * (c + 1);
                    bad += fabs(px[3 * (8 * y + x) + c] - want) > 1e-5 * want;
                }
        T_CHECK(bad == 0, "%d channels off: left %g %g %g, right %g %g %g", bad, px[0], px[1],
                px[2], px[21], px[22], px[23]);
    } else {
        T_CHECK(0, "the textured mesh did not render");
    }
    free(px);
    sc = load("mesh { file \"@/tex.obj\" }");
    if (sc) {
        const char *wn = mcrt_scene_warnings(sc);
        T_CHECK(strstr(wn, "/tex.mtl:3:8: warning: texture map options such as '-s' are ignored")
                    && !strstr(strchr(wn, '\n') + 1, "map options"),
                "map options warned once: %s", wn);
        mcrt_scene_free(sc);
    }
    /* A face of material gone: its missing image is an error at the file name in the MTL file. */
    write_in_tmp("tex.obj", "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gone\nf 1 2 3\n");
    if ((sc = mcrt_scene_new())) {
        char want[200];
        snprintf(text, sizeof text, "mesh { file \"%s/tex.obj\" }\n", tmpdir);
        snprintf(want, sizeof want, "%s/tex.mtl:10:8: cannot read '%s/missing.pfm'", tmpdir, tmpdir);
        T_CHECK(mcrt_scene_load_string(sc, text, strlen(text), "t.mcrt") == MCRT_ERR_IO
                    && !strncmp(mcrt_scene_error(sc), want, strlen(want)),
                "missing map_Kd image: %s", mcrt_scene_error(sc));
        mcrt_scene_free(sc);
    }
    remove(path);
}

/* Random decimal tokens of every shape the fast path takes or refuses (signs, leading zeros, 1 to
 * 24 digits, a point anywhere, exponents to +-40, hex and words), each read by mc_wf_number and
 * by strtod: the same double, bit for bit, wherever strtod reads the whole token as a number in
 * a float's range (the others are errors, as before). */
static void test_numbers(void)
{
    struct wf_reader r = {"t.obj", "an OBJ file", 1, NULL, NULL};
    pcg32 g;
    mc_diag d;
    int i, differ = 0, errors = 0, checked = 0;
    pcg32_seed(&g, 17, 0);
    r.d = &d;
    for (i = 0; i < 300000; i++) {
        char tok[64];
        int n = 0, k, digits = 1 + (int)(pcg32_next(&g) % 24), point = (int)(pcg32_next(&g) % 28);
        unsigned form = pcg32_next(&g);
        double want, got = 0.0;
        char *end;
        if (form % 5 == 0)
            tok[n++] = form % 2 ? '-' : '+';
        for (k = 0; k < digits; k++) {
            if (k == point)
                tok[n++] = '.';
            tok[n++] = (char)('0' + (k < (int)(form >> 8) % 4 ? 0 : pcg32_next(&g) % 10));
        }
        if (form % 7 == 0)
            n += sprintf(tok + n, "e%d", (int)(pcg32_next(&g) % 81) - 40);
        if (form % 97 == 0)
            n = sprintf(tok, "%s", form % 3 ? "0x1p3" : "inf");
        tok[n] = '\0';
        r.line_start = tok;
        want = strtod(tok, &end);
        if (end != tok + n || !isfinite(want) || fabs(want) > 3.4028234663852886e38) {
            errors += mc_wf_number(&r, tok, tok + n, &got) != MCRT_OK;
            continue;
        }
        checked++;
        if (mc_wf_number(&r, tok, tok + n, &got) != MCRT_OK || memcmp(&got, &want, sizeof got)) {
            if (differ++ < 5)
                printf("  '%s': %.17g, strtod %.17g\n", tok, got, want);
        }
    }
    T_CHECK(differ == 0, "%d of %d numbers differ from strtod's", differ, checked);
    T_CHECK(checked > 250000 && errors > 1000, "%d numbers checked, %d refused", checked, errors);
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/mcrt_mtl_XXXXXX");
    if (!mkdtemp(tmpdir)) {
        printf("FAIL mkdtemp\n");
        return 1;
    }
    test_numbers();
    test_mapping();
    test_faces_and_overrides();
    test_emitting_box();
    test_map_kd();
    {
        static const char *const files[] = {"kinds.mtl", "halves.mtl", "halves.obj", "none.obj",
                                            "box.mtl", "box.obj", "tex.mtl", "tex.obj"};
        char path[160];
        size_t i;
        for (i = 0; i < sizeof files / sizeof files[0]; i++) {
            snprintf(path, sizeof path, "%s/%s", tmpdir, files[i]);
            remove(path);
        }
        rmdir(tmpdir);
    }
    return t_done();
}
