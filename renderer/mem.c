/* mem: the large buffers' allocator (mem.h): huge-page-advised anonymous
 * mappings for large buffers, malloc for small ones, a header in front of
 * each that says which and how large. */
#define _GNU_SOURCE /* mremap, MAP_ANONYMOUS, MADV_HUGEPAGE */
#include "mem.h"

#include <assert.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define MEM_ALIGN ((size_t)2 << 20) /* a huge page */
#define MEM_HEAD 64u                /* the header's room: keeps the buffer 64-byte aligned */
#define MEM_MAGIC 0x6d656d62u

typedef struct {
    size_t map;   /* bytes of the mapping (header included), 0: from malloc */
    size_t bytes; /* bytes asked for */
    uint32_t magic;
} mem_head;

static mem_head *head_of(void *p)
{
    mem_head *h = (mem_head *)(void *)((char *)p - MEM_HEAD);
    assert(h->magic == MEM_MAGIC);
    return h;
}

static size_t page_round(size_t n)
{
    return (n + 4095u) & ~(size_t)4095u;
}

/* Advises [p, p + len) as huge pages (p 2 MiB aligned); advice only. */
static void advise_huge(void *p, size_t len)
{
#ifdef MADV_HUGEPAGE
    (void)madvise(p, len, MADV_HUGEPAGE);
#else
    (void)p;
    (void)len;
#endif
}

/* A mapping of `map` bytes (page-rounded) whose start is 2 MiB aligned:
 * maps 2 MiB more and trims both ends. Returns NULL when it fails. */
static void *map_aligned(size_t map)
{
    if (map > SIZE_MAX - MEM_ALIGN)
        return NULL;
    size_t len = map + MEM_ALIGN;
    char *raw = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED)
        return NULL;
    uintptr_t a = ((uintptr_t)raw + MEM_ALIGN - 1) & ~(uintptr_t)(MEM_ALIGN - 1);
    char *p = (char *)a;
    size_t before = (size_t)(p - raw), after = len - before - map;
    if (before)
        munmap(raw, before);
    if (after)
        munmap(p + map, after);
    advise_huge(p, map);
    return p;
}

static void *alloc_impl(size_t bytes, int zero)
{
    if (bytes > SIZE_MAX - MEM_ALIGN - MEM_HEAD)
        return NULL;
    size_t total = bytes + MEM_HEAD;
    mem_head *h;
    if (total < MEM_HUGE_MIN) {
        void *m = NULL;
        if (posix_memalign(&m, MEM_HEAD, total) != 0)
            return NULL;
        if (zero)
            memset(m, 0, total);
        h = m;
        h->map = 0;
    } else {
        size_t map = page_round(total);
        h = map_aligned(map);
        if (!h)
            return NULL;
        h->map = map;
    }
    h->bytes = bytes;
    h->magic = MEM_MAGIC;
    return (char *)h + MEM_HEAD;
}

size_t mem_round(size_t bytes)
{
    if (bytes < MEM_HUGE_MIN / 2 || bytes > SIZE_MAX - 2 * MEM_ALIGN)
        return bytes;
    size_t map = (bytes + MEM_HEAD + MEM_ALIGN - 1) & ~(MEM_ALIGN - 1);
    return map - MEM_HEAD;
}

void *mem_alloc(size_t bytes)
{
    return alloc_impl(bytes, 0);
}

void *mem_zalloc(size_t bytes)
{
    return alloc_impl(bytes, 1);
}

void mem_free(void *p)
{
    if (!p)
        return;
    mem_head *h = head_of(p);
    h->magic = 0;
    if (h->map)
        munmap(h, h->map);
    else
        free(h);
}

void mem_release(void *p, size_t off, size_t len)
{
    if (!p || len == 0)
        return;
    mem_head *h = head_of(p);
    assert(off <= h->bytes && len <= h->bytes - off);
    if (!h->map)
        return;
    uintptr_t a = (uintptr_t)p + off, b = a + len;
    a = (a + 4095u) & ~(uintptr_t)4095u;
    b &= ~(uintptr_t)4095u;
    if (b > a)
        (void)madvise((void *)a, (size_t)(b - a), MADV_DONTNEED);
}

void *mem_realloc(void *p, size_t bytes)
{
    if (!p)
        return mem_alloc(bytes);
    mem_head *h = head_of(p);
    if (bytes > SIZE_MAX - MEM_ALIGN - MEM_HEAD)
        return NULL;
    size_t total = bytes + MEM_HEAD;
    if (h->map && (total >= MEM_HUGE_MIN || page_round(total) <= h->map)) {
        /* a mapping stays one, also when it shrinks below MEM_HUGE_MIN:
         * moving it to malloc would copy it into fresh small pages */
        size_t map = page_round(total);
        if (map == h->map) {
            h->bytes = bytes;
            return p;
        }
#ifdef MREMAP_MAYMOVE
        if (map < h->map) {
            /* shrinking in place: the tail's pages go back */
            munmap((char *)h + map, h->map - map);
            h->map = map;
            h->bytes = bytes;
            return p;
        }
        void *n = mremap(h, h->map, map, MREMAP_MAYMOVE);
        if (n != MAP_FAILED) {
            h = n;
            h->map = map;
            h->bytes = bytes;
            advise_huge(h, map); /* where the move kept 2 MiB regions whole */
            return (char *)h + MEM_HEAD;
        }
        /* else fall through to a fresh buffer and a copy */
#endif
    }
    void *n = mem_alloc(bytes);
    if (!n)
        return NULL;
    memcpy(n, p, h->bytes < bytes ? h->bytes : bytes);
    mem_free(p);
    return n;
}
