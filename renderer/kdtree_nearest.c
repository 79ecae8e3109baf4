/* kdtree_nearest: kd_nearest_if, the nearest point that passes a caller's
 * predicate: a descent to each leaf in turn (nearest first) with the base
 * leaf scan's mask, the bound shrinking to the best distance found, the
 * hint's distance bounding the search from the start. */
#include "kdtree_impl.h"

#include <string.h>

uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, uint32_t hint,
                       float *d2)
{
    uint32_t best = KD_NONE;
    float best_d2 = max_d2;
    if (hint < t->n) {
        float dx = t->x[hint] - q[0], dy = t->y[hint] - q[1], dz = t->z[hint] - q[2];
        float d = dx * dx + dy * dy + dz * dz; /* as chunk_d2 computes it */
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
            do {
                uint32_t leaf = descend(t, node, q, rd, off, prune_bound(best_d2), stack, &sp);
                uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
                for (uint32_t c = beg; c < end; c += KD_CHUNK) {
                    /* only the lanes within the best distance so far */
                    uint32_t bits[KD_CHUNK];
                    uint32_t m = chunk_mask(t->x, t->y, t->z, c, &qv, bits);
                    if (end - c < KD_CHUNK)
                        m &= (1u << (end - c)) - 1u;
                    while (m) {
                        uint32_t j = (uint32_t)__builtin_ctz(m);
                        m &= m - 1u;
                        float d;
                        memcpy(&d, &bits[j], sizeof d);
                        if (d <= best_d2 && (best == KD_NONE || d < best_d2 || c + j < best) &&
                            (!pred || pred(c + j, ctx))) {
                            best = c + j;
                            best_d2 = d;
                            KD_QBASE_SETR2(qv, best_d2);
                        }
                    }
                }
            } while (pop(stack, &sp, prune_bound(best_d2), &node, &rd, off));
        }
    }
    *d2 = best == KD_NONE ? 0.0f : best_d2;
    return best;
}
