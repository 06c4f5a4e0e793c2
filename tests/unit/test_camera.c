/* test_camera.c: the thin-lens camera and its shutter (src/camera/camera.h), then depth of field
 * in whole renders through the public API: an out-of-focus point images to a uniform disk of the
 * diameter thin-lens geometry predicts, and a plane at the focus distance is as sharp as through
 * a pinhole. Statistical checks pass within 4 standard errors of a noise model stated at each
 * (two-sided p ≈ 6e-5 per check); geometric ones within a stated float-rounding bound. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera/camera.h"
#include "scene/scene.h"
#include "chi2.h"
#include "mcrt.h"
#include "render_util.h"
#include "t.h"

/* Chi-square tests this binary expects to accept (Šidák correction). */
#define CHI2_TESTS 1

static const double PI = 3.14159265358979323846;

/* A camera description with the scene language's defaults, then the given view. */
static struct camera_desc make_desc(vec3 eye, vec3 look, float fov, float lens_radius, float focus)
{
    struct scene s;
    struct camera_desc d;
    mc_scene_init(&s);
    d = s.camera;
    mc_scene_free(&s);
    d.eye = eye;
    d.look = look;
    d.fov = fov;
    d.lens_radius = lens_radius;
    d.focus_distance = focus;
    return d;
}

static vec2 rand2(pcg32 *r)
{
    float a = pcg32_float(r);
    return v2(a, pcg32_float(r));
}

static int same_ray(struct ray a, struct ray b)
{
    return a.o.x == b.o.x && a.o.y == b.o.y && a.o.z == b.o.z && a.d.x == b.d.x && a.d.y == b.d.y
           && a.d.z == b.d.z && a.tmax == b.tmax && a.time == b.time;
}

/* ---- geometry, in double from the description alone ---- */

typedef struct { double x, y, z; } dvec;

static dvec dv(vec3 a) { dvec r = {a.x, a.y, a.z}; return r; }
static dvec d_add(dvec a, dvec b) { dvec r = {a.x + b.x, a.y + b.y, a.z + b.z}; return r; }
static dvec d_scale(dvec a, double s) { dvec r = {a.x * s, a.y * s, a.z * s}; return r; }
static dvec d_sub(dvec a, dvec b) { return d_add(a, d_scale(b, -1.0)); }
static double d_dot(dvec a, dvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double d_len(dvec a) { return sqrt(d_dot(a, a)); }
static dvec d_norm(dvec a) { return d_scale(a, 1.0 / d_len(a)); }
static dvec d_cross(dvec a, dvec b)
{
    dvec r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}

/* The camera frame of man/mcrt.5: forward to look, right = forward × up, up' = right × forward. */
struct view { dvec eye, f, r, u; double tan_half, focus; };

static struct view view_of(const struct camera_desc *d)
{
    struct view fr;
    fr.eye = dv(d->eye);
    fr.f = d_norm(d_sub(dv(d->look), fr.eye));
    fr.r = d_norm(d_cross(fr.f, dv(d->up)));
    fr.u = d_cross(fr.r, fr.f);
    fr.tan_half = tan(0.5 * d->fov * PI / 180.0);
    fr.focus = d->focus_distance > 0.0f ? d->focus_distance : d_len(d_sub(dv(d->look), fr.eye));
    return fr;
}

/* Where the pinhole ray of film point (x, y) meets the focus plane. */
static dvec focus_point(const struct view *fr, int w, int h, double x, double y)
{
    double sx = (2.0 * x / w - 1.0) * fr->tan_half * w / h, sy = (1.0 - 2.0 * y / h) * fr->tan_half;
    dvec dir = d_add(fr->f, d_add(d_scale(fr->r, sx), d_scale(fr->u, sy)));
    return d_add(fr->eye, d_scale(dir, fr->focus));
}

/* Distance from p to the line of ray r. */
static double line_distance(dvec p, struct ray r)
{
    dvec v = d_sub(p, dv(r.o)), d = dv(r.d);
    return d_len(d_sub(v, d_scale(d, d_dot(v, d))));
}

/* With lens_radius 0 the lens ray is the pinhole ray bit for bit, for any lens sample. */
static void test_zero_lens_is_pinhole(void)
{
    struct camera_desc d = make_desc(v3(1, 2, 3), v3(2, 1, -4), 50, 0, 0);
    struct camera c;
    pcg32 rng;
    int i, same = 0, n = 10000;
    mc_camera_init(&c, &d, 160, 90);
    pcg32_seed(&rng, 1, 2);
    for (i = 0; i < n; i++) {
        float x = 160 * pcg32_float(&rng), y = 90 * pcg32_float(&rng);
        same += same_ray(mc_camera_ray_lens(&c, x, y, rand2(&rng)), mc_camera_ray(&c, x, y));
    }
    T_CHECK(same == n, "%d of %d lens rays differ from the pinhole ray", n - same, n);
}

/* Every lens sample's ray through film point (x, y) passes through the one focus-plane point the
 * pinhole ray meets, for an explicit focus distance and for the default |look − eye|; each ray
 * starts on the lens disk, in the plane through the eye normal to the view. The bound on the
 * rounding: each float operation errs by at most ε = 2^-24 relative, and the longest chain
 * (frame normalisation, film direction, lens offset, normalisation) has about a dozen, so the
 * focus point computed in double is missed by at most 16ε·(|eye| + R + F·|D|), |D| ≤ 2 the length
 * of the film direction; the lens-plane checks use 16ε·(|eye| + R). */
static void check_convergence(float focus)
{
    const int w = 160, h = 90;
    const float R = 0.25f;
    const double eps = 0x1p-24;
    struct camera_desc d = make_desc(v3(1, 2, 3), v3(2, 1, -4), 50, R, focus);
    struct view fr = view_of(&d);
    struct camera c;
    pcg32 rng;
    double worst = 0.0, worst_plane = 0.0, widest = 0.0;
    double tol_lens = 16 * eps * (d_len(fr.eye) + R), tol = tol_lens + 32 * eps * fr.focus;
    int i, j, behind = 0;
    mc_camera_init(&c, &d, w, h);
    pcg32_seed(&rng, 3, 4);
    for (i = 0; i < 64; i++) {
        /* the corners, then random film points */
        float x = i < 4 ? (float)((i & 1) * w) : w * pcg32_float(&rng);
        float y = i < 4 ? (float)((i >> 1) * h) : h * pcg32_float(&rng);
        dvec p = focus_point(&fr, w, h, x, y);
        for (j = 0; j < 256; j++) {
            struct ray r = mc_camera_ray_lens(&c, x, y, rand2(&rng));
            dvec lens = d_sub(dv(r.o), fr.eye);
            worst = fmax(worst, line_distance(p, r));
            worst_plane = fmax(worst_plane, fabs(d_dot(lens, fr.f)));
            widest = fmax(widest, d_len(lens));
            /* the focus point lies ahead, along a unit direction (normalised in float: 4ε) */
            behind += d_dot(d_sub(p, dv(r.o)), dv(r.d)) <= 0.0
                      || fabs(d_len(dv(r.d)) - 1.0) > 4 * eps;
        }
    }
    T_NOTE("focus %g: farthest ray from its focus point %.3g (bound %.3g); lens points off the "
           "lens plane by %.3g, out to radius %.7g", fr.focus, worst, tol, worst_plane, widest);
    T_CHECK(worst <= tol, "rays miss the focus point by %g", worst);
    T_CHECK(behind == 0, "%d rays point away from the focus point or are not unit", behind);
    T_CHECK(worst_plane <= tol_lens, "lens points leave the lens plane by %g", worst_plane);
    T_CHECK(widest <= R + tol_lens, "lens points reach radius %.9g > %g", widest, R);
}

/* The lens points are uniform on the disk of radius R: in (ρ²/R², φ/2π) a uniform disk is the
 * uniform density 1 on the unit square (dA = ρ dρ dφ = ½ dρ² dφ), which has no edge that the
 * histogram's cells would cut. Chi-square over 24 × 24 cells, 1e6 samples at random film points. */
struct lens_ctx { struct camera c; struct view fr; double R; };

static int sample_lens(void *ctx, pcg32 *rng, double *x, double *y)
{
    const struct lens_ctx *l = (const struct lens_ctx *)ctx;
    float fx = 64 * pcg32_float(rng), fy = 48 * pcg32_float(rng);
    struct ray r = mc_camera_ray_lens(&l->c, fx, fy, rand2(rng));
    dvec p = d_sub(dv(r.o), l->fr.eye);
    double a = d_dot(p, l->fr.r), b = d_dot(p, l->fr.u), phi = atan2(b, a);
    *x = (a * a + b * b) / (l->R * l->R);
    *y = (phi < 0.0 ? phi + 2.0 * PI : phi) / (2.0 * PI);
    return 1;
}
static void test_lens_uniform(void)
{
    struct lens_ctx l;
    struct camera_desc d = make_desc(v3(-3, 1, 2), v3(0, 0, 0), 35, 0.5f, 2);
    struct chi2_spec s;
    struct chi2_result r;
    mc_camera_init(&l.c, &d, 64, 48);
    l.fr = view_of(&d);
    l.R = 0.5;
    s = chi2_unit_spec("lens points", sample_lens, chi2_unit_density, &l, 24);
    s.seed = 5;
    s.tests = CHI2_TESTS;
    r = chi2_run(&s);
    T_NOTE("lens points: chi2 %.1f, dof %d, p %.3f", r.chi2, r.dof, r.p);
    T_CHECK(r.pass, "lens points are not uniform on the disk: %s", r.why);
}

/* The shutter: times cover [open, close] (u < 1 may round up to close); rays start at shutter
 * open where the camera is then; moving a ray to time t translates its origin by (t − open)·move and keeps its direction, so a
 * lens ray at time t still passes through the focus point carried by t·move. A static camera's
 * rays keep their origin bit for bit. Tolerance: each component of a moved origin comes from
 * eye + open·move + (t − open)·move in five roundings of at most ε/2 of |eye| + |move| (t ≤ 1),
 * so the point is within √3·2.5ε·(|eye| + |move|) < 8ε·(|eye| + |move|) of the exact one; the
 * moved lens rays add that to the convergence bound above. */
static void test_shutter(void)
{
    const double eps = 0x1p-24;
    struct camera_desc d = make_desc(v3(1, 2, 3), v3(2, 1, -4), 50, 0.25f, 0);
    struct view fr;
    struct camera c;
    struct ray r, moved;
    dvec want, p;
    double tol, tol_focus;
    float t;
    int i, ok_dir = 1, still = 1;
    pcg32 rng;

    mc_camera_init(&c, &d, 160, 90);
    r = mc_camera_ray(&c, 10, 20);
    T_CHECK(r.time == 0.0f && mc_camera_time(&c, 0.0f) == 0.0f, "default shutter opens at 0");
    T_CHECK(mc_camera_time(&c, 0.5f) == 0.5f, "default shutter: time(0.5) = %g",
            mc_camera_time(&c, 0.5f));
    pcg32_seed(&rng, 6, 7);
    for (i = 0; i < 1000; i++) {
        r = mc_camera_ray_lens(&c, 160 * pcg32_float(&rng), 90 * pcg32_float(&rng), rand2(&rng));
        moved = r;
        mc_camera_at_time(&c, &moved, pcg32_float(&rng));
        still &= moved.o.x == r.o.x && moved.o.y == r.o.y && moved.o.z == r.o.z;
    }
    T_CHECK(still, "a static camera's rays move with time");

    d.shutter[0] = 0.25f;
    d.shutter[1] = 0.75f;
    d.move = v3(1, -2, 0.5f);
    fr = view_of(&d);
    tol = 8 * eps * (d_len(fr.eye) + d_len(dv(d.move)));
    tol_focus = tol + 16 * eps * (d_len(fr.eye) + 0.25 + 2 * fr.focus);
    mc_camera_init(&c, &d, 160, 90);
    T_CHECK(mc_camera_time(&c, 0.0f) == 0.25f, "time(0) = %g", mc_camera_time(&c, 0.0f));
    T_CHECK(mc_camera_time(&c, 0.5f) == 0.5f, "time(0.5) = %g", mc_camera_time(&c, 0.5f));
    T_CHECK(mc_camera_time(&c, 1.0f - 0x1p-24f) <= 0.75f, "time(1⁻) passes the shutter close");
    r = mc_camera_ray(&c, 80, 45);
    want = d_add(fr.eye, d_scale(dv(d.move), 0.25));
    T_CHECK(r.time == 0.25f, "pinhole ray at time %g, not shutter open", r.time);
    T_NEAR(d_len(d_sub(dv(r.o), want)), 0, tol, "pinhole ray starts at the eye at shutter open");
    moved = r;
    mc_camera_at_time(&c, &moved, 0.7f);
    want = d_add(fr.eye, d_scale(dv(d.move), 0.7f));
    T_CHECK(moved.time == 0.7f, "ray at time %g, not 0.7", moved.time);
    T_NEAR(d_len(d_sub(dv(moved.o), want)), 0, tol, "pinhole ray origin at time 0.7");
    T_CHECK(moved.d.x == r.d.x && moved.d.y == r.d.y && moved.d.z == r.d.z, "direction changed");

    /* Lens rays at random times converge on the moved focus point. */
    for (i = 0; i < 1000; i++) {
        float x = 160 * pcg32_float(&rng), y = 90 * pcg32_float(&rng);
        r = mc_camera_ray_lens(&c, x, y, rand2(&rng));
        t = mc_camera_time(&c, pcg32_float(&rng));
        mc_camera_at_time(&c, &r, t);
        p = d_add(focus_point(&fr, 160, 90, x, y), d_scale(dv(d.move), t));
        ok_dir &= r.time == t && line_distance(p, r) <= tol_focus;
    }
    T_CHECK(ok_dir, "a moved lens ray misses its moved focus point");
}

/* ---- whole renders ---- */

struct img { int w, h; double *v; }; /* green channel */

static int render(const char *text, int spp, uint64_t seed, struct img *out)
{
    struct t_render_opts o = {0, 0, 0, 0, NULL, NULL};
    float *px;
    int i;
    memset(out, 0, sizeof *out);
    o.spp = spp;
    o.seed = seed;
    px = t_render(text, &o, &out->w, &out->h, NULL);
    if (px && (out->v = malloc((size_t)out->w * (size_t)out->h * sizeof *out->v)))
        for (i = 0; i < out->w * out->h; i++)
            out->v[i] = px[3 * i + 1];
    free(px);
    return out->v ? 0 : -1;
}

/* A tiny emitting sphere (radiance Le, black, on the axis at depth dp, radius rs) with the lens
 * (radius R) focused at depth df, on an H × H film with a 40° field of view, nothing else in the
 * scene. Thin-lens geometry: the ray from lens point L through focus-plane point Q meets the
 * sphere iff Q lies in the sphere's projection from L onto the focus plane, centred at
 * L·(1 − df/dp), a linear map of the uniform lens disk. So the image is the uniform disk of
 * radius ρ = R·|dp − df|/dp in focus-plane units (the circle of confusion, diameter
 * c = 2R·|dp − df|/dp), ρ_px = ρ/(2·df·tan 20°)·H pixels, blurred by the sphere's own image, a
 * disk of radius s_px = rs/√(dp² − rs²)/(2·tan 20°)·H.
 * - Radius, from the second moment about the film centre. For the uniform disk convolved with
 *   the sphere's disk E[r²] = ρ²/2 + s²/2, refined by two effects: (1) the projection from L has
 *   area ∝ 1/cosθ = √(1 + |L|²/dp²), which weights the lens and raises ρ²/2 by the factor
 *   1 + R²/(12·dp²); (2) a pixel's value is the image convolved with the unit box (second moment
 *   1/6) taken at the pixel centre, and for an image smooth on the pixel scale (the edge is
 *   blurred over 2s ≈ 5 pixels) the sum over centres equals the integral, so the pixel moment is
 *   E[r²] + 1/6 (checked by quadrature of the closed-form image: +0.166). Terms left out (the
 *   ellipse's centre offset, its shape) moved ρ by < 0.015 px in a 4e8-ray simulation of this
 *   camera, under a tenth of the tolerance. Noise: every sample is Le or 0, a Bernoulli draw
 *   with the `random` sampler, so a pixel of value p has variance (Le·p − p²)/spp; the ratio
 *   estimate's standard error follows by the delta method, and ρ passes within 4 of them.
 * - Energy: Σ pixels = Le·π·s²·E[1/cosθ], E[1/cosθ] = 2/(3a)·((1 + a)^{3/2} − 1), a = R²/dp², over
 *   the uniform lens, within 4 standard errors of the same noise model.
 * - Uniform: no light at all beyond ρ + s + 1 pixels (exact); inside ρ − s − 1 the pixels scatter
 *   only as the Bernoulli noise predicts (their χ²/dof within 4·√(2/dof) of 1), and the mean of
 *   the inner half (by radius) equals the mean of the outer ring (a lens map denser at its
 *   centre, such as ρ = R·ξ, fails all three by far: its E[r²] is ρ²/3, a radius 18% short). The
 *   lens weight 1/cosθ brightens the rim by at most a/2 (2%), under a third of those tolerances.
 * - Centre: the centroid is the film centre, the image of the point, within 4 standard errors. */
static void check_blur_disk(double R, double df, double dp, double rs, int spp, uint64_t seed)
{
    const int H = 96;
    const double t = tan(20.0 * PI / 180.0), a = R * R / (dp * dp);
    const double rho = R * fabs(dp - df) / dp / (2.0 * df * t) * H;
    const double s = rs / sqrt(dp * dp - rs * rs) / (2.0 * t) * H, r_in = rho - s - 1.0;
    const double Le = rho * rho / (s * s); /* the disk's level near 1 */
    const double flux = Le * PI * s * s * 2.0 / (3.0 * a) * (pow(1.0 + a, 1.5) - 1.0);
    double sum = 0.0, m2 = 0.0, var_m2 = 0.0, var_sum = 0.0, outside = 0.0, cx = 0.0, cy = 0.0;
    double in_n = 0.0, in_sum = 0.0, core_n = 0.0, core_sum = 0.0, chi2 = 0.0;
    double var_cx = 0.0, var_cy = 0.0, lvl, core, ring, noise, rho_est, se_rho;
    char text[1024];
    struct img im;
    int i;
    snprintf(text, sizeof text,
             "film { width %d height %d sampler random filter box }\n"
             "camera { eye 0 0 0 look 0 0 -1 fov 40 lens_radius %.9g focus_distance %.9g }\n"
             "material black { diffuse 0 }\n"
             "sphere { center 0 0 %.9g radius %.9g material black emit %.9g }\n",
             H, H, R, df, -dp, rs, Le);
    if (render(text, spp, seed, &im) != 0) {
        T_CHECK(0, "blur render failed");
        return;
    }
    for (i = 0; i < H * H; i++) {
        double x = i % H + 0.5 - H / 2.0, y = i / H + 0.5 - H / 2.0;
        double r2 = x * x + y * y, p = im.v[i];
        sum += p;
        m2 += p * r2;
        cx += p * x;
        cy += p * y;
        if (r2 > (rho + s + 1.0) * (rho + s + 1.0))
            outside += p;
        if (r2 < r_in * r_in) {
            in_n++;
            in_sum += p;
            if (r2 < 0.25 * r_in * r_in) {
                core_n++;
                core_sum += p;
            }
        }
    }
    m2 /= sum;
    cx /= sum;
    cy /= sum;
    lvl = in_sum / in_n;
    core = core_sum / core_n;
    ring = (in_sum - core_sum) / (in_n - core_n);
    noise = (Le * lvl - lvl * lvl) / spp; /* a pixel's variance inside the disk */
    for (i = 0; i < H * H; i++) {
        double x = i % H + 0.5 - H / 2.0, y = i / H + 0.5 - H / 2.0;
        double r2 = x * x + y * y, p = im.v[i];
        double v = fmax(0.0, Le * p - p * p) / spp;
        var_m2 += (r2 - m2) * (r2 - m2) * v;
        var_cx += (x - cx) * (x - cx) * v;
        var_cy += (y - cy) * (y - cy) * v;
        var_sum += v;
        if (r2 < r_in * r_in)
            chi2 += (p - lvl) * (p - lvl) / noise;
    }
    chi2 /= in_n - 1.0;
    /* E[r²] + 1/6 = ρ²/2·(1 + a/12) + s²/2 + 1/6 solved for ρ; d(ρ²) = 2·d(E[r²])/(1 + a/12). */
    rho_est = sqrt((2.0 * (m2 - 1.0 / 6.0) - s * s) / (1.0 + a / 12.0));
    se_rho = sqrt(var_m2) / sum / (rho_est * (1.0 + a / 12.0));
    T_NOTE("focus %g, point at %g, R %g: blur radius %.3f ± %.3f px (thin lens %.3f), centre "
           "(%+.3f, %+.3f) ± %.3f, flux %.1f ± %.1f (expect %.1f), light outside %g, level %.3f "
           "(core %.3f, ring %.3f), χ²/dof %.3f over %.0f pixels",
           df, dp, R, rho_est, se_rho, rho, cx, cy, sqrt(var_cx) / sum, sum, sqrt(var_sum), flux,
           outside, lvl, core, ring, chi2, in_n);
    T_NEAR(rho_est, rho, 4.0 * se_rho, "blur radius");
    T_NEAR(cx, 0.0, 4.0 * sqrt(var_cx) / sum, "blur disk off centre in x");
    T_NEAR(cy, 0.0, 4.0 * sqrt(var_cy) / sum, "blur disk off centre in y");
    T_NEAR(sum, flux, 4.0 * sqrt(var_sum), "flux");
    T_CHECK(outside == 0.0, "light %g beyond the blur disk", outside);
    T_NEAR(chi2, 1.0, 4.0 * sqrt(2.0 / (in_n - 1.0)), "pixels inside the disk scatter beyond noise");
    T_NEAR(core, ring, 4.0 * sqrt(noise * (1.0 / core_n + 1.0 / (in_n - core_n))),
           "the disk's middle and rim differ");
    free(im.v);
}

/* A checker of emitting squares (2.3 pixels wide, so most pixels straddle an edge) on the plane
 * at depth 4, seen through the given camera keys. */
static int render_checker(const char *camera, int spp, uint64_t seed, struct img *out)
{
    const double side = 2.3 * (2.0 * 4.0 * tan(20.0 * PI / 180.0) / 96.0);
    char text[65536];
    size_t n;
    int i, j;
    n = (size_t)snprintf(text, sizeof text,
                         "film { width 96 height 96 sampler random filter box }\n"
                         "camera { eye 0 0 0 look 0 0 -1 fov 40 %s }\n"
                         "material black { diffuse 0 }\n", camera);
    /* 20 × 20 cells centred on the axis, every other one emitting; (a,0,0) × (0,a,0) faces +z. */
    for (i = 0; i < 20; i++)
        for (j = 0; j < 20; j++)
            if ((i + j) % 2 == 0)
                n += (size_t)snprintf(text + n, sizeof text - n,
                                      "quad { corner %.9g %.9g -4 edge1 %.9g 0 0 edge2 0 %.9g 0 "
                                      "material black emit 1 }\n",
                                      (i - 10) * side, (j - 10) * side, side, side);
    return render(text, spp, seed, out);
}

/* The checker through a pinhole, through a lens of radius 0.3 focused on it, and through the
 * same lens focused at 4.2 (a circle of confusion of about one pixel). Every film point sees the
 * same point of the focus plane through every lens point, so the focused lens image equals the
 * pinhole image in expectation. Each sample is 1 or 0, so with independent seeds a pixel
 * difference d has variance V = 2·(m − m²)/spp, m the mean of the two renders' values;
 * S = Σd² has mean ΣV and, d being near normal, variance Σ2V². The focused lens must give
 * z = (S − ΣV)/√(Σ2V²) ≤ 4; the misfocused one must not, which shows the check can fail. */
static double excess_over_noise(const char *camera, const struct img *pin, int spp)
{
    struct img im;
    double S = 0.0, EV = 0.0, VV = 0.0, z;
    int i;
    if (render_checker(camera, spp, 11, &im) != 0) {
        T_CHECK(0, "checker render failed");
        return INFINITY;
    }
    for (i = 0; i < im.w * im.h; i++) {
        double d = im.v[i] - pin->v[i], m = 0.5 * (im.v[i] + pin->v[i]);
        double V = 2.0 * fmax(0.0, m - m * m) / spp;
        S += d * d;
        EV += V;
        VV += 2.0 * V * V;
    }
    z = (S - EV) / sqrt(VV);
    T_NOTE("checker on the focus plane, camera { %s }: Σd² %.4f, noise alone %.4f ± %.4f, "
           "z = %.1f", camera, S, EV, sqrt(VV), z);
    free(im.v);
    return z;
}

static void test_focus_plane_sharp(void)
{
    const int spp = 64;
    struct img pin;
    if (render_checker("", spp, 10, &pin) != 0) {
        T_CHECK(0, "pinhole checker render failed");
        return;
    }
    T_CHECK(excess_over_noise("lens_radius 0.3 focus_distance 4", &pin, spp) <= 4.0,
            "the focus plane is blurred by the lens");
    T_CHECK(excess_over_noise("lens_radius 0.3 focus_distance 4.2", &pin, spp) > 4.0,
            "a one-pixel circle of confusion passes as sharp: the check has no power");
    free(pin.v);
}

int main(void)
{
    test_zero_lens_is_pinhole();
    check_convergence(6.0f);
    check_convergence(0.0f); /* |look − eye| */
    test_lens_uniform();
    test_shutter();
    /* Behind the focus plane (R/dp = 0.075) and in front of it (R/dp = 0.2). */
    check_blur_disk(0.45, 2.0, 6.0, 0.12, 1024, 21);
    check_blur_disk(0.5, 10.0, 2.5, 0.05, 1024, 22);
    test_focus_plane_sharp();
    return t_done();
}
