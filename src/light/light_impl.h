/* light_impl.h: private to src/light: what each kind's file (src/light/NAME.c, one per line of
 * MC_LIGHTS in light.h) defines; light.c dispatches to these with a switch over the kind. The
 * functions are those of light.h for one kind: */
#ifndef MCRT_LIGHT_IMPL_H
#define MCRT_LIGHT_IMPL_H

#include "light/light.h"

#define MC_LIGHT_DECLARE(kind, name)                                                           \
    double mc_##name##_light_power(const struct light_scene *s, const struct light *l);        \
    int mc_##name##_light_bounds(const struct light_scene *s, const struct light *l,           \
                                 struct light_bounds *b);                                      \
    int mc_##name##_light_sample(const struct light_scene *s, const struct light *l, vec3 p,    \
                                 float time, vec2 u, struct light_sample *out);                \
    float mc_##name##_light_pdf(const struct light_scene *s, const struct light *l, vec3 p,     \
                                float time, vec3 wi, float t, const struct surface *sf);       \
    int mc_##name##_light_emission(const struct light_scene *s, const struct light *l,         \
                                   float time, vec2 u_pos, vec2 u_dir,                         \
                                   struct light_emission *out);                                \
    extern const struct light_desc mc_##name##_light;
MC_LIGHTS(MC_LIGHT_DECLARE)
#undef MC_LIGHT_DECLARE

#endif
