/* stats_json.h: a render's statistics as the JSON object that `mcrt --stats` and
 * mcrt_render_save_stats write (keys documented in mcrt(1)). */
#ifndef MCRT_STATS_JSON_H
#define MCRT_STATS_JSON_H

#include <stdint.h>
#include <stdio.h>

#include "mcrt.h"

/* Write st, the seed and the two labels (NULL: JSON null) to f. */
void mc_stats_json(FILE *f, const mcrt_stats *st, uint64_t seed, const char *scene,
                   const char *image);

#endif
