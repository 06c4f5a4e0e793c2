/* light.c: the light functions of light.h over the kinds of MC_LIGHTS: a switch over the kind
 * that calls the kind's own function (src/light/NAME.c), and the table of descriptors. */
#include "light/light_impl.h"

#define X(kind, name) [kind] = &mc_##name##_light,
const struct light_desc *const mc_light_kinds[LIGHT_KIND_COUNT] = {MC_LIGHTS(X)};
#undef X
const char *const mc_light_names[LIGHT_KIND_COUNT + 1] = {MC_LIGHTS(MC_NAMES_IDENT)
                                                          [LIGHT_KIND_COUNT] = NULL};

double mc_light_power(const struct light_scene *s, const struct light *l)
{
    switch (l->kind) {
#define X(kind, name) case kind: return mc_##name##_light_power(s, l);
        MC_LIGHTS(X)
#undef X
    }
    return 0.0;
}

int mc_light_bounds(const struct light_scene *s, const struct light *l, struct light_bounds *b)
{
    switch (l->kind) {
#define X(kind, name) case kind: return mc_##name##_light_bounds(s, l, b);
        MC_LIGHTS(X)
#undef X
    }
    return 0;
}

int mc_light_sample(const struct light_scene *s, const struct light *l, vec3 p, float time,
                    vec2 u, struct light_sample *out)
{
    switch (l->kind) {
#define X(kind, name) case kind: return mc_##name##_light_sample(s, l, p, time, u, out);
        MC_LIGHTS(X)
#undef X
    }
    return 0;
}

float mc_light_pdf(const struct light_scene *s, const struct light *l, vec3 p, float time,
                   vec3 wi, float t, const struct surface *sf)
{
    switch (l->kind) {
#define X(kind, name) case kind: return mc_##name##_light_pdf(s, l, p, time, wi, t, sf);
        MC_LIGHTS(X)
#undef X
    }
    return 0.0f;
}

int mc_light_sample_emission(const struct light_scene *s, const struct light *l, float time,
                             vec2 u_pos, vec2 u_dir, struct light_emission *out)
{
    switch (l->kind) {
#define X(kind, name) case kind: return mc_##name##_light_emission(s, l, time, u_pos, u_dir, out);
        MC_LIGHTS(X)
#undef X
    }
    return 0;
}
