/* Coherent, stratified photon emission (S1). The multi-pass GPU photon map paper traces photons
   in groups of 32 with nearby directions so that a warp's rays stay together. Here the n photons a
   light emits in a pass each own one stratum of the unit square of emission parameters (u, v)
   (eq. 2's cos(theta) and phi): photon i takes t uniform in [i/n, (i+1)/n), and t runs along a
   Hilbert curve through a 1024 x 1024 grid of cells, so consecutive photons, the lanes of one
   warp, leave in neighbouring directions. t uniform over [0, 1) lands uniformly in the square (the
   curve visits every cell once, each for 1/2^20 of t, and the point is jittered uniformly inside
   its cell), so the photons are a stratified sample of the same distribution as independent
   uniform ones: unbiased, with less variance. */
#ifndef PM_EMISSION_ORDER_H
#define PM_EMISSION_ORDER_H

#include "types.h"

#define PM_HILBERT_LEVELS 10u /* 2^10 x 2^10 cells */

/* Cell (x, y) at distance d along the Hilbert curve of a 2^levels square (the classic iterative
   decoding: each level places one quadrant and rotates the rest). */
PM_DEVICE void hilbert_cell(uint d, uint levels, uint* x_out, uint* y_out)
{
  uint x = 0u, y = 0u;
  for (uint s = 1u; s < (1u << levels); s <<= 1) {
    uint rx = 1u & (d >> 1);
    uint ry = 1u & (d ^ rx);
    if (ry == 0u) {
      if (rx == 1u) {
        x = s - 1u - x;
        y = s - 1u - y;
      }
      uint t = x;
      x = y;
      y = t;
    }
    x += s * rx;
    y += s * ry;
    d >>= 2;
  }
  *x_out = x;
  *y_out = y;
}

/* Photon i of n (i < n): a point of its stratum, uniform within it, from three random words. */
PM_DEVICE void stratified_emission(uint i, uint n, uint stratum_bits, uint jitter_u_bits, uint jitter_v_bits,
                                   float* u, float* v)
{
  const uint cells_log2 = 2u * PM_HILBERT_LEVELS;
  /* d = floor((i + xi) 2^20 / n), xi with 20 bits: exact in 64-bit integers. */
  uint64_t scaled = ((uint64_t)i << cells_log2) + (uint64_t)(stratum_bits >> (32u - cells_log2));
  uint d = (uint)(scaled / (uint64_t)n);
  uint x, y;
  hilbert_cell(d, PM_HILBERT_LEVELS, &x, &y);
  /* 24-bit fixed point: 10 bits of cell, 14 of jitter; always below 1. */
  *u = (float)((x << 14) | (jitter_u_bits >> 18)) * (1.0f / 16777216.0f);
  *v = (float)((y << 14) | (jitter_v_bits >> 18)) * (1.0f / 16777216.0f);
}

#endif
