/* Counter-based random numbers (Random123's Philox4x32-10, Salmon et al. 2011): a pure function of
   (key, counter), so every backend draws the very same numbers for the same photon, bounce and
   frame, and no generator state is stored. key = (seed, frame); counter = (index, event, stream). */
#ifndef PM_RNG_H
#define PM_RNG_H

#include <Random123/philox.h>

/* Streams keep the uses of one (index, event) pair independent. */
#define PM_STREAM_PHOTON 0x50484f54u /* "PHOT" */

typedef struct Uniform4 { float u0, u1, u2, u3; } Uniform4;

/* Top 24 bits to a float in [0, 1): exactly representable, never 1. */
PM_DEVICE float rng_to_unit(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

PM_DEVICE Uniform4 rng_uniform4(uint seed, uint frame, uint index, uint event, uint stream)
{
  philox4x32_key_t key = {{seed, frame}};
  philox4x32_ctr_t ctr = {{index, event, stream, 0u}};
  philox4x32_ctr_t r = philox4x32(ctr, key);
  Uniform4 u;
  u.u0 = rng_to_unit(r.v[0]);
  u.u1 = rng_to_unit(r.v[1]);
  u.u2 = rng_to_unit(r.v[2]);
  u.u3 = rng_to_unit(r.v[3]);
  return u;
}

#endif
