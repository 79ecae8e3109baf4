/* mem: the large buffers (photon lists, the tree build's copy, the tree,
 * the map's records): from MEM_HUGE_MIN bytes on, 2 MiB-aligned mappings
 * advised as huge pages (renderer/README.md), below it malloc. A buffer
 * from here is freed by mem_free only, never by free. */
#ifndef PM_MEM_H
#define PM_MEM_H

#include <stddef.h>

/* Buffers at least this large (header included) are huge-page mappings. */
#define MEM_HUGE_MIN ((size_t)2 << 20)

/* The bytes a buffer asked for `bytes` can hold at no extra cost in pages:
 * from MEM_HUGE_MIN / 2 up, rounded so that its mapping is whole huge
 * pages (a huge page is backed whole once touched, and a partial one at
 * the end would be small pages, a fault each); smaller sizes as they are. */
size_t mem_round(size_t bytes);
/* A buffer of `bytes` (0 is fine: a valid, empty buffer), 64-byte aligned,
 * contents undefined. Returns NULL when memory runs out. */
void *mem_alloc(size_t bytes);
/* As mem_alloc, contents zeroed (free for the mapped ones: fresh pages are
 * zero). Returns NULL when memory runs out. */
void *mem_zalloc(size_t bytes);
/* Grows or shrinks p (NULL: as mem_alloc) to `bytes`, keeping its first
 * bytes; large buffers move by remapping and shrink in place. Returns the
 * new pointer, or NULL when memory runs out (p is then unchanged). */
void *mem_realloc(void *p, size_t bytes);
/* Gives back the whole 4 KiB pages of p's bytes [off, off + len), which
 * then read as zero (nothing for a malloc buffer); the buffer stays valid.
 * Never fails. */
void mem_release(void *p, size_t off, size_t len);
/* Frees a buffer of mem_alloc/mem_zalloc/mem_realloc; NULL is fine. */
void mem_free(void *p);

#endif
