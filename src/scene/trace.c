/* trace.c: ray queries on a prepared scene over its two BVHs, static primitives and moving ones
 * (scene.h), and the surface at a hit, carried from a moving primitive's time-0 frame to the
 * world at the ray's time (geom/motion.h). */
#include "scene/scene.h"

int mc_scene_intersect(const struct scene *s, const struct ray *r, struct hit *h)
{
    int found = mc_bvh_intersect(&s->bvh, s->prims, r, h);
    if (s->motion_bvh.node_count != 0) {
        /* Only moving primitives nearer than the static hit matter. */
        struct ray near = *r;
        if (found)
            near.tmax = h->t;
        if (mc_bvh_intersect_moving(&s->motion_bvh, s->prims + s->static_count, s->motions, &near,
                                    h)) {
            h->prim += (uint32_t)s->static_count;
            found = 1;
        }
    }
    return found;
}

int mc_scene_occluded(const struct scene *s, const struct ray *r)
{
    return mc_bvh_occluded(&s->bvh, s->prims, r)
        || (s->motion_bvh.node_count != 0
            && mc_bvh_occluded_moving(&s->motion_bvh, s->prims + s->static_count, s->motions, r));
}

vec2 mc_scene_uv(const struct scene *s, const struct ray *r, const struct hit *h)
{
    const struct prim *p = &s->prims[h->prim];
    struct rigid x;
    if (p->motion == 0)
        return mc_prim_uv(p, s->uvs, r, h);
    /* In the primitive's time-0 frame, as mc_scene_surface. */
    mc_motion_at(&s->motions[p->motion - 1], r->time, &x);
    {
        struct ray local = rigid_inv_ray(&x, r);
        return mc_prim_uv(p, s->uvs, &local, h);
    }
}

void mc_scene_bsdf(const struct scene *s, const struct ray *r, const struct hit *h, struct bsdf *b)
{
    const struct material *m = &s->materials[s->prims[h->prim].material];
    vec3 color = m->color;
    float alpha = m->alpha;
    vec2 uv;
    if (!m->texture && !m->roughness_texture) {
        mc_bsdf_init(b, m);
        return;
    }
    uv = mc_scene_uv(s, r, h);
    if (m->texture)
        color = v3_mul(color, mc_texture_eval(&s->textures[m->texture - 1], uv));
    if (m->roughness_texture) {
        vec3 t = mc_texture_eval(&s->textures[m->roughness_texture - 1], uv);
        float rough = (t.x + t.y + t.z) * (1.0f / 3.0f);
        alpha *= rough * rough;
    }
    mc_bsdf_init_at(b, m, color, alpha);
}

void mc_scene_surface(const struct scene *s, const struct ray *r, const struct hit *h,
                      struct surface *sf)
{
    const struct prim *p = &s->prims[h->prim];
    struct rigid x;
    struct ray local;
    if (p->motion == 0) {
        mc_prim_surface(p, s->normals, r, h, sf);
        return;
    }
    /* The same map as the intersection test used (bvh.c), so the hit parameters belong to this
     * ray. Rigid maps preserve dot products, so sf->front found in the time-0 frame holds. */
    mc_motion_at(&s->motions[p->motion - 1], r->time, &x);
    local = rigid_inv_ray(&x, r);
    mc_prim_surface(p, s->normals, &local, h, sf);
    sf->p = rigid_point(&x, sf->p);
    sf->ng = rigid_vector(&x, sf->ng);
    sf->ns = rigid_vector(&x, sf->ns);
}
