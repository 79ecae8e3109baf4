/* rng: counter-based random streams. A stream is named by (seed, index) and
 * yields the same numbers whichever thread draws them, so photon i and pixel j
 * see the same randomness for any thread count. */
#ifndef PM_RNG_H
#define PM_RNG_H

#include <stdint.h>

/* One random stream: its key and position. */
typedef struct {
    uint64_t key;     /* hash of (seed, stream index) */
    uint64_t counter; /* how many numbers were drawn */
} rng_stream;

/* The stream for (seed, index); never fails. */
rng_stream rng_make(uint64_t seed, uint64_t index);
/* Next 64 random bits of the stream. */
uint64_t rng_next_u64(rng_stream *s);
/* Uniform double in [0, 1), 53 bits. */
double rng_next_double(rng_stream *s);

#endif
