/* stats_json.c: a render's statistics as JSON (see stats_json.h). */
#include "api/stats_json.h"

#include <inttypes.h>
#include <math.h>

/* A JSON string: quotes and backslashes escaped, control characters as \u00XX; NULL is null. */
static void json_string(FILE *f, const char *key, const char *s)
{
    fprintf(f, "  \"%s\": ", key);
    if (!s) {
        fputs("null,\n", f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputs("\",\n", f);
}

/* "  "KEY": VALUE" then end; null for NaN and infinities, which JSON cannot hold. */
static void json_number(FILE *f, const char *key, double value, const char *end)
{
    if (isfinite(value))
        fprintf(f, "  \"%s\": %.6g%s", key, value, end);
    else
        fprintf(f, "  \"%s\": null%s", key, end);
}

void mc_stats_json(FILE *f, const mcrt_stats *st, uint64_t seed, const char *scene,
                   const char *image)
{
    int i;
    fputs("{\n", f);
    json_string(f, "scene", scene);
    json_string(f, "image", image);
    fprintf(f,
            "  \"width\": %d,\n  \"height\": %d,\n  \"spp\": %d,\n  \"threads\": %d,\n"
            "  \"seed\": %" PRIu64 ",\n  \"seconds\": %.6f,\n  \"rays\": %" PRIu64 ",\n"
            "  \"mrays_per_second\": %.6g,\n  \"nan_count\": %" PRIu64 ",\n",
            st->width, st->height, st->spp, st->threads, seed, st->seconds, st->rays,
            st->seconds > 0.0 ? (double)st->rays / st->seconds * 1e-6 : 0.0, st->nan_count);
    /* spp is the mean per pixel; an adaptive render spreads it from spp_min to spp_max. */
    fprintf(f, "  \"passes\": %d,\n  \"adaptive\": %s,\n  \"spp_min\": %d,\n  \"spp_max\": %d,\n",
            st->passes, st->adaptive ? "true" : "false", st->spp_min, st->spp_max);
    /* An error that cannot be estimated (1 spp) is null. */
    json_number(f, "est_relmse", st->est_relmse, ",\n");
    /* The raw image's, beside a denoised one's (the same without denoising). */
    json_number(f, "est_relmse_raw", st->est_relmse_raw, ",\n");
    json_number(f, "est_relmse_sd", st->est_relmse_sd, ",\n");
    json_number(f, "denoise_seconds", st->denoise_seconds, ",\n");
    json_number(f, "efficiency", st->efficiency, ",\n");
    /* A biased integrator's est_relmse in its parts; null for the others. */
    json_number(f, "est_relmse_bias2", st->est_relmse_bias2, ",\n");
    json_number(f, "est_relmse_variance", st->est_relmse_variance, ",\n");
    json_number(f, "relmse_slope", st->relmse_slope, ",\n");
    /* The seconds to a relMSE of 1e-2, 1e-3, 1e-4 (mcrt_seconds_to_relmse). */
    fputs("  \"seconds_to_relmse\": {", f);
    for (i = 0; i < 3; i++) {
        fprintf(f, "%s\"1e-%d\": ", i ? ", " : "", i + 2);
        if (isfinite(st->seconds_to_relmse[i]))
            fprintf(f, "%.6g", st->seconds_to_relmse[i]);
        else
            fputs("null", f);
    }
    fputs("}\n}\n", f);
}
