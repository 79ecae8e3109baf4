/* photons: the photon pass and the map build (renderer/README.md). */
#include "photons.h"

#include <assert.h>
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "material.h"
#include "mem.h"
#include "parallel.h"
#include "rng.h"

/* Photons per chunk: a power of two from PHOTONS_CHUNK_MIN to
 * PHOTONS_CHUNK_MAX giving at least PHOTONS_CHUNKS_MIN chunks (the stored
 * list does not depend on it: chunks are joined in index order). Large
 * chunks keep their buffers on huge pages (mem.h); enough chunks keep the
 * threads' shares even. */
#define PHOTONS_CHUNK_MIN 4096u
#define PHOTONS_CHUNK_MAX 262144u
#define PHOTONS_CHUNKS_MIN 64u
#define PHOTONS_PILOT 4096u
#define PHOTONS_FIRST_CAP 4096u /* records of a buffer nothing is known about yet */
#define PHOTONS_CAP_SLACK 1.1   /* a chunk's buffer: this times the stored-per-photon of chunk 0 */

void photons_pack_dir(double x, double y, double z, int8_t out[3])
{
    out[0] = (int8_t)lrint(vec_max2(-1.0, vec_min2(1.0, x)) * 127.0);
    out[1] = (int8_t)lrint(vec_max2(-1.0, vec_min2(1.0, y)) * 127.0);
    out[2] = (int8_t)lrint(vec_max2(-1.0, vec_min2(1.0, z)) * 127.0);
}

vec3 photons_unpack_dir(const int8_t d[3])
{
    return vec_make(d[0] / 127.0, d[1] / 127.0, d[2] / 127.0);
}

/* One chunk's photons, in index order. A worker fills a local copy and
 * writes it back once, at the chunk's end, so two threads never write the
 * same cache line of the chunks array while they trace. */
typedef struct {
    uint64_t count, cap;
    double *pos;
    photons_record *ph;
    uint64_t truncated, escaped;
    uint64_t rays, shape_tests; /* rays cast and their shape tests (work.h) */
    pm_status status; /* PM_OK, or why the chunk stopped */
} photons_chunk;

typedef struct {
    const scene *sc;
    const photons_params *p;
    photons_chunk *chunks;
    uint64_t chunk_len;  /* photons per chunk */
    uint64_t cap;        /* records a chunk's buffers start with (0: PHOTONS_FIRST_CAP on first store) */
    int first;           /* chunk 0 is done: trace_chunk skips it */
    progress *prog;
} trace_ctx;

/* Sets c's buffers to hold at least `want` records (and what that costs
 * no more pages: mem_round), keeping its photons. Returns PM_OK, or
 * PM_ERR_NOMEM (c is then unchanged). */
static pm_status chunk_reserve(photons_chunk *c, uint64_t want)
{
    /* never below what mem_round makes a mapping of: a chunk's memory
     * then goes back to the system when the join frees it (malloc would
     * keep it for reuse, so the chunks and the list would both be held) */
    uint64_t least = MEM_HUGE_MIN / 2 / sizeof(photons_record) + 1;
    want = want > least ? want : least;
    size_t pos_bytes = mem_round(want * 3 * sizeof(double)), ph_bytes = mem_round(want * sizeof(photons_record));
    uint64_t a = pos_bytes / (3 * sizeof(double)), b = ph_bytes / sizeof(photons_record);
    double *np = mem_realloc(c->pos, pos_bytes);
    if (!np)
        return PM_ERR_NOMEM;
    c->pos = np;
    photons_record *nph = mem_realloc(c->ph, ph_bytes);
    if (!nph)
        return PM_ERR_NOMEM;
    c->ph = nph;
    c->cap = a < b ? a : b;
    assert(c->cap >= want);
    return PM_OK;
}

/* Appends one photon of relative power `power` to c. Returns PM_OK, or
 * PM_ERR_NOMEM. */
static pm_status chunk_store(photons_chunk *c, vec3 p, vec3 dir, vec3 power, vec3 n, unsigned flags)
{
    pm_status rc;
    if (c->count == c->cap &&
        (rc = chunk_reserve(c, c->cap ? c->cap + c->cap / 2 : PHOTONS_FIRST_CAP)) != PM_OK)
        return rc;
    double *q = c->pos + 3 * c->count;
    q[0] = p.x;
    q[1] = p.y;
    q[2] = p.z;
    photons_record *ph = &c->ph[c->count];
    ph->power[0] = (float)power.x;
    ph->power[1] = (float)power.y;
    ph->power[2] = (float)power.z;
    photons_pack_dir(dir.x, dir.y, dir.z, ph->dir);
    photons_pack_dir(n.x, n.y, n.z, ph->normal);
    ph->flags = (uint8_t)flags;
    ph->pad = 0;
    c->count++;
    return PM_OK;
}

/* Traces photon `index` into chunk c; its power starts at 1 (the list's
 * unit). Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status trace_one(const trace_ctx *tc, uint64_t index, photons_chunk *c)
{
    const scene *sc = tc->sc;
    const photons_params *pp = tc->p;
    rng_stream rs = rng_make(pp->seed, index);
    /* isotropic emission */
    double u1 = rng_next_double(&rs), u2 = rng_next_double(&rs);
    double z = 1.0 - 2.0 * u1, s = sqrt(vec_max2(0.0, 1.0 - z * z)), phi = 2.0 * VEC_PI * u2;
    shape_ray r = {sc->light.position, vec_make(s * cos(phi), s * sin(phi), z)};
    vec3 power = vec_make(1, 1, 1);
    unsigned bounces = 0;
    int diffuse_before = 0; /* a diffuse bounce on the path so far: not a caustic path */
    for (uint32_t depth = 0;; depth++) {
        if (depth >= pp->photon_depth) {
            c->truncated++;
            return PM_OK;
        }
        scene_hit h;
        c->rays++;
        if (!scene_intersect_counted(sc, &r, INFINITY, &h, &c->shape_tests)) {
            c->escaped++;
            return PM_OK;
        }
        const material *m = &sc->materials[sc->shapes[h.shape].material];
        if (m->kind == MATERIAL_LAMBERT) {
            if (pp->store_first_hits || bounces > 0) {
                unsigned flags = bounces == 0       ? PHOTONS_FLAG_DIRECT
                                 : !diffuse_before ? PHOTONS_FLAG_CAUSTIC
                                                   : 0u;
                pm_status rc = chunk_store(c, h.p, r.dir, power, h.n, flags);
                if (rc != PM_OK)
                    return rc;
            }
            double pc = vec_maxc(m->color);
            if (!(rng_next_double(&rs) < pc))
                return PM_OK;
            power = vec_scale(vec_mul(power, m->color), 1.0 / pc);
            double v1 = rng_next_double(&rs), v2 = rng_next_double(&rs);
            r = scene_spawn(&h, material_sample_cosine(h.n, v1, v2), 1);
            diffuse_before = 1;
        } else if (m->kind == MATERIAL_MIRROR) {
            power = vec_mul(power, m->color);
            if (vec_maxc(power) <= 0.0)
                return PM_OK;
            r = scene_spawn(&h, material_reflect(r.dir, h.n), 1);
        } else {
            double n1 = h.front ? 1.0 : m->ior, n2 = h.front ? m->ior : 1.0;
            double fr = material_fresnel(-vec_dot(r.dir, h.n), n1, n2);
            vec3 refr;
            if (rng_next_double(&rs) < fr || !material_refract(r.dir, h.n, n1 / n2, &refr))
                r = scene_spawn(&h, material_reflect(r.dir, h.n), 1);
            else
                r = scene_spawn(&h, refr, 0);
        }
        bounces++;
    }
}

static void trace_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    (void)thread;
    trace_ctx *tc = arg;
    if (chunk == 0 && tc->first)
        return;
    photons_chunk c = {0};
    uint64_t lo = chunk * tc->chunk_len;
    uint64_t hi = lo + tc->chunk_len < tc->p->photons ? lo + tc->chunk_len : tc->p->photons;
    if (tc->cap)
        c.status = chunk_reserve(&c, tc->cap);
    for (uint64_t i = lo; i < hi && c.status == PM_OK; i++)
        c.status = trace_one(tc, i, &c);
    if (c.status == PM_OK && c.cap > c.count) {
        /* the buffers' unused tails go back: their last huge page is
         * backed whole once touched, a waste of up to 2 MiB each while the
         * chunk waits to be joined (a failed shrink keeps them as they are) */
        double *np = mem_realloc(c.pos, (c.count ? c.count : 1) * 3 * sizeof(double));
        c.pos = np ? np : c.pos;
        photons_record *nph = mem_realloc(c.ph, (c.count ? c.count : 1) * sizeof(photons_record));
        c.ph = nph ? nph : c.ph;
    }
    tc->chunks[chunk] = c;
    progress_add(tc->prog, hi - lo);
}

typedef struct {
    photons_chunk *chunks;
    const uint64_t *at; /* each chunk's first index in the list */
    photons_list *out;
} join_ctx;

/* Copies one chunk into its place in the list and frees its buffers. */
static void join_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    (void)thread;
    join_ctx *jc = arg;
    photons_chunk *c = &jc->chunks[chunk];
    if (c->count) {
        memcpy(jc->out->pos + 3 * jc->at[chunk], c->pos, c->count * 3 * sizeof(double));
        memcpy(jc->out->ph + jc->at[chunk], c->ph, c->count * sizeof(photons_record));
    }
    mem_free(c->pos);
    mem_free(c->ph);
    c->pos = NULL;
    c->ph = NULL;
}

pm_status photons_trace(const scene *sc, const photons_params *p, unsigned threads, progress *prog, photons_list *out)
{
    memset(out, 0, sizeof *out);
    uint64_t len = PHOTONS_CHUNK_MIN;
    while (len < PHOTONS_CHUNK_MAX && len * PHOTONS_CHUNKS_MIN < p->photons)
        len *= 2;
    uint64_t nchunks = (p->photons + len - 1) / len;
    photons_chunk *chunks = calloc(nchunks ? nchunks : 1, sizeof(photons_chunk));
    uint64_t *at = malloc(sizeof(uint64_t) * (nchunks ? nchunks : 1));
    if (!chunks || !at) {
        free(chunks);
        free(at);
        return PM_ERR_NOMEM;
    }
    trace_ctx tc = {sc, p, chunks, len, 0, 0, prog};
    if (nchunks > 0) {
        /* chunk 0 alone first: what it stores per photon sizes the other
         * chunks' buffers, so that they rarely grow */
        trace_chunk(0, 0, &tc);
        double per = (double)chunks[0].count / (double)(len < p->photons ? len : p->photons);
        tc.cap = (uint64_t)(per * PHOTONS_CAP_SLACK * (double)len) + 64;
        tc.first = 1;
    }
    parallel_for(threads, nchunks, trace_chunk, &tc);
    pm_status rc = PM_OK;
    uint64_t total = 0;
    for (uint64_t i = 0; i < nchunks; i++) {
        if (rc == PM_OK)
            rc = chunks[i].status;
        at[i] = total;
        total += chunks[i].count;
        out->truncated += chunks[i].truncated;
        out->escaped += chunks[i].escaped;
        out->rays += chunks[i].rays;
        out->shape_tests += chunks[i].shape_tests;
    }
    if (rc == PM_OK) {
        out->pos = mem_alloc((total ? total : 1) * 3 * sizeof(double));
        out->ph = mem_alloc((total ? total : 1) * sizeof(photons_record));
        if (!out->pos || !out->ph)
            rc = PM_ERR_NOMEM;
    }
    if (rc == PM_OK) {
        join_ctx jc = {chunks, at, out};
        parallel_for(threads, nchunks, join_chunk, &jc);
    }
    for (uint64_t i = 0; i < nchunks; i++) {
        mem_free(chunks[i].pos);
        mem_free(chunks[i].ph);
    }
    free(chunks);
    free(at);
    if (rc != PM_OK) {
        photons_list_free(out);
        return rc;
    }
    out->count = total;
    out->unit = p->photons ? vec_scale(sc->light.power, 1.0 / (double)p->photons) : vec_make(0, 0, 0);
    return PM_OK;
}

void photons_list_free(photons_list *l)
{
    mem_free(l->pos);
    mem_free(l->ph);
    memset(l, 0, sizeof *l);
}

pm_status photons_list_select(const photons_list *l, uint8_t mask, photons_list *out)
{
    memset(out, 0, sizeof *out);
    uint64_t n = 0;
    for (uint64_t i = 0; i < l->count; i++)
        n += (l->ph[i].flags & mask) != 0;
    out->pos = mem_alloc((n ? n : 1) * 3 * sizeof(double));
    out->ph = mem_alloc((n ? n : 1) * sizeof(photons_record));
    if (!out->pos || !out->ph) {
        photons_list_free(out);
        return PM_ERR_NOMEM;
    }
    uint64_t j = 0;
    for (uint64_t i = 0; i < l->count; i++) {
        if (l->ph[i].flags & mask) {
            memcpy(out->pos + 3 * j, l->pos + 3 * i, 3 * sizeof(double));
            out->ph[j++] = l->ph[i];
        }
    }
    out->count = n;
    out->unit = l->unit;
    return PM_OK;
}

/* The map frame of a list whose bounding box is lo..hi (lo > hi in some
 * axis: no photons): the centre of the box and the power of two at or
 * above its half-diagonal (1 for an empty or one-point list), and the box's
 * diagonal. */
static void map_frame(uint64_t count, const double lo[3], const double hi[3], vec3 *centre, double *scale,
                      double *extent)
{
    *extent = 0.0;
    if (count == 0) {
        *centre = vec_make(0, 0, 0);
        *scale = 1.0;
        return;
    }
    *centre = vec_make(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
    double half = 0.5 * sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(half > 0.0) || !isfinite(half)) {
        *scale = 1.0;
        return;
    }
    *extent = 2.0 * half;
    int e;
    frexp(half, &e); /* half = f * 2^e, f in [0.5, 1) */
    *scale = ldexp(1.0, e);
}

/* The build's passes over the list run over blocks of this many photons;
 * what a block finds (bounds by strict comparisons in list order, counts)
 * is merged in block order, which gives what one pass in order gives. */
#define PHOTONS_BLOCK 65536u

/* The conversion into the tree's items runs over this many segments of
 * blocks, in order; after each, the list's pages it has read go back to
 * the system, so the list and the items are never both whole. */
#define PHOTONS_SEGMENTS 32u

_Static_assert(sizeof(photons_record) == sizeof(((kd_build_item *)0)->payload),
               "a record is a tree item's payload");

typedef struct {
    const photons_list *l;
    uint8_t leave_out;
    photons_map *m;
    photons_list *left;
    kd_build_item *items; /* the tree's input, then (in place) its leaf order */
    uint64_t first;       /* split_block: the segment's first block; compact_block: the round's first item */
    uint64_t end;         /* compact_block: the round's end */
    double (*box)[2][3];  /* per block: min, max */
    uint32_t (*at)[2];    /* per block: its photons' first tree input, first left-out */
} build_ctx;

static void block_range(uint64_t blk, uint64_t count, uint32_t *lo, uint32_t *hi)
{
    *lo = (uint32_t)(blk * PHOTONS_BLOCK);
    *hi = count - *lo < PHOTONS_BLOCK ? (uint32_t)count : *lo + PHOTONS_BLOCK;
}

/* A block's bounds and its count of photons left out (to at[blk][1]). */
static void scan_block(uint64_t blk, unsigned thread, void *arg)
{
    (void)thread;
    build_ctx *bc = arg;
    const photons_list *l = bc->l;
    uint32_t lo, hi, out = 0;
    block_range(blk, l->count, &lo, &hi);
    double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = lo; i < hi; i++) {
        for (int a = 0; a < 3; a++) {
            double v = l->pos[3 * (size_t)i + (size_t)a];
            mn[a] = v < mn[a] ? v : mn[a];
            mx[a] = v > mx[a] ? v : mx[a];
        }
        out += (l->ph[i].flags & bc->leave_out) != 0;
    }
    memcpy(bc->box[blk][0], mn, sizeof mn);
    memcpy(bc->box[blk][1], mx, sizeof mx);
    bc->at[blk][1] = out;
}

/* Block first + k's photons into the tree's items (map frame, the record
 * as payload) or the left-out list. */
static void split_block(uint64_t k, unsigned thread, void *arg)
{
    (void)thread;
    build_ctx *bc = arg;
    const photons_list *l = bc->l;
    uint64_t blk = bc->first + k;
    uint32_t lo, hi, j = bc->at[blk][0], r = bc->at[blk][1];
    block_range(blk, l->count, &lo, &hi);
    for (uint32_t i = lo; i < hi; i++) {
        if (l->ph[i].flags & bc->leave_out) {
            memcpy(bc->left->pos + 3 * (size_t)r, l->pos + 3 * (size_t)i, 3 * sizeof(double));
            bc->left->ph[r++] = l->ph[i];
            continue;
        }
        vec3 x = vec_make(l->pos[3 * (size_t)i], l->pos[3 * (size_t)i + 1], l->pos[3 * (size_t)i + 2]);
        photons_map_point(bc->m, x, bc->items[j].p);
        memcpy(bc->items[j].payload, &l->ph[i], sizeof(photons_record));
        j++;
    }
}

/* Moves the payload of items [lo, hi) to records [lo, hi) of the same
 * buffer (record i at byte 20 i, item i at byte 32 i). */
static void compact_range(kd_build_item *items, uint32_t lo, uint32_t hi)
{
    char *base = (char *)items;
    for (uint32_t i = lo; i < hi; i++)
        memmove(base + (size_t)i * sizeof(photons_record), items[i].payload, sizeof(photons_record));
}

/* One block of a compaction round [first, end). */
static void compact_block(uint64_t k, unsigned thread, void *arg)
{
    (void)thread;
    build_ctx *bc = arg;
    uint64_t lo = bc->first + k * PHOTONS_BLOCK, hi = lo + PHOTONS_BLOCK < bc->end ? lo + PHOTONS_BLOCK : bc->end;
    compact_range(bc->items, (uint32_t)lo, (uint32_t)hi);
}

/* Turns the n items, in leaf order, into n records at the front of their
 * own buffer. A round over items [a, b) writes bytes [20 a, 20 b) and reads
 * [32 a, 32 b): with b <= 1.6 a no write of a round lands on an item that
 * is still to be read, so a round's blocks run in parallel. */
static void compact_items(build_ctx *bc, uint32_t n, unsigned threads)
{
    uint64_t a = n < PHOTONS_BLOCK ? n : PHOTONS_BLOCK;
    compact_range(bc->items, 0, (uint32_t)a); /* in order: the first items' records overlap them */
    while (a < n) {
        uint64_t b = a + a * 3 / 5;
        b = b < n ? b : n;
        assert(b * sizeof(photons_record) <= a * sizeof(kd_build_item));
        bc->first = a;
        bc->end = b;
        parallel_for(threads, (b - a + PHOTONS_BLOCK - 1) / PHOTONS_BLOCK, compact_block, bc);
        a = b;
    }
}

void photons_map_point(const photons_map *m, vec3 x, float q[3])
{
    double inv = 1.0 / m->scale; /* exact: a power of two */
    q[0] = (float)((x.x - m->centre.x) * inv);
    q[1] = (float)((x.y - m->centre.y) * inv);
    q[2] = (float)((x.z - m->centre.z) * inv);
}

/* Converts the list's blocks into the tree's items and the left-out list,
 * a segment at a time, handing the list's pages back after each. */
static void convert_list(build_ctx *bc, uint64_t nblocks, unsigned threads)
{
    const photons_list *l = bc->l;
    uint64_t per = nblocks / PHOTONS_SEGMENTS ? nblocks / PHOTONS_SEGMENTS : 1, done = 0;
    for (uint64_t s = 0; s < nblocks; s += per) {
        uint64_t e = s + per < nblocks ? s + per : nblocks;
        bc->first = s;
        parallel_for(threads, e - s, split_block, bc);
        uint64_t upto = e * PHOTONS_BLOCK < l->count ? e * PHOTONS_BLOCK : l->count;
        mem_release(l->pos, done * 3 * sizeof(double), (upto - done) * 3 * sizeof(double));
        mem_release(l->ph, done * sizeof(photons_record), (upto - done) * sizeof(photons_record));
        done = upto;
    }
}

pm_status photons_build_map(photons_list *l, uint8_t leave_out, unsigned threads, photons_map *m, photons_list *left)
{
    assert(left || leave_out == 0);
    memset(m, 0, sizeof *m);
    if (left)
        memset(left, 0, sizeof *left);
    if (l->count > UINT32_MAX - 1) {
        photons_list_free(l);
        return PM_ERR_NOMEM;
    }
    m->unit = l->unit;
    m->stored = l->count;
    uint64_t nblocks = (l->count + PHOTONS_BLOCK - 1) / PHOTONS_BLOCK;
    build_ctx bc = {l, leave_out, m, left, NULL, 0, 0, NULL, NULL};
    bc.box = mem_alloc(sizeof *bc.box * (nblocks ? nblocks : 1));
    bc.at = mem_alloc(sizeof *bc.at * (nblocks ? nblocks : 1));
    pm_status rc = (!bc.box || !bc.at) ? PM_ERR_NOMEM : PM_OK;
    uint32_t n = 0, nout = 0;
    if (rc == PM_OK) {
        parallel_for(threads, nblocks, scan_block, &bc);
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (uint64_t k = 0; k < nblocks; k++) {
            for (int a = 0; a < 3; a++) {
                lo[a] = bc.box[k][0][a] < lo[a] ? bc.box[k][0][a] : lo[a];
                hi[a] = bc.box[k][1][a] > hi[a] ? bc.box[k][1][a] : hi[a];
            }
            uint32_t lo_i, hi_i, out = bc.at[k][1];
            block_range(k, l->count, &lo_i, &hi_i);
            bc.at[k][0] = n;
            bc.at[k][1] = nout;
            n += hi_i - lo_i - out;
            nout += out;
        }
        map_frame(l->count, lo, hi, &m->centre, &m->scale, &m->extent);
        bc.items = mem_alloc(sizeof(kd_build_item) * (n ? n : 1));
        rc = !bc.items ? PM_ERR_NOMEM : PM_OK;
    }
    if (rc == PM_OK && left) {
        left->pos = mem_alloc(sizeof(double) * 3 * (nout ? nout : 1));
        left->ph = mem_alloc(sizeof(photons_record) * (nout ? nout : 1));
        left->unit = l->unit;
        rc = (!left->pos || !left->ph) ? PM_ERR_NOMEM : PM_OK;
    }
    assert(rc != PM_OK || left || nout == 0);
    if (rc == PM_OK) {
        convert_list(&bc, nblocks, threads);
        if (left)
            left->count = nout;
    }
    mem_free(bc.box);
    mem_free(bc.at);
    photons_list_free(l);
    if (rc == PM_OK)
        rc = kd_build_items(&m->tree, bc.items, n, KD_DEFAULT_LEAF, threads);
    if (rc == PM_OK) {
        m->count = n;
        compact_items(&bc, n, threads);
        /* the records' tail of the items' buffer goes back (a shrink
         * keeps the buffer where it is; should a copy fail, the buffer
         * stays as it is, larger than it needs) */
        photons_record *ph = mem_realloc(bc.items, sizeof(photons_record) * (n ? n : 1));
        m->ph = ph ? ph : (photons_record *)(void *)bc.items;
    } else {
        mem_free(bc.items);
        photons_map_free(m);
        if (left)
            photons_list_free(left);
    }
    return rc;
}

void photons_map_free(photons_map *m)
{
    kd_free(&m->tree);
    mem_free(m->ph);
    memset(m, 0, sizeof *m);
}

size_t photons_map_bytes(const photons_map *m)
{
    return kd_bytes(&m->tree) + (size_t)m->count * sizeof(photons_record);
}

double photons_peak_bytes(double stored)
{
    /* The trace: the chunks (each shrunk to its photons when done) and
     * the joined list, each chunk freed as soon as it is copied: one list
     * (double positions and a record) at once. The conversion: the list,
     * its pages handed back a segment at a time, beside the tree's items
     * (or the left-out list) written so far: at most one segment of both.
     * The build: the items, reordered in place, beside the tree's arrays;
     * then the records compacted into the items' buffer, which shrinks. */
    double list = 3.0 * sizeof(double) + sizeof(photons_record);
    /* beside them, while chunks are traced, the last huge page of each
     * buffer of a chunk in flight (two buffers, on two threads) */
    double inflight = 4.0 * (double)MEM_HUGE_MIN;
    double convert = stored * list * (1.0 + 1.0 / PHOTONS_SEGMENTS) + inflight;
    double build = stored * (double)sizeof(kd_build_item) + kd_tree_bytes(stored, KD_DEFAULT_LEAF);
    return fmax(convert, build);
}

pm_status photons_stored_per_emitted(const scene *sc, const photons_params *p, double *per)
{
    photons_params pilot = *p;
    pilot.photons = p->photons < PHOTONS_PILOT ? p->photons : PHOTONS_PILOT;
    *per = 0.0;
    if (pilot.photons == 0)
        return PM_OK;
    photons_list l;
    pm_status rc = photons_trace(sc, &pilot, 1, NULL, &l);
    if (rc != PM_OK)
        return rc;
    *per = (double)l.count / (double)pilot.photons;
    photons_list_free(&l);
    return PM_OK;
}
