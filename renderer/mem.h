/* mem: allocation of the large buffers (photon lists, the kd-tree build's
 * working copy, the tree's coordinates, the map's records). Buffers of at
 * least MEM_HUGE_MIN bytes are their own anonymous mappings, aligned to
 * 2 MiB and advised as transparent huge pages: first touching fresh memory
 * in 4 KiB pages costs a page fault per 4 KiB, which dominates the photon
 * pass and the build at tens of millions of photons. The advice may be
 * ignored (the kernel's THP setting), in which case the buffer works the
 * same in small pages. Smaller buffers come from malloc.
 *
 * Every buffer carries a small header, so mem_free and mem_realloc need no
 * size, and a buffer from these functions must only be freed by mem_free
 * (never by free), and vice versa. */
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
/* Grows or shrinks p (NULL: as mem_alloc) to `bytes`, keeping the first
 * min(old, bytes) bytes; large buffers move by remapping, not copying,
 * where the system can, and shrink in place (also below MEM_HUGE_MIN),
 * their tail's pages going back to the system. Returns the new pointer, or NULL when memory runs
 * out (p is then unchanged and still valid). */
void *mem_realloc(void *p, size_t bytes);
/* Gives back to the system the whole 4 KiB pages of p's bytes
 * [off, off + len) (off + len <= the buffer's size), which read as zero
 * afterwards; the buffer stays valid. Lets a pass that consumes a large
 * buffer in order hand its memory back as it goes. Does nothing for a
 * buffer from malloc (below MEM_HUGE_MIN). Never fails (the advice may be
 * ignored, which costs memory, never correctness of what is still to be
 * read). */
void mem_release(void *p, size_t off, size_t len);
/* Frees a buffer of mem_alloc/mem_zalloc/mem_realloc; NULL is fine. */
void mem_free(void *p);

#endif
