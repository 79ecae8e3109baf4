/* kdtree_test: the stateless k-nearest search, for the unit tests only.
 * The renderer and the benchmark always carry a kd_query (each thread has
 * one, and its starting radius is what makes coherent queries cheap), so
 * kd_knn is not part of kdtree.h; the tests keep it as a second entry point
 * that must give kd_query_knn's result with no state at all. */
#ifndef PM_KDTREE_TEST_H
#define PM_KDTREE_TEST_H

#include "kdtree.h"

/* kd_query_knn without a state (the same result; no starting radius, so
 * slower on coherent query sequences). Never fails. */
uint32_t kd_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2,
                float *r2);

#endif
