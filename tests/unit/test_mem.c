/* test_mem: the large buffers' allocator (mem.c): rounding, alignment,
 * zeroing, growth and shrinking across the mapping threshold with the
 * contents kept, pages handed back reading as zero, and kept buffers that
 * fault no fresh page. */
#include <stdint.h>
#include <string.h>
#include <sys/resource.h>

#include "check.h"
#include "mem.h"
#include "tests.h"

/* mem_round: sizes below MEM_HUGE_MIN / 2 as they are; from there up, at
 * least the size asked and a mapping of whole huge pages (the header is 64
 * bytes), less than one huge page more; rounding twice changes nothing. */
void test_mem_round(void)
{
    CHECK(mem_round(0) == 0);
    CHECK(mem_round(100) == 100);
    CHECK(mem_round(MEM_HUGE_MIN / 2 - 1) == MEM_HUGE_MIN / 2 - 1);
    CHECK(mem_round(MEM_HUGE_MIN / 2) == MEM_HUGE_MIN - 64);
    size_t sizes[] = {MEM_HUGE_MIN - 64, MEM_HUGE_MIN, MEM_HUGE_MIN + 1, 3 * MEM_HUGE_MIN + 12345, (size_t)100 << 20};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        size_t r = mem_round(sizes[i]);
        CHECK_MSG(r >= sizes[i], "%zu -> %zu", sizes[i], r);
        CHECK_MSG((r + 64) % MEM_HUGE_MIN == 0, "%zu -> %zu", sizes[i], r);
        CHECK_MSG(r - sizes[i] < MEM_HUGE_MIN, "%zu -> %zu", sizes[i], r);
        CHECK(mem_round(r) == r);
    }
    /* negative control: a size that is not whole huge pages fails the check */
    CHECK(!((MEM_HUGE_MIN + 1 + 64) % MEM_HUGE_MIN == 0));
}

/* Small and large buffers are 64-byte aligned (a large one's mapping, its
 * header in front, on a huge-page boundary); mem_zalloc's are zero; a
 * buffer grown from malloc's range into a mapping, grown again and shrunk
 * below the threshold keeps its first bytes; mem_release zeroes the whole
 * pages of its range and nothing outside them, and nothing while mem_keep
 * keeps memory. */
void test_mem_buffers(void)
{
    size_t small = 1000, large = 3 * MEM_HUGE_MIN + 100;
    unsigned char *a = mem_alloc(small), *b = mem_zalloc(large), *z = mem_alloc(0);
    CHECK(a && b && z);
    if (!a || !b || !z)
        return;
    CHECK((uintptr_t)a % 64 == 0 && (uintptr_t)b % 64 == 0 && (uintptr_t)z % 64 == 0);
    CHECK(((uintptr_t)b - 64) % MEM_HUGE_MIN == 0);
    size_t nonzero = 0;
    for (size_t i = 0; i < large; i++)
        nonzero += b[i] != 0;
    CHECK(nonzero == 0);

    for (size_t i = 0; i < small; i++)
        a[i] = (unsigned char)(i * 7 + 1);
    a = mem_realloc(a, large); /* malloc -> mapping */
    CHECK(a != NULL);
    if (!a)
        return;
    size_t bad = 0;
    for (size_t i = 0; i < small; i++)
        bad += a[i] != (unsigned char)(i * 7 + 1);
    CHECK(bad == 0);
    for (size_t i = 0; i < large; i++)
        a[i] = (unsigned char)(i * 13 + 5);
    a = mem_realloc(a, 2 * large); /* mapping grows: remapped */
    CHECK(a != NULL);
    if (!a)
        return;
    bad = 0;
    for (size_t i = 0; i < large; i++)
        bad += a[i] != (unsigned char)(i * 13 + 5);
    CHECK(bad == 0);
    a = mem_realloc(a, small); /* shrinks in place, below the threshold */
    CHECK(a != NULL);
    if (!a)
        return;
    bad = 0;
    for (size_t i = 0; i < small; i++)
        bad += a[i] != (unsigned char)(i * 13 + 5);
    CHECK(bad == 0);

    /* release the pages of [5000, 5000 + 3 * 4096): the whole pages inside
     * read zero, the bytes around them keep their values */
    memset(b, 0xab, large);
    size_t off = 5000, len = 3 * 4096;
    mem_release(b, off, len);
    uintptr_t lo = ((uintptr_t)b + off + 4095) & ~(uintptr_t)4095, hi = ((uintptr_t)b + off + len) & ~(uintptr_t)4095;
    size_t zeroed = 0, kept = 0;
    for (size_t i = 0; i < large; i++) {
        uintptr_t p = (uintptr_t)b + i;
        if (p >= lo && p < hi)
            zeroed += b[i] == 0;
        else
            kept += b[i] == 0xab;
    }
    CHECK(hi > lo);
    CHECK_MSG(zeroed == (size_t)(hi - lo), "%zu of %zu released bytes read zero", zeroed, (size_t)(hi - lo));
    CHECK(kept == large - (size_t)(hi - lo));
    /* while mem_keep keeps memory, nothing is handed back */
    memset(b, 0xab, large);
    mem_keep(MEM_HUGE_MIN);
    mem_release(b, off, len);
    mem_keep(0);
    kept = 0;
    for (size_t i = 0; i < large; i++)
        kept += b[i] == 0xab;
    CHECK(kept == large);
    mem_free(a);
    mem_free(b);
    mem_free(z);
    mem_free(NULL);
}

/* Nothing is kept until mem_keep asks; then a freed mapping serves the
 * next buffer it can hold (the smallest that fits), zeroed for mem_zalloc,
 * and grows in place within its size; mem_trim unmaps what is kept and
 * returns its bytes; malloc's buffers are never kept, nor a mapping past
 * mem_keep's bytes. */
void test_mem_reuse(void)
{
    CHECK(mem_trim() == 0); /* nothing is kept unless asked */
    size_t large = 3 * MEM_HUGE_MIN + 100, larger = 5 * MEM_HUGE_MIN;
    unsigned char *a = mem_alloc(large), *c = mem_alloc(larger);
    CHECK(a && c);
    if (!a || !c)
        return;
    memset(a, 0xcd, large);
    memset(c, 0xcd, larger);
    unsigned char *was_a = a, *was_c = c;
    mem_keep((size_t)64 << 20);
    mem_free(c);
    mem_free(a);
    unsigned char *b = mem_zalloc(large - 1000);
    CHECK(b == was_a); /* the smaller of the two that fit */
    if (!b)
        return;
    size_t nonzero = 0;
    for (size_t i = 0; i < large - 1000; i++)
        nonzero += b[i] != 0;
    CHECK_MSG(nonzero == 0, "%zu bytes of a reused mapping not zeroed", nonzero);
    b = mem_realloc(b, large); /* within the mapping: in place */
    CHECK(b == was_a);
    unsigned char *d = mem_alloc(large + 1); /* only the larger one fits */
    CHECK(d == was_c);
    mem_free(d);
    mem_free(b);
    size_t kept = mem_trim();
    CHECK_MSG(kept >= large + larger + 2 * 64, "mem_trim returned %zu bytes", kept);
    CHECK(mem_trim() == 0);
    mem_free(mem_alloc(1000)); /* malloc's */
    CHECK(mem_trim() == 0);
    /* the addresses alone could match without a cache (the kernel often
     * maps a freed range again): what mem_trim finds is the proof */
    unsigned char *e = mem_alloc(large);
    CHECK(e != NULL);
    mem_free(e);
    CHECK(mem_trim() > 0);
    /* past mem_keep's bytes a freed mapping is unmapped */
    mem_keep(MEM_HUGE_MIN);
    mem_free(mem_alloc(large));
    CHECK(mem_trim() == 0);
    mem_keep(0);
}

/* The cache's count does not bind before mem_keep's bytes: more freed
 * mappings than a photon pass's chunks leave (two per chunk, 64 chunks and
 * more) are all kept, and each serves a later buffer with its pages (a
 * marker written before the free survives: a fresh mapping reads zero). */
void test_mem_reuse_many(void)
{
    enum { N = 300 };
    CHECK(N <= MEM_CACHE_SLOTS);
    unsigned char *b[N];
    size_t bytes = MEM_HUGE_MIN; /* a mapping of two huge pages */
    mem_keep((size_t)N * 2 * MEM_HUGE_MIN);
    size_t made = 0;
    for (size_t i = 0; i < N; i++)
        made += (b[i] = mem_alloc(bytes)) != NULL;
    CHECK(made == N);
    if (made != N) {
        mem_keep(0);
        mem_trim();
        return;
    }
    for (size_t i = 0; i < N; i++) {
        b[i][0] = 0x5a;
        b[i][bytes - 1] = 0xa5;
        mem_free(b[i]);
    }
    size_t reused = 0;
    for (size_t i = 0; i < N; i++) {
        b[i] = mem_alloc(bytes);
        reused += b[i] && b[i][0] == 0x5a && b[i][bytes - 1] == 0xa5;
    }
    CHECK_MSG(reused == N, "%zu of %d freed mappings served again", reused, N);
    for (size_t i = 0; i < N; i++)
        mem_free(b[i]);
    CHECK(mem_trim() >= (size_t)N * bytes);
    /* control: without mem_keep nothing is kept, and the markers are gone */
    mem_keep(0);
    for (size_t i = 0; i < N; i++)
        if ((b[i] = mem_alloc(bytes)) != NULL)
            b[i][0] = 0x5a;
    for (size_t i = 0; i < N; i++)
        mem_free(b[i]);
    reused = 0;
    for (size_t i = 0; i < N; i++) {
        b[i] = mem_alloc(bytes);
        reused += b[i] && b[i][0] == 0x5a;
    }
    CHECK_MSG(reused == 0, "%zu mappings kept without mem_keep", reused);
    for (size_t i = 0; i < N; i++)
        mem_free(b[i]);
}

/* The minor page faults of filling bytes [0, n) of p. */
static long fill_faults(unsigned char *p, size_t n)
{
    struct rusage a, b;
    getrusage(RUSAGE_SELF, &a);
    memset(p, 0x5a, n);
    getrusage(RUSAGE_SELF, &b);
    return b.ru_minflt - a.ru_minflt;
}

/* Fills a fresh buffer of n bytes, frees it, and fills a buffer of n
 * bytes again: the second fill's page faults, the first's in *first; -1
 * when memory runs out. */
static long refill_faults(size_t n, long *first)
{
    unsigned char *a = mem_alloc(n);
    if (!a)
        return -1;
    *first = fill_faults(a, n);
    mem_free(a);
    unsigned char *b = mem_alloc(n);
    if (!b)
        return -1;
    long again = fill_faults(b, n);
    mem_free(b);
    return again;
}

/* A buffer from MEM_MAP_MIN bytes (header included) is a mapping, kept by
 * mem_keep, so that the same buffer again touches no fresh page; one below
 * is malloc's and never kept. Control: without mem_keep the same buffer
 * again faults its pages afresh. */
void test_mem_reuse_mid(void)
{
    size_t mid = (size_t)1 << 20; /* between MEM_MAP_MIN and MEM_HUGE_MIN */
    long pages = (long)(mid / 4096), first = 0;
    CHECK(mid + 64 >= MEM_MAP_MIN && mid + 64 < MEM_HUGE_MIN);
    mem_keep((size_t)64 << 20);
    mem_free(mem_alloc(MEM_MAP_MIN - 64 - 1)); /* malloc's */
    CHECK(mem_trim() == 0);
    long again = refill_faults(mid, &first);
    CHECK_MSG(first >= pages / 2, "the first fill faulted %ld pages", first);
    CHECK_MSG(again >= 0 && again <= 4, "the kept buffer faulted %ld fresh pages again", again);
    CHECK(mem_trim() >= mid);
    mem_keep(0);
    long control = refill_faults(mid, &first); /* nothing kept: fresh pages again */
    CHECK_MSG(control >= pages / 2, "without mem_keep only %ld pages faulted", control);
    CHECK(mem_trim() == 0);
}
