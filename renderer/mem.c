/* mem: the large buffers' allocator (mem.h): anonymous mappings for large
 * buffers (huge-page-advised from MEM_HUGE_MIN), malloc for small ones, a header in front of
 * each that says which and how large, and, when asked (mem_keep), the
 * freed mappings kept for the next buffer (the renderer's one piece of
 * process-wide state: an allocator's free list, like malloc's own, behind
 * a mutex). */
#define _GNU_SOURCE /* mremap, MAP_ANONYMOUS, MADV_HUGEPAGE */
#include "mem.h"

#include <assert.h>
#include <pthread.h>
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

/* The freed mappings, each whole (its header's map bytes), for mem_alloc
 * to reuse until mem_trim: a page fault on fresh memory costs far more than
 * the work that fills it on some machines (renderer/README.md), and a
 * repeat that reused nothing would time the kernel, not the code. */
static struct {
    pthread_mutex_t lock;
    size_t keep;  /* the most bytes kept at once (mem_keep; 0: none) */
    size_t bytes; /* bytes kept */
    size_t n;
    mem_head *slot[MEM_CACHE_SLOTS];
} cache = {PTHREAD_MUTEX_INITIALIZER, 0, 0, 0, {NULL}};

/* Takes the smallest cached mapping of at least `map` bytes out of the
 * cache. Returns it, or NULL when none is large enough. */
static mem_head *cache_take(size_t map)
{
    mem_head *h = NULL;
    pthread_mutex_lock(&cache.lock);
    size_t best = cache.n;
    for (size_t i = 0; i < cache.n; i++)
        if (cache.slot[i]->map >= map && (best == cache.n || cache.slot[i]->map < cache.slot[best]->map))
            best = i;
    if (best < cache.n) {
        h = cache.slot[best];
        cache.slot[best] = cache.slot[--cache.n];
        cache.bytes -= h->map;
    }
    pthread_mutex_unlock(&cache.lock);
    return h;
}

/* Keeps the mapping h for reuse. Returns 0, or -1 when the cache is full
 * or h would take it past mem_keep's bytes (h is then the caller's to
 * unmap). */
static int cache_put(mem_head *h)
{
    int rc = -1;
    pthread_mutex_lock(&cache.lock);
    if (cache.n < MEM_CACHE_SLOTS && h->map <= cache.keep && cache.bytes <= cache.keep - h->map) {
        cache.slot[cache.n++] = h;
        cache.bytes += h->map;
        rc = 0;
    }
    pthread_mutex_unlock(&cache.lock);
    return rc;
}

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

/* Hands back the whole pages of the mapping h's bytes [a, b) (offsets
 * from h), unless mem_keep keeps memory: a repeat would then fault them
 * in again, small pages each a fault of its own. */
static void give_back(mem_head *h, size_t a, size_t b)
{
    pthread_mutex_lock(&cache.lock);
    int keeping = cache.keep > 0;
    pthread_mutex_unlock(&cache.lock);
    a = page_round(a);
    b &= ~(size_t)4095u;
    if (!keeping && b > a)
        (void)madvise((char *)h + a, b - a, MADV_DONTNEED);
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

/* A mapping of `map` bytes (page-rounded): below MEM_HUGE_MIN a plain
 * one; from there one whose start is 2 MiB aligned, advised as huge pages
 * (maps 2 MiB more and trims both ends). Returns NULL when it fails. */
static void *map_aligned(size_t map)
{
    if (map < MEM_HUGE_MIN) { /* no huge page: 4 KiB pages, as mmap aligns */
        void *p = mmap(NULL, map, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        return p == MAP_FAILED ? NULL : p;
    }
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
    if (total < MEM_MAP_MIN) {
        void *m = NULL;
        if (posix_memalign(&m, MEM_HEAD, total) != 0)
            return NULL;
        if (zero)
            memset(m, 0, total);
        h = m;
        h->map = 0;
    } else {
        size_t map = page_round(total);
        h = cache_take(map);
        if (h) {
            map = h->map; /* the whole reused mapping stays this buffer's */
            if (zero)
                memset((char *)h + MEM_HEAD, 0, bytes);
        } else if (!(h = map_aligned(map)))
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
    if (!h->map)
        free(h);
    else if (cache_put(h) != 0)
        munmap(h, h->map);
}

void mem_keep(size_t bytes)
{
    pthread_mutex_lock(&cache.lock);
    cache.keep = bytes;
    pthread_mutex_unlock(&cache.lock);
}

size_t mem_trim(void)
{
    pthread_mutex_lock(&cache.lock);
    size_t bytes = cache.bytes;
    while (cache.n > 0) {
        mem_head *h = cache.slot[--cache.n];
        munmap(h, h->map);
    }
    cache.bytes = 0;
    pthread_mutex_unlock(&cache.lock);
    return bytes;
}

void mem_release(void *p, size_t off, size_t len)
{
    if (!p || len == 0)
        return;
    mem_head *h = head_of(p);
    assert(off <= h->bytes && len <= h->bytes - off);
    if (h->map)
        give_back(h, MEM_HEAD + off, MEM_HEAD + off + len);
}

void *mem_realloc(void *p, size_t bytes)
{
    if (!p)
        return mem_alloc(bytes);
    mem_head *h = head_of(p);
    if (bytes > SIZE_MAX - MEM_ALIGN - MEM_HEAD)
        return NULL;
    size_t total = bytes + MEM_HEAD;
    if (h->map && (total >= MEM_MAP_MIN || page_round(total) <= h->map)) {
        /* a mapping stays one, also when it shrinks below MEM_MAP_MIN:
         * moving it to malloc would copy it into fresh small pages */
        size_t map = page_round(total);
        if (map <= h->map) {
            /* in place: a shrink hands back the pages past the new end
             * (give_back), and the mapping keeps its size for reuse */
            if (bytes < h->bytes)
                give_back(h, total, h->map);
            h->bytes = bytes;
            return p;
        }
#ifdef MREMAP_MAYMOVE
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
