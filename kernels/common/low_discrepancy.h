/* Low-discrepancy points for final gathering's first bounce (final_gather.h): the first two
   dimensions of Sobol's sequence, randomised by Owen's nested uniform scrambling. (The path
   tracer and the error control keep independent numbers: docs/final-gathering.md.)

   Why: a pixel's final-gathered light is an integral over the shading point's hemisphere, two
   numbers a ray. Independent rays lower its error as n^-1/2; the points of a scrambled
   (0,2)-sequence lower it as about n^-3/4 where the integrand is smooth but for edges
   (visibility, shadow boundaries), n^-1 where it is smooth (Owen 1997,
   "Scrambled net variance for integrals of smooth functions"), and never worse than independent
   rays by more than a constant (Owen 1997, "Monte Carlo variance of scrambled net quadrature":
   the variance of a scrambled (0,m,2)-net in base 2 is at most twice independent points').

   Sobol's first two dimensions form a (0,2)-sequence in base 2 (Sobol 1967; Niederreiter 1992,
   section 4.5): every 2^m consecutive points from a multiple of 2^m form a (0,m,2)-net, one
   point in each of the 2^m elementary intervals [a 2^-j, (a+1) 2^-j) x [b 2^-(m-j), (b+1)
   2^-(m-j)). Dimension 0 is the van der Corput sequence (the index's bits mirrored); dimension 1
   XORs the direction numbers v_k = v_(k-1) XOR (v_(k-1) >> 1), v_1 = 1/2 (primitive polynomial
   x + 1), one per set bit of the index.

   Owen's scrambling (Owen 1995, "Randomly permuted (t,m,s)-nets and (t,s)-sequences") flips each
   binary digit of a coordinate by a random bit that depends on the digits before it: each point
   is then uniform on [0, 1)^2 (the estimate stays unbiased), and a net stays a net. With the
   digits mirrored (digit k at bit k), an integer map whose bit k depends only on bits 0..k of
   its input, flipping bit k by a function of the bits below it, is such a scrambling of every
   digit at once (Laine and Karras 2011, "Stratified sampling for stochastic transparency";
   Burley 2020, "Practical hash-based Owen scrambling"): adding a key, multiplying by an odd
   number, and x ^= x * c for an even c all are. The map here chains five of those, two of them
   keyed (the constants and the order of Vegdahl 2021, "Building a better LK hash", whose keyed
   multiply brings the key's high bits into the first digits' flips). A scramble is so a pure
   function of its key, the same on every backend, at about ten integer operations a coordinate
   where hashing each digit on its own took 24 hashes.

   Coherent rays (Sadeghi, Chen and Jensen 2009, "Coherent path tracing", share random numbers
   between pixels for the same reason): the first PM_TILE_SHARED_DIGITS digits of each coordinate
   are scrambled under the pixel's tile's key (pixel_order.h: the 8 x 4 pixels a GPU warp
   shades), the rest under the pixel's own. Ray s of a pass then leaves every pixel of a warp
   into the same 2^-4 x 2^-4 cell of the square, about the same direction about each normal, so
   the warp's rays walk the scene's tree and read the cache together. Each pixel's points are
   still an Owen-scrambled net (each digit's flip is a random bit; which key gave it does not
   matter to one pixel), so a pixel's estimate and its error are what they were. Pixels of a tile
   share only which cells their points lie in: given the tile's scramble, a point is uniform in
   its cell, so their errors share at most the net's error on the cells' averages, and none once
   a replicate has 2^8 points (sixteen passes of 16 rays: its points then fill every 2^-4 x 2^-4
   cell once, an elementary interval of area 2^-8, and the cells' averages integrate exactly).

   Replicates: a frame's passes alternate between two independently scrambled sequences (even
   passes the first, odd passes the second, each pass the next block of its own). The even and
   odd passes' means are then independent estimates, as with independent rays, so the frame's own
   noise is still read from their difference (render/bias_control.cpp, the film's variance from
   its even and odd passes): one scrambled sequence would make the halves' difference larger than
   the whole's error and the bias read beside it too small. */
#ifndef PM_LOW_DISCREPANCY_H
#define PM_LOW_DISCREPANCY_H

#include "rng.h"

/* Sobol's second dimension of index i with its digits mirrored (digit k at bit k): the
   direction numbers, mirrored, are w_1 = 1, w_k = w_(k-1) XOR (w_(k-1) << 1). */
PM_DEVICE uint sobol_dimension1_mirrored(uint i)
{
  uint w = 1u, x = 0u;
  for (; i != 0u; i >>= 1, w ^= w << 1)
    if (i & 1u) x ^= w;
  return x;
}

/* Sobol's second dimension of index i, as a 32-bit fraction. */
PM_DEVICE uint sobol_dimension1_bits(uint i)
{
  return radical_inverse2_bits(sobol_dimension1_mirrored(i)); /* mirrors the bits back */
}

/* Digits of each coordinate scrambled under the tile's key rather than the pixel's own (above). */
#define PM_TILE_SHARED_DIGITS 4u

/* Owen's nested scrambling of mirrored digits (digit k at bit k) under `key`: each step keeps
   bit k a function of bits 0..k, so digit k is flipped by a function of the key and the digits
   before it (above). The flips come from one hash rather than from an independent random bit for
   every node of the digit tree; the points integrate as well (docs/final-gathering.md, "One hash
   a coordinate"). */
PM_DEVICE uint owen_scramble_mirrored(uint x, uint key)
{
  x ^= x * 0x3d20adeau;
  x += key;
  x *= (key >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

/* The fraction whose mirrored digits are `mirrored`, Owen-scrambled: the digits k < shared_digits
   under shared_key, the others under key; a 32-bit fraction. Each part is a nested scrambling
   of the same digits, so the whole is one. */
PM_DEVICE uint owen_scramble_mirrored_split(uint mirrored, uint shared_key, uint shared_digits, uint key)
{
  uint shared_mask = (1u << shared_digits) - 1u;
  uint scrambled = (owen_scramble_mirrored(mirrored, shared_key) & shared_mask) |
                   (owen_scramble_mirrored(mirrored, key) & ~shared_mask);
  return radical_inverse2_bits(scrambled); /* the digits back in place */
}

/* The same for a 32-bit fraction x. */
PM_DEVICE uint owen_scramble_bits_split(uint x, uint shared_key, uint shared_digits, uint key)
{
  return owen_scramble_mirrored_split(radical_inverse2_bits(x), shared_key, shared_digits, key);
}

/* Point `index` of the sequence scrambled as a pixel's replicate is, one key a dimension for the
   first PM_TILE_SHARED_DIGITS digits (tile_key0, tile_key1) and one for the rest (key0, key1); in
   [0, 1)^2. */
PM_DEVICE void scrambled_sobol2(uint index, uint tile_key0, uint tile_key1, uint key0, uint key1, float* u0, float* u1)
{
  /* Dimension 0 is the van der Corput sequence: its mirrored digits are the index itself. */
  *u0 = rng_to_unit(owen_scramble_mirrored_split(index, tile_key0, PM_TILE_SHARED_DIGITS, key0));
  *u1 = rng_to_unit(owen_scramble_mirrored_split(sobol_dimension1_mirrored(index), tile_key1, PM_TILE_SHARED_DIGITS, key1));
}

/* The scrambles of a pixel's two replicates, the same in every pass of the frame: each four
   random words, b0, b1 replicate 0's two dimensions, b2, b3 replicate 1's; `tile`'s for the first
   PM_TILE_SHARED_DIGITS digits (the same for every pixel of the tile), `own` for the rest. */
typedef struct FirstBounceKeys {
  Bits4 tile, own;
} FirstBounceKeys;

/* The first bounce's 2D point of ray `ray` of pass `pass` (rays_per_pass a pass), from the
   replicate of the pass's parity: pass 2j + r draws points j * rays_per_pass .. of replicate r. */
PM_DEVICE void first_bounce_point(FirstBounceKeys keys, uint pass, uint rays_per_pass, uint ray, float* u0, float* u1)
{
  uint index = (pass >> 1) * rays_per_pass + ray;
  if (pass & 1u)
    scrambled_sobol2(index, keys.tile.b2, keys.tile.b3, keys.own.b2, keys.own.b3, u0, u1);
  else
    scrambled_sobol2(index, keys.tile.b0, keys.tile.b1, keys.own.b0, keys.own.b1, u0, u1);
}

/* A lobe chosen by the point's first coordinate, which is then stretched back over [0, 1): the
   diffuse lobe below p_diffuse. So each lobe's directions keep the points' spread (a separate
   random number per ray would hand each lobe a random subset of them). Returns 1 for glossy. */
PM_DEVICE int first_bounce_lobe(float p_diffuse, float* u0)
{
  if (*u0 < p_diffuse) {
    *u0 = pm_fminf(*u0 / p_diffuse, 0.99999994f);
    return 0;
  }
  *u0 = pm_fminf((*u0 - p_diffuse) / (1.0f - p_diffuse), 0.99999994f);
  return 1;
}

#endif
