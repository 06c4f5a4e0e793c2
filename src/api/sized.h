/* sized.h: structs of mcrt.h that carry their size, so that a program built against an older (or
 * newer) mcrt.h keeps working with this library.
 *
 * Structs the caller fills (mcrt_options, mcrt_diff_options) begin with `size`, set by their
 * *_init to the sizeof the caller was compiled with. The library reads the fields that size
 * covers; the fields past it keep their defaults, as OpenEXR reads an exr_context_initializer_t
 * by its size. A size larger than the library's struct is accepted when every byte past the
 * library's end is zero (the newer fields are at their defaults, which are all zero), and refused
 * otherwise: a field this library does not know would be silently ignored, and a render must not
 * differ from what was asked without saying so. A size above 4096 bytes is refused unread, as
 * no version of these structs comes near it and the size of options never initialised is
 * garbage. Those are the rules of Linux's copy_struct_from_user and clone3 (which refuses sizes
 * above a page).
 *
 * Structs the library fills (mcrt_stats, mcrt_diff_result) come with the caller's sizeof as an
 * argument, and only that many bytes are written. */
#ifndef MCRT_SIZED_H
#define MCRT_SIZED_H

#include <stddef.h>

/* Copy the caller's struct (src, src_size bytes) over the library's (dst, dst_size bytes, holding
 * the defaults). Returns 0, copying nothing, when src_size does not even cover the size field, is
 * above MC_SIZED_MAX, or is larger than dst_size with a nonzero byte past it. */
#define MC_SIZED_MAX 4096
int mc_sized_read(void *dst, size_t dst_size, const void *src, size_t src_size);
/* Write the first out_size bytes (at most src_size) of the library's struct src to out. */
void mc_sized_write(void *out, size_t out_size, const void *src, size_t src_size);

#endif
