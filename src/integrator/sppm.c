/* sppm.c: stochastic progressive photon mapping (Hachisuka and Jensen 2009), the consistent
 * estimator beside the path tracer, with the per-pixel statistics and update of pbrt-v4's
 * SPPMIntegrator, written for mcrt's determinism: the image depends only on the scene, the
 * options and the seed, for any number of threads.
 *
 * Each pass k:
 *   1. the camera pass (one camera sample per pixel, on the tile pool): the path is followed
 *      through delta surfaces and through glossy ones smoother than SPPM_GLOSSY_ALPHA, with
 *      emission and next-event estimation under MIS exactly as the path tracer does; at the
 *      first other surface it takes the direct light there (a light sample and a BSDF sample,
 *      both MIS-weighted) and stops: that surface point is the pixel's visible point of the pass;
 *   2. the visible points go into a hash grid (cells of twice the largest radius, so a point
 *      lies in at most 8; filled by a counting sort, serially, so in a fixed order);
 *   3. the photon pass: `photons` paths from the lights (emission sampling, BSDFs in importance
 *      mode with the shading-normal correction, Russian roulette keeping the flux constant),
 *      traced in fixed chunks of SPPM_CHUNK photons, each photon's numbers keyed by (seed, pass,
 *      photon); from its second surface on, a photon at a non-delta surface is given to every
 *      visible point of its grid cell within that point's radius, unless it arrives on the other
 *      side of a surface that only reflects (Mitsuba #145: such photons would shrink the radius
 *      and add noise); each chunk records its deposits, and the records are summed chunk by chunk
 *      in order, so no float is ever added in an order that depends on threads;
 *   4. the update of each pixel that received M photons of flux Φ (pbrt-v4):
 *      N' = N + αM, R' = R·sqrt(N'/(N + M)), τ' = (τ + β·Φ)·R'²/R².
 * The camera ray's time, and the photons', is one time per pass (pbrt-v4 #440).
 *
 * The pixel is L = Ld/k + τ/(k·photons·π·R²), Ld the sum of the passes' direct (and emitted and
 * specular-chain) light. The bias comes from the radius (the photon density is blurred over a
 * disk of radius R, which shrinks as N^−(1−α)/2 per pixel); the variance falls as the photons
 * accumulate.
 *
 * Path lengths agree with the path tracer's max_depth: a visible point found after k bounces of
 * the camera path (k = 0 at the first hit) takes photons that have made at most max_depth − k − 1
 * bounces before reaching it, so that a camera-and-photon path has at most max_depth scattering
 * vertices, as the path tracer's paths do. */
#include "integrator/integrator.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "camera/camera.h"
#include "core/alloc.h"
#include "core/clock.h"
#include "integrator/path_vertex.h"
#include "integrator/point_grid.h"
#include "sample/filter.h"
#include "sample/sampler.h"
#include "scene/features.h"

/* Photons per chunk: the unit of work of the photon pass, and the unit its records are merged in. */
#define SPPM_CHUNK 1024
/* The groups the passes are dealt into for the error estimate (see pixel_value): each group's
 * camera samples are one complete sampler set of its own seed. */
#define SPPM_GROUPS 4


/* ---- the state ---- */

/* Glossy lobes smoother than this GGX α (roughness² ≈ 0.1², a highlight a few degrees wide) are
 * followed by the camera path like mirrors, since a photon density blurred over the radius would
 * blur their reflections; rougher ones, and every diffuse surface, take the visible point. */
#define SPPM_GLOSSY_ALPHA 0.01f

struct vpoint {
    struct bsdf b;     /* the visible point's BSDF */
    frame fr;          /* its shading frame */
    vec3 p, wo;        /* position; direction to the camera in the local frame */
    vec3 ng;           /* geometric normal on the camera's side */
    vec3 beta;         /* camera-path throughput to the point */
    int depth;         /* camera bounces before it (0: the first hit) */
    int valid;
    int reflect_only;  /* the material does not transmit: photons from behind are not counted */
    vec3 ld;           /* this pass's direct (and emitted) light */
};

struct sppm_pixel {
    double ld[3];      /* Σ over passes of the direct (and emitted) light of the camera path */
    double tau[3];     /* the flux statistic τ */
    double n;          /* N */
    double r;          /* the radius R */
    double phi[3];     /* this pass: Σ β_photon·f over the photons it received */
    double phi_lap[3]; /* this pass: Σ β_photon·f·(6s² − 3), s = distance / R (see pixel_value) */
    uint64_t m;        /* this pass: photons received */
    /* For the error estimate, per group of passes (pass_group): Σ Y_j, the passes' own
     * estimates, and Σ B_j, their estimated biases. */
    double ysum[SPPM_GROUPS][3], bsum[SPPM_GROUPS][3];
};

struct deposit {
    uint32_t vp;       /* the visible point */
    float phi[3];
    float lap;         /* 6s² − 3, s = the distance over the point's radius */
};

struct chunk {
    struct deposit *d;
    size_t n, cap;
    int failed;        /* out of memory: the pass fails */
    uint64_t rays;
};

struct sppm_state {
    int width, height, x0, y0;
    size_t npix;
    long photons;
    double radius0;
    struct sppm_pixel *px;
    struct vpoint *vp;
    vec3 *vp_p;        /* the visible points' positions and radii (0: none), for the grid */
    double *vp_r;
    struct point_grid grid;
    struct chunk *chunks;
    size_t nchunks;
};


/* ---- the camera pass ---- */

/* The group of pass j (passes are dealt round the groups; see pixel_value), and how many of
 * passes 0 .. k−1 are in group g. */
static int pass_group(int j) { return j % SPPM_GROUPS; }
static int group_passes(int k, int g) { return k / SPPM_GROUPS + (g < k % SPPM_GROUPS); }

struct pass_ctx {
    const struct scene *s;
    const struct integrator_desc *cfg;
    const struct render_settings *rs;
    struct sppm_state *st;
    struct camera cam;
    int pass, lens, mis;
    unsigned motion; /* FEATURE_MOTION when the scene moves, else 0: the F of path_vertex.h */
    uint32_t sampler_spp[SPPM_GROUPS]; /* the camera samples of each group of passes */
    float time;
    uint64_t seed;
};

static vec3 direct(const struct pass_ctx *c, const struct surface *sf, struct light_select_at *at,
                   const frame *fr, const struct bsdf *b, vec3 wo, struct sampler *smp,
                   uint64_t *rays)
{
    vec3 L = v3s(0.0f);
    int i, n = c->cfg->light_samples;
    for (i = 0; i < n; i++)
        L = v3_add(L, light_sample(c->s, sf, at, c->time, fr, b, wo, smp, rays, n, c->motion, c->mis));
    return L;
}

/* The MIS weight of emission from light `light` found by a BSDF sample of pdf bsdf_pdf from the
 * shading point prev, whose light samples chose there. */
static float emitted_weight(const struct pass_ctx *c, int light, struct light_select_at *prev,
                            float bsdf_pdf, const struct ray *r, float t, const struct surface *sf)
{
    return emitted_mis_weight(c->s, c->cfg->light_samples, light, prev, bsdf_pdf, r, t, sf);
}

/* The light a BSDF sample from the visible point finds directly (MIS-weighted): the other half of
 * the direct light at the visible point, whose light samples direct() took. */
static vec3 bsdf_emission(const struct pass_ctx *c, const struct surface *sf,
                          struct light_select_at *at, const frame *fr, const struct bsdf *b,
                          vec3 wo, struct sampler *smp, uint64_t *rays)
{
    const struct scene *s = c->s;
    struct bsdf_sample bs;
    struct ray r;
    struct hit h;
    float uc = mc_bsdf_chooses(b) ? mc_sampler_1d(smp) : 0.5f;
    vec2 u = mc_sampler_2d(smp);
    if (!mc_bsdf_sample(b, wo, uc, u, MC_RADIANCE, &bs) || bs.delta)
        return v3s(0.0f); /* a delta lobe's light is the camera path's, followed elsewhere */
    r.d = frame_to_world(fr, bs.wi);
    if (through_surface(b, sf->ng, frame_to_world(fr, wo), r.d))
        return v3s(0.0f);
    r.o = ray_spawn(sf->p, side_normal(sf->ng, r.d), sf->err);
    r.tmax = INFINITY;
    r.time = c->time;
    h.t = INFINITY;
    ++*rays;
    if (!trace(s, &r, &h, c->motion)) {
        if (s->env_light < 0)
            return v3s(0.0f);
        vec3 Le = mc_environment_radiance(&s->lights[s->env_light], r.d);
        return v3_scale(v3_mul(bs.weight, Le),
                        emitted_weight(c, s->env_light, at, bs.pdf, &r, INFINITY, NULL));
    } else {
        struct surface lsf;
        const struct prim *pr = &s->prims[h.prim];
        vec3 Le;
        if (pr->light < 0)
            return v3s(0.0f);
        surface(s, &r, &h, &lsf, c->motion);
        Le = mc_light_emitted(pr, &lsf);
        if (v3_is_zero(Le))
            return v3s(0.0f);
        return v3_scale(v3_mul(bs.weight, Le),
                        emitted_weight(c, pr->light, at, bs.pdf, &r, h.t, &lsf));
    }
}

/* The discrete probability of a BSDF's delta lobe at wo, for BSDFs that mix one with non-delta
 * lobes (plastic's smooth coat), or 0: such a BSDF chooses its delta lobe for uc below that
 * probability (bsdf.h), so a sample at uc = 0 reports it as its pdf. */
static float delta_probability(const struct bsdf *b, vec3 wo)
{
    struct bsdf_sample bs;
    if (mc_bsdf_sample(b, wo, 0.0f, v2(0.5f, 0.5f), MC_RADIANCE, &bs) && bs.delta)
        return bs.pdf;
    return 0.0f;
}

static void camera_pixel(const struct pass_ctx *c, struct tile_worker *w, int x, int y)
{
    const struct scene *s = c->s;
    const struct integrator_desc *cfg = c->cfg;
    struct sppm_state *st = c->st;
    size_t i = (size_t)(y - st->y0) * (size_t)st->width + (size_t)(x - st->x0);
    struct vpoint *v = &st->vp[i];
    struct sampler smp;
    struct ray r;
    vec3 L = v3s(0.0f), beta = v3s(1.0f);
    struct light_select_at prev; /* the last non-delta vertex (path.c, radiance) */
    vec2 off;
    float prev_pdf = 0.0f, eta_scale = 1.0f;
    int depth = 0, specular = 1;
    v->valid = 0;
    mc_sampler_pixel(&smp, c->rs->sampler, mc_film_half_seed(c->rs->seed, pass_group(c->pass)), x,
                     y, (int)c->sampler_spp[pass_group(c->pass)]); /* its group's sampler set */
    mc_sampler_start(&smp, (uint32_t)(c->pass / SPPM_GROUPS));
    off = mc_filter_sample(s->film.filter, mc_sampler_2d(&smp));
    off.x += (float)x + 0.5f;
    off.y += (float)y + 0.5f;
    r = c->lens ? mc_camera_ray_lens(&c->cam, off.x, off.y, mc_sampler_2d(&smp))
                : mc_camera_ray(&c->cam, off.x, off.y);
    if (c->motion)
        mc_camera_at_time(&c->cam, &r, c->time);
    if (c->rs->aov) /* first-hit layers: each pass's camera ray, as a per-ray render's samples */
        mc_aov_record(&c->rs->aov->pixels[i], (int)(c->pass & 1), s, &r);
    mc_light_select_at(&prev, r.o, v3s(0.0f));
    for (;;) {
        struct hit h;
        struct surface sf;
        struct bsdf b;
        struct bsdf_sample bs;
        const struct prim *pr;
        frame fr;
        vec3 wo, wi, Le;
        float uc;
        vec2 u;
        h.t = r.tmax;
        w->rays++;
        if (!trace(s, &r, &h, c->motion)) {
            if (s->env_light >= 0) {
                float wt = specular || !c->mis ? 1.0f
                                               : emitted_weight(c, s->env_light, &prev, prev_pdf,
                                                                &r, INFINITY, NULL);
                Le = mc_environment_radiance(&s->lights[s->env_light], r.d);
                L = v3_add(L, v3_scale(v3_mul(beta, Le), wt));
            }
            break;
        }
        pr = &s->prims[h.prim];
        surface(s, &r, &h, &sf, c->motion);
        Le = mc_light_emitted(pr, &sf);
        if (!v3_is_zero(Le)) {
            float wt = specular || !c->mis ? 1.0f
                                           : emitted_weight(c, pr->light, &prev, prev_pdf, &r,
                                                            h.t, &sf);
            L = v3_add(L, v3_scale(v3_mul(beta, Le), wt));
        }
        if (depth == cfg->max_depth)
            break;
        mc_scene_bsdf(s, &r, &h, &b);
        fr = frame_from_normal(sf.ns);
        wo = frame_to_local(&fr, v3_neg(r.d));
        uc = mc_sampler_1d(&smp);
        u = mc_sampler_2d(&smp);
        if (!mc_bsdf_is_delta(&b)) {
            mc_light_select_at(&prev, sf.p, sf.ns);
            if (!(b.alpha > 0.0f && b.alpha < SPPM_GLOSSY_ALPHA)) {
                float pd = delta_probability(&b, wo);
                if (!(uc < pd)) {
                    /* The visible point: taken with probability 1 − pd, so weighted by its
                     * inverse. */
                    vec3 bv = v3_scale(beta, 1.0f / (1.0f - pd));
                    L = v3_add(L, v3_mul(bv, direct(c, &sf, &prev, &fr, &b, wo, &smp, &w->rays)));
                    if (c->mis)
                        L = v3_add(L, v3_mul(bv, bsdf_emission(c, &sf, &prev, &fr, &b, wo, &smp,
                                                               &w->rays)));
                    v->b = b;
                    v->fr = fr;
                    v->p = sf.p;
                    v->wo = wo;
                    v->ng = side_normal(sf.ng, v3_neg(r.d));
                    v->beta = bv;
                    v->depth = depth;
                    v->reflect_only = s->materials[pr->material].kind != MC_MATERIAL_KIND(glass);
                    v->valid = !v3_is_zero(bv) && v3_is_finite(bv);
                    break;
                }
                /* The delta lobe, chosen with probability pd: the sample below is it. */
            } else {
                L = v3_add(L, v3_mul(beta, direct(c, &sf, &prev, &fr, &b, wo, &smp, &w->rays)));
            }
        }
        if (!mc_bsdf_sample(&b, wo, uc, u, MC_RADIANCE, &bs))
            break;
        beta = v3_mul(beta, bs.weight);
        if (v3_is_zero(beta))
            break;
        if (bs.eta != 1.0f)
            eta_scale *= bs.eta * bs.eta;
        wi = frame_to_world(&fr, bs.wi);
        if (through_surface(&b, sf.ng, v3_neg(r.d), wi))
            break;
        specular = bs.delta;
        prev_pdf = bs.pdf;
        r.o = ray_spawn(sf.p, side_normal(sf.ng, wi), sf.err);
        r.d = wi;
        r.tmax = INFINITY;
        depth++;
        if (depth >= cfg->rr_depth) {
            float q = v3_max_comp(beta) * eta_scale;
            if (q < 1.0f) {
                if (!(mc_sampler_1d(&smp) < q))
                    break;
                beta = v3_scale(beta, 1.0f / q);
            }
        }
    }
    if (!v3_is_finite(L)) {
        w->nans++;
        L = v3s(0.0f);
        v->valid = 0;
    }
    v->ld = L;
}

static void camera_tile(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)
{
    int x, y;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++)
            camera_pixel(ctx, w, x, y);
}

/* ---- the photon pass ---- */

static int record(struct chunk *ch, uint32_t vp, vec3 phi, float lap)
{
    if (ch->n == ch->cap) {
        size_t cap = ch->cap ? 2 * ch->cap : 1024;
        struct deposit *d = mc_realloc(ch->d, cap * sizeof *d);
        if (!d) {
            ch->failed = 1;
            return -1;
        }
        ch->d = d;
        ch->cap = cap;
    }
    ch->d[ch->n].vp = vp;
    ch->d[ch->n].phi[0] = phi.x;
    ch->d[ch->n].phi[1] = phi.y;
    ch->d[ch->n].phi[2] = phi.z;
    ch->d[ch->n].lap = lap;
    ch->n++;
    return 0;
}

/* A photon of flux beta at p arriving from direction wi (toward where it came from), after
 * `hits` surfaces (this one included): to every visible point that it reaches. */
static void deposit(const struct pass_ctx *c, struct chunk *ch, vec3 p, vec3 wi, int hits,
                    vec3 beta)
{
    const struct sppm_state *st = c->st;
    size_t n, k;
    const uint32_t *cand = mc_point_grid_query(&st->grid, p, &n);
    for (k = 0; k < n; k++) {
        uint32_t i = cand[k];
        const struct vpoint *v = &st->vp[i];
        double r = st->vp_r[i];
        vec3 d = v3_sub(v->p, p);
        if ((double)v3_dot(d, d) > r * r)
            continue;
        if (v->reflect_only && !(v3_dot(wi, v->ng) > 0.0f))
            continue; /* from behind a surface that only reflects (Mitsuba #145) */
        if (c->cfg->max_depth >= 0 && v->depth + hits > c->cfg->max_depth)
            continue;
        record(ch, i,
               v3_mul(beta, mc_bsdf_eval(&v->b, v->wo, frame_to_local(&v->fr, wi), MC_RADIANCE)),
               (float)(6.0 * (double)v3_dot(d, d) / (r * r) - 3.0));
    }
}

static void trace_photon(const struct pass_ctx *c, struct chunk *ch, uint64_t index)
{
    const struct scene *s = c->s;
    struct light_emission e;
    struct ray r;
    pcg32 g;
    vec3 beta;
    vec2 up, ud;
    float pmf;
    int li, hits, maxd = c->cfg->max_depth;
    pcg32_seed(&g, mc_hash3(c->seed, (uint64_t)c->pass, index), 0x70686f746f6eULL);
    li = mc_alias_sample(&s->light_select.power, pcg32_double(&g), &pmf); /* photons: by power */
    if (li < 0 || !(pmf > 0.0f))
        return;
    up.x = pcg32_float(&g);
    up.y = pcg32_float(&g);
    ud.x = pcg32_float(&g);
    ud.y = pcg32_float(&g);
    if (!mc_light_sample_emission(&s->light_scene, &s->lights[li], c->time, up, ud, &e))
        return;
    beta = v3_scale(e.weight, 1.0f / pmf);
    if (v3_is_zero(beta) || !v3_is_finite(beta))
        return;
    r.o = s->lights[li].kind == LIGHT_AREA
              ? ray_spawn(e.p, e.n, s->lights[li].point_error)
              : e.p;
    r.d = e.d;
    r.tmax = INFINITY;
    r.time = c->time;
    for (hits = 1;; hits++) {
        struct hit h;
        struct surface sf;
        struct bsdf b;
        struct bsdf_sample bs;
        frame fr;
        vec3 wi = v3_neg(r.d), wn, bn;
        float num, den, q;
        h.t = r.tmax;
        ch->rays++;
        if (!trace(s, &r, &h, c->motion))
            break;
        surface(s, &r, &h, &sf, c->motion);
        mc_scene_bsdf(s, &r, &h, &b);
        /* The first surface a photon reaches is direct light, which the camera pass takes. */
        if (hits >= 2 && !mc_bsdf_is_delta(&b))
            deposit(c, ch, sf.p, wi, hits, beta);
        if (maxd >= 0 && hits >= maxd)
            break;
        fr = frame_from_normal(sf.ns);
        {
            float uc = pcg32_float(&g);
            vec2 u;
            u.x = pcg32_float(&g);
            u.y = pcg32_float(&g);
            if (!mc_bsdf_sample(&b, frame_to_local(&fr, wi), uc, u, MC_IMPORTANCE, &bs))
                break;
        }
        wn = frame_to_world(&fr, bs.wi);
        if (through_surface(&b, sf.ng, wi, wn))
            break;
        /* Shading normals are not symmetric for importance (Veach 1997 §5.3, pbrt-v4
         * CorrectShadingNormal): |wi·ns||wn·ng| / (|wi·ng||wn·ns|), wi toward the light. */
        num = fabsf(v3_dot(wi, sf.ns)) * fabsf(v3_dot(wn, sf.ng));
        den = fabsf(v3_dot(wi, sf.ng)) * fabsf(v3_dot(wn, sf.ns));
        if (!(den > 0.0f))
            break;
        bn = v3_scale(v3_mul(beta, bs.weight), num / den);
        /* Russian roulette keeps the photon's flux about constant: survive with the ratio of
         * the new to the old largest channel. */
        q = v3_max_comp(bn) / v3_max_comp(beta);
        if (!(q > 0.0f) || !v3_is_finite(bn))
            break;
        if (q < 1.0f) {
            if (!(pcg32_float(&g) < q))
                break;
            bn = v3_scale(bn, 1.0f / q);
        }
        beta = bn;
        r.o = ray_spawn(sf.p, side_normal(sf.ng, wn), sf.err);
        r.d = wn;
        r.tmax = INFINITY;
    }
}

/* Tile x range [16k, 16k + 16) of a window 16·nchunks wide is chunk k. */
static void photon_tile(void *ctx, struct tile_worker *w, int x0, int y0, int x1, int y1)
{
    const struct pass_ctx *c = ctx;
    struct sppm_state *st = c->st;
    size_t k = (size_t)x0 / MC_TILE;
    struct chunk *ch = &st->chunks[k];
    uint64_t i, first = (uint64_t)k * SPPM_CHUNK, last = first + SPPM_CHUNK;
    (void)y0, (void)y1, (void)x1;
    if (last > (uint64_t)st->photons)
        last = (uint64_t)st->photons;
    ch->n = 0;
    ch->failed = 0;
    ch->rays = 0;
    for (i = first; i < last; i++)
        trace_photon(c, ch, i);
    w->rays += ch->rays;
}

/* ---- the passes ---- */

/* The progress of the whole render, from the fraction of each tile run: the camera pass takes
 * the first fifth of a pass, the photons the rest; with a time budget, the time spent. Never
 * decreasing. */
struct progress {
    const struct render_settings *rs;
    double base, span, last, t0;
};

static int report(void *user, double done)
{
    struct progress *p = user;
    double f = p->base + p->span * done;
    if (p->rs->time_budget > 0.0) {
        double t = (mc_seconds() - p->t0) / p->rs->time_budget;
        f = t > f ? t : f;
    }
    f = f < 0.999 ? f : 0.999;
    if (f > p->last)
        p->last = f;
    return p->rs->progress(p->rs->user, p->last);
}

static mcrt_status sppm_prepare(const struct integrator *self, const struct scene *s,
                                struct render_settings *rs, void **state, mc_diag *d)
{
    (void)self;
    (void)s;
    (void)state;
    if (rs->adaptive)
        return mc_fail(d, MCRT_ERR_INVALID,
                       "sppm does not sample adaptively (its passes share per-pixel statistics)");
    return MCRT_OK;
}

static void state_free(struct sppm_state *st)
{
    size_t k;
    for (k = 0; k < st->nchunks; k++)
        free(st->chunks[k].d);
    free(st->chunks);
    free(st->px);
    free(st->vp);
    free(st->vp_p);
    free(st->vp_r);
    mc_point_grid_free(&st->grid);
}

/* The pixel's estimate after `passes` passes, and the estimated mean squared error of it per
 * channel, bias² + variance (-1 when fewer than 2 passes), in mse[0..2]; the estimate of bias²
 * alone (which may be negative, see below) in bias2[0..2] when not NULL.
 *
 * Variance: the estimate is the mean of the passes' own estimates Y_j (each with the radius it
 * gathered with: τ/R² telescopes to Σ Φ_j/R_{j−1}²), which are independent across passes for
 * their photons but not for their camera samples when a stratified or Sobol sampler spreads
 * those over the passes: the passes' own spread then overstates the mean's variance (the
 * successive differences of the Y_j, von Neumann 1941, read 2.0× and 2.6× the true relMSE at
 * 64 and 256 passes on a 32² cornell). So the passes are dealt round G = SPPM_GROUPS groups,
 * each a complete sampler set of its own seed (as the path tracer's two halves are, film.h),
 * whose means Ȳ_g are independent, and Var(mean) = Σ_g n_g(Ȳ_g − Ȳ)² / ((G − 1)·k), the
 * between-groups estimate of the one-pass variance σ² over k. Dealt round, the groups share the
 * drift of the Y_j (the bias shrinking, the variance growing with the radius) to O(1/k). G = 4
 * (measured, 32², 4 seeds, the truth against a 4096-spp path-traced reference): with 2 groups
 * the estimate read 1.6–2.5× the truth on cornell (its one degree of freedom per pixel makes
 * the floor of the film's denominator, mc_film_mean_squared, bite in noisy pixels), with 4
 * 1.3–1.7× on cornell and 0.82–0.87× on cornell-spheres at 64 and 256 passes, for every
 * sampler; more groups estimate better still but stratify each group's camera samples less
 * (cornell's true relMSE at 64 passes grew 1.3–1.6× from 2 groups to 4).
 *
 * Bias, without a reference, as Hachisuka, Jarosz and Jensen 2010 estimate it: where the
 * radiance is smooth to second order over the disk, a disk of radius R gathers L + R²ΔL/8 in
 * expectation (its second moment is R²/4 per axis), and ΔL is estimated from the same photons by
 * the Laplacian of a smooth kernel, the biweight K(s) = (3/π)(1 − s²)² (Silverman 1986), whose
 * ΔK_R = (3/π)(16s² − 8)/R⁴ for s = distance/R: the pass's bias is then
 * B_j = R²ΔL̂/8 = β·Σ_p Φ_p·(6s_p² − 3) / (photons·πR²) (the weight 6s² − 3 integrates to 0 over
 * the disk: a flat density has no bias). The estimate's bias is b = mean B_j; its square is
 * taken less its own noise (the variance of that mean, from the groups as for Y), which leaves
 * b² unbiased where b is small but may make it negative: only the sum bias² + variance is kept
 * from going below 0, so that the image's mean over pixels stays close to unbiased. (Clamping
 * each b² at 0 overestimated the relMSE 2.4× at 256 passes on a 24² cornell; pooling b over
 * 3×3 pixels underestimated it 3× on the caustics of cornell-spheres.)
 *
 * Measured against the truth (32², 4 seeds, bias² = the true MSE less the seeds' spread), it
 * reads 0.46–0.63 of bias² on cornell-spheres at 64 and 256 passes: at edges and caustic
 * boundaries the bias is first order in R, which a second-order estimate misses. A finite
 * difference of two radii (what R gathers against R/√2: the same expectation under the same
 * assumption) read the same, 0.49–0.66, with more noise (its weight ±2 has second moment 4
 * against 3), which put cornell's total at 1.3–1.7× the truth against 1.1–1.5× with the kernel;
 * a third radius, R/2, fitting the order per pixel (Aitken's Δ²) read 0.73–0.89 of bias² but its
 * noise, through the clamp at 0, took cornell's total to 2.0×. */
static vec3 pixel_value(const struct sppm_state *st, size_t i, int passes, double *mse,
                        double *bias2)
{
    const struct sppm_pixel *q = &st->px[i];
    double k = passes, np = k * (double)st->photons, area = MC_PI * q->r * q->r, v[3];
    int ch, g, groups = passes < SPPM_GROUPS ? passes : SPPM_GROUPS; /* the groups not empty */
    for (ch = 0; ch < 3; ch++) {
        v[ch] = q->ld[ch] / k + q->tau[ch] / (np * area);
        if (passes >= 2) {
            double ym = 0.0, b = 0.0, sy = 0.0, sb = 0.0, b2, var;
            for (g = 0; g < groups; g++) {
                ym += q->ysum[g][ch] / k;
                b += q->bsum[g][ch] / k;
            }
            for (g = 0; g < groups; g++) { /* the between-groups sums of squares */
                double ng = group_passes(passes, g);
                double ey = q->ysum[g][ch] / ng - ym, eb = q->bsum[g][ch] / ng - b;
                sy += ng * ey * ey;
                sb += ng * eb * eb;
            }
            var = sy / ((groups - 1) * k);
            b2 = b * b - sb / ((groups - 1) * k);
            mse[ch] = var + b2 > 0.0 ? var + b2 : 0.0;
            if (bias2)
                bias2[ch] = b2;
        } else {
            mse[ch] = -1.0;
            if (bias2)
                bias2[ch] = 0.0;
        }
    }
    return v3((float)v[0], (float)v[1], (float)v[2]);
}

/* The film pixel of an SPPM estimate: the one place SPPM writes a film. One sample v ∓ √mse in
 * each half gives the film the mean v and, whether it reads the halves ((A − B)²/4) or the pooled
 * sample variance (2·mse over 2 samples), the variance of the mean mse; without an error
 * estimate, one sample in half 0. */
static void film_put(struct film_pixel *fp, vec3 v, const double *mse)
{
    if (mse[0] >= 0.0) {
        vec3 e = v3((float)sqrt(mse[0]), (float)sqrt(mse[1]), (float)sqrt(mse[2]));
        mc_film_add(&fp->half[0], v3_sub(v, e));
        mc_film_add(&fp->half[1], v3_add(v, e));
    } else {
        mc_film_add(&fp->half[0], v);
    }
}

/* Merge the chunks' records in chunk order, then update each pixel (pbrt-v4's formulas). */
static void update(struct sppm_state *st, const struct integrator_desc *cfg, int passes)
{
    size_t k, i;
    double alpha = cfg->alpha, np = (double)st->photons;
    int group = pass_group(passes);
    for (k = 0; k < st->nchunks; k++) {
        const struct chunk *ch = &st->chunks[k];
        for (i = 0; i < ch->n; i++) {
            struct sppm_pixel *q = &st->px[ch->d[i].vp];
            q->phi[0] += ch->d[i].phi[0];
            q->phi[1] += ch->d[i].phi[1];
            q->phi[2] += ch->d[i].phi[2];
            q->phi_lap[0] += ch->d[i].phi[0] * ch->d[i].lap;
            q->phi_lap[1] += ch->d[i].phi[1] * ch->d[i].lap;
            q->phi_lap[2] += ch->d[i].phi[2] * ch->d[i].lap;
            q->m++;
        }
    }
    for (i = 0; i < st->npix; i++) {
        struct sppm_pixel *q = &st->px[i];
        const struct vpoint *v = &st->vp[i];
        const double ld[3] = {v->ld.x, v->ld.y, v->ld.z}, b[3] = {v->beta.x, v->beta.y, v->beta.z};
        double area = MC_PI * q->r * q->r;
        int ch;
        for (ch = 0; ch < 3; ch++) {
            /* This pass's own estimate Y_j and its bias B_j, into its group's sums. */
            q->ysum[group][ch] += ld[ch] + (q->m ? b[ch] * q->phi[ch] / (np * area) : 0.0);
            if (q->m)
                q->bsum[group][ch] += b[ch] * q->phi_lap[ch] / (np * area);
            q->ld[ch] += ld[ch];
        }
        if (q->m > 0) {
            double n1 = q->n + alpha * (double)q->m, r1 = q->r * sqrt(n1 / (q->n + (double)q->m));
            double shrink = (r1 * r1) / (q->r * q->r);
            for (ch = 0; ch < 3; ch++)
                q->tau[ch] = (q->tau[ch] + b[ch] * q->phi[ch]) * shrink;
            q->n = n1;
            q->r = r1;
        }
        q->phi[0] = q->phi[1] = q->phi[2] = 0.0;
        q->phi_lap[0] = q->phi_lap[1] = q->phi_lap[2] = 0.0;
        q->m = 0;
    }
}

/* The image's estimated relMSE (as mc_film_est_relmse would find it in the film), and its bias²
 * part in *bias2 (NULL: not wanted); NaN below 2 passes. */
static double film_relmse(const struct sppm_state *st, int passes, double *bias2)
{
    size_t i;
    double sum = 0.0, sb = 0.0;
    for (i = 0; i < st->npix; i++) {
        double mse[3], b2[3], w[3];
        vec3 v = pixel_value(st, i, passes, mse, b2);
        int ch;
        if (mse[0] < 0.0)
            return bias2 ? *bias2 = NAN : NAN;
        /* The film's own denominator for what film_put writes (mc_film_mean_squared, plus
         * ε), so that the parts add up to the film's est_relmse whatever it does. */
        {
            struct film_pixel tmp;
            memset(&tmp, 0, sizeof tmp);
            film_put(&tmp, v, mse);
            for (ch = 0; ch < 3; ch++)
                w[ch] = 1.0 / (mc_film_mean_squared(&tmp, ch) + MC_RELMSE_EPS);
        }
        for (ch = 0; ch < 3; ch++) {
            sum += mse[ch] * w[ch] / 3.0;
            sb += b2[ch] * w[ch] / 3.0;
        }
    }
    if (bias2)
        *bias2 = sb / (double)st->npix;
    return sum / (double)st->npix;
}

static mcrt_status sppm_render(const struct integrator *self, void *state, const struct scene *s,
                               const struct render_settings *rs, struct film *f,
                               struct render_result *out, mc_diag *d)
{
    struct sppm_state st;
    struct pass_ctx c;
    struct render_settings prs = *rs;
    struct progress prog;
    struct tile_result res;
    mcrt_status status = MCRT_OK;
    int limited = rs->time_budget > 0.0 || rs->target_error > 0.0;
    int max_passes = limited ? rs->max_passes * rs->spp : rs->spp;
    double t0 = mc_seconds(), last_pass = 0.0;
    size_t i;
    (void)self;
    (void)state;
    memset(&st, 0, sizeof st);
    out->passes = 0;
    out->samples = out->rays = out->nan_count = 0;
    /* How the estimated relMSE falls with passes: N^-2/3 at α = 2/3 (Knaus and Zwicker 2011),
     * N^-min(α, 2−2α) in general; the theory's rate, not a fit. */
    out->relmse_slope = rs->integrator.alpha < 2.0f / 3.0f ? -rs->integrator.alpha
                                                           : -(2.0 - 2.0 * rs->integrator.alpha);
    st.width = f->width;
    st.height = f->height;
    st.x0 = rs->crop_x0;
    st.y0 = rs->crop_y0;
    st.npix = (size_t)f->width * (size_t)f->height;
    st.photons = rs->integrator.photons > 0 ? rs->integrator.photons
                                            : (long)s->film.width * (long)s->film.height;
    st.radius0 = rs->integrator.radius > 0.0f
                     ? rs->integrator.radius
                     : 5.0 * s->light_scene.radius
                           / (double)(s->film.width > s->film.height ? s->film.width : s->film.height);
    st.nchunks = ((size_t)st.photons + SPPM_CHUNK - 1) / SPPM_CHUNK;
    st.px = mc_calloc(st.npix, sizeof *st.px);
    st.vp = mc_calloc(st.npix, sizeof *st.vp);
    st.vp_p = mc_calloc(st.npix, sizeof *st.vp_p);
    st.vp_r = mc_calloc(st.npix, sizeof *st.vp_r);
    st.chunks = mc_calloc(st.nchunks, sizeof *st.chunks);
    if (!st.px || !st.vp || !st.vp_p || !st.vp_r || !st.chunks) {
        state_free(&st);
        return mc_fail(d, MCRT_ERR_NOMEM, "out of memory for sppm's per-pixel state");
    }
    for (i = 0; i < st.npix; i++)
        st.px[i].r = st.radius0;

    c.s = s;
    c.cfg = &rs->integrator;
    c.rs = rs;
    c.st = &st;
    mc_camera_init(&c.cam, &s->camera, s->film.width, s->film.height);
    c.motion = rs->features & FEATURE_MOTION;
    c.lens = (rs->features & FEATURE_LENS) != 0;
    c.mis = mc_features_need_mis(rs->features);
    for (i = 0; i < SPPM_GROUPS; i++)
        c.sampler_spp[i] = (uint32_t)group_passes(max_passes, (int)i);
    c.seed = rs->seed;
    prog.rs = rs;
    prog.last = 0.0;
    prog.t0 = t0;
    if (rs->progress) {
        prs.progress = report;
        prs.user = &prog;
    }
    while (out->passes < max_passes) {
        double tp = mc_seconds();
        c.pass = out->passes;
        /* One time per pass for the camera rays and the photons (pbrt-v4 #440). */
        c.time = mc_camera_time(&c.cam, (float)(mc_hash3(rs->seed, (uint64_t)c.pass, 0x74696d65ULL)
                                                >> 40) * 0x1p-24f);
        prog.base = (double)out->passes / max_passes;
        prog.span = 0.2 / max_passes;
        status = mc_tiles_run(&prs, st.x0, st.y0, st.width, st.height, camera_tile, &c, &res, d);
        out->rays += res.rays;
        out->nan_count += res.nan_count;
        if (status != MCRT_OK)
            break;
        for (i = 0; i < st.npix; i++) {
            st.vp_p[i] = st.vp[i].p;
            st.vp_r[i] = st.vp[i].valid ? st.px[i].r : 0.0;
        }
        if (mc_point_grid_build(&st.grid, st.vp_p, st.vp_r, st.npix) != 0) {
            status = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for sppm's grid");
            break;
        }
        prog.base += prog.span;
        prog.span = 0.8 / max_passes;
        status = mc_tiles_run(&prs, 0, 0, (int)st.nchunks * MC_TILE, 1, photon_tile, &c, &res, d);
        out->rays += res.rays;
        if (status != MCRT_OK)
            break;
        for (i = 0; i < st.nchunks; i++)
            if (st.chunks[i].failed) {
                status = mc_fail(d, MCRT_ERR_NOMEM, "out of memory for sppm's photon records");
                break;
            }
        if (status != MCRT_OK)
            break;
        update(&st, &rs->integrator, out->passes);
        out->passes++;
        last_pass = mc_seconds() - tp;
        if (rs->time_budget > 0.0 && mc_seconds() - t0 + last_pass > rs->time_budget)
            break;
        if (rs->target_error > 0.0 && out->passes >= 2
            && film_relmse(&st, out->passes, NULL) <= rs->target_error)
            break;
    }
    if (out->passes > 0)
        for (i = 0; i < st.npix; i++) {
            double mse[3];
            vec3 v = pixel_value(&st, i, out->passes, mse, NULL);
            film_put(&f->pixels[i], v, mse);
        }
    if (out->passes >= 2) {
        double total = film_relmse(&st, out->passes, &out->est_relmse_bias2);
        out->est_relmse_variance = total - out->est_relmse_bias2;
    }
    if (status == MCRT_OK && rs->progress)
        rs->progress(rs->user, 1.0);
    out->samples = (uint64_t)out->passes * st.npix;
    out->seconds = mc_seconds() - t0;
    state_free(&st);
    return status;
}

/* Stochastic progressive photon mapping: consistent, biased by the gather radius. */
const struct integrator mc_integrator_sppm = {
    "stochastic progressive photon mapping (consistent, biased)",
    sppm_prepare, sppm_render, NULL, NULL};
