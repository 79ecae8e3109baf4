/* mem: large buffers, as huge-page mappings from MEM_HUGE_MIN bytes on and
 * malloc below (renderer/README.md). Free them with mem_free only. */
#ifndef PM_MEM_H
#define PM_MEM_H

#include <stddef.h>

/* Buffers at least this large (header included) are huge-page mappings. */
#define MEM_HUGE_MIN ((size_t)2 << 20)

/* Returns the bytes a buffer asked for `bytes` can hold at no extra page
 * cost: whole huge pages from MEM_HUGE_MIN / 2 up. Never fails. */
size_t mem_round(size_t bytes);
/* A buffer of `bytes` (0 is fine: a valid, empty buffer), 64-byte aligned,
 * contents undefined. Returns NULL when memory runs out. */
void *mem_alloc(size_t bytes);
/* As mem_alloc, contents zeroed. Returns NULL when memory runs out. */
void *mem_zalloc(size_t bytes);
/* Resizes p (NULL: as mem_alloc) keeping its contents. Returns the new
 * pointer, or NULL when memory runs out (p is then unchanged). */
void *mem_realloc(void *p, size_t bytes);
/* Gives back the whole pages of p's bytes [off, off + len), which then
 * read as zero; p stays valid. Never fails. */
void mem_release(void *p, size_t off, size_t len);
/* Frees a buffer of mem_alloc/mem_zalloc/mem_realloc; NULL is fine. */
void mem_free(void *p);

#endif
