/* sized.c: reading and writing the sized structs of mcrt.h (see sized.h). */
#include "api/sized.h"

#include <string.h>

int mc_sized_read(void *dst, size_t dst_size, const void *src, size_t src_size)
{
    const unsigned char *tail = (const unsigned char *)src + dst_size;
    size_t i;
    if (src_size < sizeof(size_t) || src_size > MC_SIZED_MAX)
        return 0;
    for (i = 0; i + dst_size < src_size; i++)
        if (tail[i] != 0)
            return 0;
    memcpy(dst, src, src_size < dst_size ? src_size : dst_size);
    return 1;
}

void mc_sized_write(void *out, size_t out_size, const void *src, size_t src_size)
{
    memcpy(out, src, out_size < src_size ? out_size : src_size);
}
