/* test_state.c: render states (src/render/state.c) and the exact merge they rely on (film.c):
 * the words hold every bit of the sums (NaN payloads, -0, subnormals, counts above 2^32), the
 * text reads back what was written and refuses what was not, renders of other options are told
 * apart, and merging two films of samples gives the mean and M2 of all the samples (Chan, Golub
 * and LeVeque 1979) to rounding, and a tile at its place bit for bit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/hash.h"
#include "core/rng.h"
#include "render/state.h"
#include "t.h"

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void test_words(void)
{
    struct film f, g;
    uint32_t words[2 * MC_STATE_WORDS];
    uint64_t nan_bits = 0x7ff8dead0000beefULL;
    double odd[6];
    int h, c, same = 1;
    memcpy(&odd[0], &nan_bits, sizeof odd[0]);
    odd[1] = -0.0;
    odd[2] = 4.9e-324; /* the least subnormal */
    odd[3] = 1.0 / 3.0;
    odd[4] = -1e308;
    odd[5] = 0.1;
    T_CHECK(mc_film_init(&f, 2, 1) == 0 && mc_film_init(&g, 2, 1) == 0, "init");
    for (h = 0; h < 2; h++)
        for (c = 0; c < 3; c++) {
            f.pixels[1].half[h].mean[c] = odd[(c + h) % 6];
            f.pixels[1].half[h].m2[c] = odd[(c + h + 3) % 6];
        }
    f.pixels[1].half[0].count = (1ULL << 40) + 7;
    f.pixels[1].half[1].count = 3;
    mc_state_pack(&f, words);
    mc_state_unpack(&g, words);
    for (h = 0; h < 2; h++) {
        for (c = 0; c < 3; c++)
            same &= same_bits(f.pixels[1].half[h].mean[c], g.pixels[1].half[h].mean[c]) &&
                    same_bits(f.pixels[1].half[h].m2[c], g.pixels[1].half[h].m2[c]);
        same &= f.pixels[1].half[h].count == g.pixels[1].half[h].count;
    }
    T_CHECK(same, "pack then unpack keeps every bit (NaN payload, -0, subnormal, 2^40 count)");
    T_CHECK(g.pixels[0].half[0].count == 0 && g.pixels[0].half[1].mean[2] == 0.0, "empty pixel");
    mc_film_free(&f);
    mc_film_free(&g);
}

static void test_text(void)
{
    struct render_state a, b;
    const char *why = NULL;
    char text[1024];
    memset(&a, 0, sizeof a);
    a.scene = 0xfedcba9876543210ULL;
    a.width = 640;
    a.height = 480;
    a.crop[2] = 320;
    a.crop[1] = 10;
    a.crop[3] = 480;
    a.spp = 4;
    strcpy(a.integrator, "path");
    strcpy(a.sampler, "sobol");
    a.pooled = 0;
    a.seed = UINT64_MAX;
    a.first_pass = 8;
    a.passes = 16;
    T_CHECK(mc_state_format(&a, text, sizeof text) < (int)sizeof text, "fits");
    T_CHECK(mc_state_parse(text, &b, &why) == 0 && memcmp(&a, &b, sizeof a) == 0,
            "format then parse: the same state (%s)", why ? why : "");
    T_CHECK(mc_state_same_render(&a, &b, &why), "a state is a render of its own options");
    b.spp = 8;
    T_CHECK(!mc_state_same_render(&a, &b, &why) && strcmp(why, "another --spp") == 0,
            "other spp: %s", why);
    b = a;
    b.scene ^= 1;
    T_CHECK(!mc_state_same_render(&a, &b, &why) && strstr(why, "another scene"), "other scene");
    b = a;
    b.seed = 1;
    b.crop[0] = 5;
    T_CHECK(mc_state_same_render(&a, &b, &why), "seed and crop do not make another render");
    T_CHECK(mc_state_parse("mcrt-state 2\n", &b, &why) != 0, "another version refused");
    text[strlen(text) / 2] = '\0';
    T_CHECK(mc_state_parse(text, &b, &why) != 0, "cut text refused: %s", why);
    a.crop[2] = 700;
    mc_state_format(&a, text, sizeof text);
    T_CHECK(mc_state_parse(text, &b, &why) != 0, "crop outside the image refused: %s", why);
}

/* Two films of Gaussian samples, merged, against one of all the samples. */
static void test_merge(void)
{
    struct film a, b, all, big;
    pcg32 r;
    int i, c;
    double worst = 0.0;
    pcg32_seed(&r, 7, 1);
    T_CHECK(mc_film_init(&a, 1, 1) == 0 && mc_film_init(&b, 1, 1) == 0 &&
                mc_film_init(&all, 1, 1) == 0 && mc_film_init(&big, 3, 2) == 0,
            "init");
    for (i = 0; i < 1000; i++) {
        vec3 v = v3((float)(pcg32_double(&r) * 10.0), (float)pcg32_double(&r), 1e3f);
        mc_film_add(&(i < 300 ? &a : &b)->pixels[0].half[i & 1], v);
        mc_film_add(&all.pixels[0].half[i & 1], v);
    }
    mc_film_merge(&a, &b);
    for (c = 0; c < 3; c++) {
        double dm = fabs(a.pixels[0].half[0].mean[c] - all.pixels[0].half[0].mean[c]);
        double d2 = fabs(a.pixels[0].half[1].m2[c] - all.pixels[0].half[1].m2[c]) /
                    (all.pixels[0].half[1].m2[c] + 1e-300);
        worst = fmax(worst, fmax(dm / 10.0, d2));
    }
    /* Welford and Chan each round at about 1e-16 per operation; 1e-12 allows 1000 of them. */
    T_CHECK(worst < 1e-12 && a.pixels[0].half[0].count == 500,
            "merged mean and M2 as of all samples: worst relative difference %.2g", worst);
    mc_film_merge_at(&big, 2, 1, &all);
    T_CHECK(memcmp(&big.pixels[5], &all.pixels[0], sizeof all.pixels[0]) == 0 &&
                big.pixels[4].half[0].count == 0,
            "a tile merged into an empty film lands at its place bit for bit");
    mc_film_free(&a);
    mc_film_free(&b);
    mc_film_free(&all);
    mc_film_free(&big);
}

static void test_hash(void)
{
    /* FNV-1a 64 of "a" is 0xaf63dc4c8601ec8c (Fowler, Noll and Vo's test vectors). */
    T_CHECK(mc_hash(MC_HASH_INIT, "a", 1) == 0xaf63dc4c8601ec8cULL, "FNV-1a test vector");
    T_CHECK(mc_hash(MC_HASH_INIT, "ab", 2) != mc_hash(MC_HASH_INIT, "ba", 2), "order matters");
    T_CHECK(mc_hash(mc_hash(MC_HASH_INIT, "a", 1), "b", 1) == mc_hash(MC_HASH_INIT, "ab", 2),
            "folded piece by piece: the hash of the pieces joined");
}

int main(void)
{
    test_words();
    test_text();
    test_merge();
    test_hash();
    return t_done();
}
