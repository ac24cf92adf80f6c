/* Counter-based random numbers (Random123's Philox4x32-10, Salmon et al. 2011): a pure function of
   (key, counter), so every backend draws the very same numbers for the same photon, bounce and
   frame, and no generator state is stored. key = (seed, frame); counter = (index, event, stream,
   extra). Also the Halton sequence's radical inverses, for quasi-random photon emission. */
#ifndef PM_RNG_H
#define PM_RNG_H

#include <Random123/philox.h>

/* Streams keep the uses of one (index, event) pair independent. */
#define PM_STREAM_PHOTON 0x50484f54u /* "PHOT" */
#define PM_STREAM_HALTON 0x48414c54u /* "HALT": the per-light rotation of the Halton points */

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

/* The same generator as raw 32-bit words, with the counter's fourth word free for the caller. */
typedef struct Bits4 { uint b0, b1, b2, b3; } Bits4;

PM_DEVICE Bits4 rng_bits4(uint seed, uint frame, uint index, uint event, uint stream, uint extra)
{
  philox4x32_key_t key = {{seed, frame}};
  philox4x32_ctr_t ctr = {{index, event, stream, extra}};
  philox4x32_ctr_t r = philox4x32(ctr, key);
  Bits4 b;
  b.b0 = r.v[0];
  b.b1 = r.v[1];
  b.b2 = r.v[2];
  b.b3 = r.v[3];
  return b;
}

PM_DEVICE Uniform4 rng_uniform4_bits(Bits4 b)
{
  Uniform4 u;
  u.u0 = rng_to_unit(b.b0);
  u.u1 = rng_to_unit(b.b1);
  u.u2 = rng_to_unit(b.b2);
  u.u3 = rng_to_unit(b.b3);
  return u;
}

/* Radical inverses (the Halton sequence's coordinates) as 32-bit fixed-point fractions, so
   every compiler computes them bit for bit alike; rng_to_unit turns them into floats.
   Base 2: the index's bits mirrored about the binary point (van der Corput). */
PM_DEVICE uint radical_inverse2_bits(uint i)
{
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return i;
}

/* Base 3: the index's 20 lowest ternary digits mirrored (3^20 = 3486784401 < 2^32), then
   floor(mirrored * 2^32 / 3^20). Indices from 3^20 on repeat the sequence. */
PM_DEVICE uint radical_inverse3_bits(uint i)
{
  uint mirrored = 0u;
  for (int d = 0; d < 20; ++d) {
    mirrored = mirrored * 3u + i % 3u;
    i /= 3u;
  }
  return (uint)(((uint64_t)mirrored << 32) / (uint64_t)3486784401u);
}

#endif
