/* rng: counter-based streams built on the SplitMix64 finaliser: number k of
 * stream (seed, i) is mix(key(seed, i) + (k+1) * golden). Stateless apart from
 * the counter, so streams are independent of scheduling. */
#include "rng.h"

static uint64_t rng_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

rng_stream rng_make(uint64_t seed, uint64_t index)
{
    rng_stream s;
    s.key = rng_mix(rng_mix(seed ^ 0x6a09e667f3bcc909ULL) + index * 0x9e3779b97f4a7c15ULL);
    s.counter = 0;
    return s;
}

uint64_t rng_next_u64(rng_stream *s)
{
    s->counter++;
    return rng_mix(s->key + s->counter * 0x9e3779b97f4a7c15ULL);
}

double rng_next_double(rng_stream *s)
{
    return (double)(rng_next_u64(s) >> 11) * 0x1.0p-53;
}
