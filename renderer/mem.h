/* mem: large buffers, as mappings of their own from MEM_MAP_MIN bytes on
 * (huge-page mappings from MEM_HUGE_MIN) and malloc below, freed mappings
 * kept for reuse when asked (mem_keep) (renderer/README.md). Free them
 * with mem_free only. */
#ifndef PM_MEM_H
#define PM_MEM_H

#include <stddef.h>

/* Buffers at least this large (header included) are mappings of their
 * own, which mem_keep can keep whole: in malloc's heap a repeat's buffers
 * would land elsewhere than the repeat before's (freed small chunks that
 * malloc caches per thread sit between them), on fresh pages. */
#define MEM_MAP_MIN ((size_t)128 << 10)
/* Buffers at least this large (header included) are huge-page mappings. */
#define MEM_HUGE_MIN ((size_t)2 << 20)
/* The most freed mappings mem_free keeps at once: with each mapping at
 * least MEM_MAP_MIN, enough that mem_keep's bytes, not this count, bound
 * what is kept for any keep up to MEM_CACHE_SLOTS * MEM_MAP_MIN bytes. */
#define MEM_CACHE_SLOTS 8192

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
 * read as zero (nothing for a buffer below MEM_MAP_MIN); p stays valid.
 * Never fails. */
void mem_release(void *p, size_t off, size_t len);
/* Frees a buffer of mem_alloc/mem_zalloc/mem_realloc; NULL is fine. A
 * mapping is kept, whole and with its pages, for the next buffer it can
 * hold while the kept bytes stay within mem_keep's. */
void mem_free(void *p);
/* From now on mem_free keeps up to `bytes` of freed mappings (0, the
 * start: none), so that a repeated computation touches no fresh pages;
 * the memory's high-water mark grows by up to that much. Never fails. */
void mem_keep(size_t bytes);
/* Unmaps the mappings mem_free kept. Returns their bytes. */
size_t mem_trim(void);

#endif
