/* kdtree_nearest: kd_nearest_if, the nearest point that passes a caller's
 * predicate (renderer/README.md). */
#include "kdtree_impl.h"

#include <string.h>

/* The leaf holding leaf-order point i (i < t->n). Nodes split their range
 * at lo + (hi - lo) / 2, so leaves hold floor or ceil of n / nleaves
 * points and the proportional guess is at most a leaf or two off. */
static uint32_t leaf_of(const kd_tree *t, uint32_t i)
{
    assert(i < t->n);
    uint32_t leaf = (uint32_t)((uint64_t)i * t->nleaves / t->n);
    while (t->leaf_start[leaf] > i)
        leaf--;
    while (t->leaf_start[leaf + 1] <= i)
        leaf++;
    return leaf;
}

/* As descend, but along the path to `leaf` whichever side of each split q
 * is on: the child off the path is pushed when its cell lies within
 * `bound`, and *rd and off become the leaf's cell's. Returns 1, or 0 when
 * the path leaves `bound` (then what is still to search is on the stack). */
static int descend_to(const kd_tree *t, uint32_t leaf, const float q[3], float *rd, float off[3], float bound,
                      kd_frame *stack, int *sp, uint64_t *nodes)
{
    assert((t->nleaves & (t->nleaves - 1)) == 0 && leaf < t->nleaves);
    uint32_t depth = (uint32_t)__builtin_ctz(t->nleaves), node = 0;
    for (uint32_t level = depth; level-- > 0;) {
        ++*nodes;
        uint32_t right = (leaf >> level) & 1u, path = 2 * node + 1 + right;
        int a = t->axis[node];
        float diff = q[a] - t->split[node];
        float old = off[a];
        float nrd = *rd - old * old + diff * diff; /* the cell on the other side of the split from q */
        int q_right = diff >= 0.0f;
        /* the child off the path: q's side keeps rd and off; the other side gets nrd, off[a] = diff */
        float other_rd = (q_right == (int)right) ? nrd : *rd;
        if (other_rd <= bound) {
            assert(*sp < KD_STACK);
            kd_frame *f = &stack[(*sp)++];
            f->node = 4 * node + 3 - path;
            f->rd = other_rd;
            f->off[0] = off[0];
            f->off[1] = off[1];
            f->off[2] = off[2];
            if (q_right == (int)right)
                f->off[a] = diff;
        }
        if (q_right != (int)right) {
            *rd = nrd;
            off[a] = diff;
        }
        if (!(*rd <= bound))
            return 0;
        node = path;
    }
    return 1;
}

/* Scans leaf `leaf` for a qualifying point nearer than *best_d2 (of points
 * at the same distance, the lowest index), updating *best, *best_d2 and
 * qv's radius, and adds the leaf and its points to *nodes and *points
 * (inlined always: they stay in registers). */
static inline __attribute__((always_inline)) void scan_leaf(const kd_tree *t, uint32_t leaf, kd_pred pred,
                                                            const void *ctx, kd_qbase *qv, uint32_t *best,
                                                            float *best_d2, uint64_t *nodes, uint64_t *points)
{
    uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
    *nodes += 1;
    *points += end - beg;
    for (uint32_t c = beg; c < end; c += KD_CHUNK) {
        /* only the lanes within the best distance so far */
        uint32_t bits[KD_CHUNK];
        uint32_t m = chunk_mask(t->x, t->y, t->z, c, qv, bits);
        if (end - c < KD_CHUNK)
            m &= (1u << (end - c)) - 1u;
        while (m) {
            uint32_t j = (uint32_t)__builtin_ctz(m);
            m &= m - 1u;
            float d;
            memcpy(&d, &bits[j], sizeof d);
            if (d <= *best_d2 && (*best == KD_NONE || d < *best_d2 || c + j < *best) && (!pred || pred(c + j, ctx))) {
                *best = c + j;
                *best_d2 = d;
                KD_QBASE_SETR2(*qv, *best_d2);
            }
        }
    }
}

uint32_t kd_nearest_if_counted(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx,
                               uint32_t hint, float *d2, kd_work *w)
{
    uint32_t best = KD_NONE;
    float best_d2 = max_d2;
    uint64_t nodes = 0, points = 0;
    if (hint < t->n) {
        float dx = t->x[hint] - q[0], dy = t->y[hint] - q[1], dz = t->z[hint] - q[2];
        float d = dx * dx + dy * dy + dz * dz; /* as chunk_d2 computes it */
        points++;
        if (d <= max_d2 && (!pred || pred(hint, ctx))) {
            best = hint;
            best_d2 = d;
        }
    }
    if (t->n > 0) {
        kd_frame stack[KD_STACK];
        int sp = 0;
        float off[3];
        float rd = root_offsets(t, q, off);
        uint32_t node = 0;
        if (rd <= prune_bound(max_d2)) {
            kd_qbase qv;
            KD_QBASE_INIT(qv, q, best_d2);
            /* the first leaf: the hint's, reached along its known path, or q's by descent */
            if (best != KD_NONE) {
                uint32_t leaf = leaf_of(t, best);
                if (descend_to(t, leaf, q, &rd, off, prune_bound(best_d2), stack, &sp, &nodes))
                    scan_leaf(t, leaf, pred, ctx, &qv, &best, &best_d2, &nodes, &points);
            } else {
                nodes += descent_length(t, node);
                scan_leaf(t, descend(t, node, q, rd, off, prune_bound(best_d2), stack, &sp), pred, ctx, &qv, &best,
                          &best_d2, &nodes, &points);
            }
            while (pop(stack, &sp, prune_bound(best_d2), &node, &rd, off)) {
                nodes += descent_length(t, node);
                scan_leaf(t, descend(t, node, q, rd, off, prune_bound(best_d2), stack, &sp), pred, ctx, &qv, &best,
                          &best_d2, &nodes, &points);
            }
        }
    }
    *d2 = best == KD_NONE ? 0.0f : best_d2;
    if (w) {
        w->nodes += nodes;
        w->points += points;
    }
    return best;
}

uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, uint32_t hint,
                       float *d2)
{
    return kd_nearest_if_counted(t, q, max_d2, pred, ctx, hint, d2, NULL);
}
