/* kdtree_select: the selection of the k nearest among a pass's candidate
 * keys (renderer/README.md). */
#include "kdtree_impl.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* Reorders the n distinct keys a[0..n) so that a[k-1] is the k-th smallest
 * and a[0..k-1) are the smaller ones (1 <= k <= n). */
void kd_select_keys(uint64_t *a, uint32_t n, uint32_t k)
{
    assert(k >= 1 && k <= n);
    uint32_t lo = 0, hi = n - 1, want = k - 1;
    while (hi - lo > 16) {
        uint32_t mid = lo + (hi - lo) / 2;
        uint64_t x = a[lo], y = a[mid], z = a[hi];
        uint64_t pivot = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
        uint32_t i = lo, j = hi;
        for (;;) {
            while (a[i] < pivot)
                i++;
            while (a[j] > pivot)
                j--;
            if (i >= j)
                break;
            uint64_t tmp = a[i];
            a[i] = a[j];
            a[j] = tmp;
            i++;
            j--;
        }
        /* now a[lo..j] <= pivot <= a[j+1..hi] */
        if (want <= j)
            hi = j;
        else
            lo = j + 1;
    }
    for (uint32_t i = lo + 1; i <= hi; i++) {
        uint64_t v = a[i];
        uint32_t j = i;
        while (j > lo && a[j - 1] > v) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = v;
    }
}

/* Leaves in a[0..k) the k smallest of the m distinct keys in a[0..m), in
 * any order (1 <= k <= m). b and c are scratch of m + 8 keys, a has 8
 * keys of slack. hi >= every key's distance. Each pass splits the
 * candidates three ways around two distances guessed to bracket the k-th
 * (squared distances of points on a surface around the query are close to
 * uniform between the bounds known so far), keeps the part below, and goes
 * on with the one part that holds the k-th, until few are left; a guess
 * that splits nothing off (equal distances) hands over to quickselect. */
void kd_select_k(uint64_t *a, uint64_t *b, uint64_t *c, uint32_t m, uint32_t k, float hi, const kd_ops *ops)
{
    assert(k >= 1 && k <= m);
    uint32_t nacc = 0, need = k, mc = m;
    uint64_t *cand = a; /* candidates cand[0..mc): at a + nacc, in b or in c */
    float lo = 0.0f;
    while (need < mc) {
        if (mc <= KD_RANK_MAX) {
            ops->smallest(cand, mc, need, a + nacc);
            return;
        }
        float span = hi - lo, w = 2.0f * sqrtf((float)need * (float)(mc - need) / (float)mc) + 1.0f;
        float t1 = lo + span * ((float)need - w) / (float)mc, t2 = lo + span * ((float)need + w) / (float)mc;
        t1 = t1 > lo ? t1 : lo;
        t2 = t2 < hi ? t2 : hi;
        /* below t1 joins the result at a + nacc; [t1, t2) goes to b, the rest to c
         * (b or c may be cand itself: each is written behind the read position) */
        uint32_t cnt[3], before = mc;
        ops->split3(cand, mc, pack_key(t1, 0), pack_key(t2, 0), a + nacc, b, c, cnt);
        assert(cnt[0] + cnt[1] + cnt[2] == mc);
        if (cnt[0] > need) { /* the k-th is below t1 */
            cand = a + nacc;
            mc = cnt[0];
            hi = t1;
        } else if (cnt[0] + cnt[1] >= need) { /* in [t1, t2) */
            nacc += cnt[0];
            need -= cnt[0];
            cand = b;
            mc = cnt[1];
            lo = t1;
            hi = t2;
        } else { /* at or above t2 */
            memcpy(a + nacc + cnt[0], b, sizeof(uint64_t) * cnt[1]);
            nacc += cnt[0] + cnt[1];
            need -= cnt[0] + cnt[1];
            cand = c;
            mc = cnt[2];
            lo = t2;
        }
        if (need == 0)
            return;
        if (mc == before) { /* the guess split nothing off */
            kd_select_keys(cand, mc, need);
            break;
        }
    }
    if (cand != a + nacc)
        memmove(a + nacc, cand, sizeof(uint64_t) * need);
}
