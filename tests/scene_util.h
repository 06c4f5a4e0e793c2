/* scene_util.h: a scene parsed from text and prepared, for the tests of what a prepared scene
 * holds (lights, their selection, emission); header only, like render_util.h. */
#ifndef MCRT_TEST_SCENE_UTIL_H
#define MCRT_TEST_SCENE_UTIL_H

#include <string.h>

#include "scene/scene.h"
#include "t.h"

/* Parse text as the scene `name` (OBJ paths relative to dir; NULL: the current folder) into s and
 * prepare it; 1 on success, else a failed check naming the error and 0 (s freed). */
static inline int t_load_scene(struct scene *s, const char *text, const char *name, const char *dir)
{
    mc_diag d;
    mc_scene_init(s);
    if (mc_scene_parse(s, text, strlen(text), name, dir, &d) != MCRT_OK
        || mc_scene_prepare(s, &d) != MCRT_OK) {
        T_CHECK(0, "scene does not load: %s", d.msg);
        mc_scene_free(s);
        return 0;
    }
    return 1;
}

#endif
