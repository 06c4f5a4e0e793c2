/* words.c: the names the code knows, from its own tables, for tests/docs.sh to find in the
 * manuals: each word of the scene language (mc_scene_words) as "block NAME", "key BLOCK NAME" or
 * "value BLOCK KEY NAME", and each name of the library's closed sets (mcrt_names) as
 * "SET NAME", and each statement of the MTL reader's table (MC_MTL_STATEMENTS) as "mtl NAME". One
 * per line. */
#include <stdio.h>

#include "mcrt.h"
#include "scene/mtl.h"
#include "scene/scene.h"

static void print_word(void *user, const char *block, const char *key, const char *value)
{
    (void)user;
    if (value)
        printf("value %s %s %s\n", block, key, value);
    else if (key)
        printf("key %s %s\n", block, key);
    else
        printf("block %s\n", block);
}

int main(void)
{
    static const char *const sets[] = {"integrator", "sampler", "aov", "filter", "shape", "light", "material", "texture"};
    size_t i;
    mc_scene_words(print_word, NULL);
    for (i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        const char *const *n = mcrt_names(sets[i]);
        for (; n && *n; n++)
            printf("%s %s\n", sets[i], *n);
    }
    for (i = 0; i < MTL_STATEMENT_COUNT; i++)
        printf("mtl %s\n", mc_mtl_statement_names[i]);
    return fflush(stdout) == 0 ? 0 : 1;
}
