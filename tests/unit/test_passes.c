/* test_passes.c: crops and progressive passes through the public API (mcrt.h): a crop has exactly
 * the pixel values of the whole image with the same seed; a render stopped by a target error is
 * the same image every time; one progressive pass is the plain render; passes add up to the
 * samples they report; bad crops are refused. */
#include <math.h>
#include <string.h>

#include "mcrt.h"
#include "t.h"

static const char scene_text[] =
    "film { width 40 height 30 spp 4 sampler stratified }\n"
    "camera { eye 0 3 6  look 0 0.5 0  fov 40 }\n"
    "material m { diffuse 0.7 }\n"
    "quad { corner -4 0 4  edge1 8 0 0  edge2 0 0 -8  material m }\n"
    "sphere { center 0 0.7 0  radius 0.7  material m }\n"
    "quad { corner -0.5 3 -0.5  edge1 1 0 0  edge2 0 0 1  emit 20 }\n";

/* Render with o; returns the render (caller frees) or NULL after recording a failure. */
static mcrt_render *run(const mcrt_scene *s, const mcrt_options *o, mcrt_status want)
{
    mcrt_render *r = mcrt_render_new(s, o);
    mcrt_status st = r ? mcrt_render_run(r) : MCRT_ERR_NOMEM;
    T_CHECK(st == want, "run: status %d, want %d: %s", (int)st, (int)want, mcrt_render_error(r));
    return r;
}

int main(void)
{
    mcrt_scene *s = mcrt_scene_new();
    mcrt_options o;
    mcrt_render *full, *crop, *a, *b;
    mcrt_stats st;
    const float *pf, *pc, *pa, *pb;
    int w, h, cw, ch, x, y, same = 1;

    T_CHECK(mcrt_scene_load_string(s, scene_text, strlen(scene_text), NULL) == MCRT_OK, "load: %s",
            mcrt_scene_error(s));
    mcrt_options_init(&o);
    o.seed = 7;
    o.threads = 2;
    full = run(s, &o, MCRT_OK);
    o.crop_x0 = 5, o.crop_y0 = 17, o.crop_x1 = 38, o.crop_y1 = 29; /* across tile borders */
    crop = run(s, &o, MCRT_OK);
    pf = mcrt_render_pixels(full, &w, &h);
    pc = mcrt_render_pixels(crop, &cw, &ch);
    T_CHECK(w == 40 && h == 30 && cw == 33 && ch == 12, "sizes %dx%d, crop %dx%d", w, h, cw, ch);
    for (y = 0; y < ch && pc && pf; y++)
        for (x = 0; x < cw; x++)
            same &= memcmp(pc + 3 * (y * cw + x), pf + 3 * ((y + 17) * w + x + 5),
                           3 * sizeof *pc) == 0;
    T_CHECK(same, "the crop has the whole image's pixel values, bit for bit");
    mcrt_render_free(crop);

    /* One progressive pass (a target the first pass meets) is the plain render. */
    o.crop_x0 = o.crop_y0 = o.crop_x1 = o.crop_y1 = 0;
    o.target_error = 1e9;
    a = run(s, &o, MCRT_OK);
    mcrt_render_stats(a, &st, sizeof st);
    pa = mcrt_render_pixels(a, NULL, NULL);
    T_CHECK(st.passes == 1 && st.spp == 4 && pa && memcmp(pa, pf, 40 * 30 * 3 * sizeof *pa) == 0,
            "one pass is the plain render (passes %d, spp %d)", st.passes, st.spp);
    mcrt_render_free(a);

    /* A reachable target: several passes, the same image twice (and with 1 thread). */
    o.target_error = 0.01;
    a = run(s, &o, MCRT_OK);
    o.threads = 1;
    b = run(s, &o, MCRT_OK);
    mcrt_render_stats(a, &st, sizeof st);
    pa = mcrt_render_pixels(a, NULL, NULL);
    pb = mcrt_render_pixels(b, NULL, NULL);
    T_NOTE("target 0.01: %d passes, %d spp, est relMSE %.4g", st.passes, st.spp, st.est_relmse);
    T_CHECK(st.passes > 1 && st.spp == 4 * st.passes && st.est_relmse <= 0.01,
            "passes %d, spp %d, est %g", st.passes, st.spp, st.est_relmse);
    T_CHECK(pa && pb && memcmp(pa, pb, 40 * 30 * 3 * sizeof *pa) == 0,
            "a target-error render is deterministic");
    mcrt_render_free(a);
    mcrt_render_free(b);

    o.target_error = 0.0;
    o.crop_x0 = 30, o.crop_x1 = 41, o.crop_y1 = 5;
    mcrt_render_free(run(s, &o, MCRT_ERR_INVALID));
    o.crop_x0 = 3, o.crop_x1 = 3;
    mcrt_render_free(run(s, &o, MCRT_ERR_INVALID));
    o.crop_x0 = o.crop_x1 = o.crop_y1 = 0;
    o.time_budget = -1.0;
    mcrt_render_free(run(s, &o, MCRT_ERR_INVALID));
    mcrt_render_free(full);
    mcrt_scene_free(s);
    return t_done();
}
