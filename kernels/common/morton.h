/* 30-bit Morton codes (10 bits per axis) of points normalised into a bounding box, for the linear
   BVH photon map (stage S4; Fabianowski & Dingliana 2009, sections 5.2 and 6.2; Lauterbach et al.
   2009). Owns only the bit interleaving and the guarded quantisation; the photon map kernels that
   use them live in photon_map.h.

   Bit order: x is the most significant axis of every 3-bit group, so
   code = ... x9 y9 z9 ... x0 y0 z0 (bit 29 = x9, bit 0 = z0).
   Degenerate bounds: an axis whose extent is zero, negative (empty box), not finite, or a NaN
   coordinate quantises to cell 0 on that axis; no division by zero reaches the result. */
#ifndef PM_MORTON_H
#define PM_MORTON_H

#include "vec3.h"

#define PM_MORTON_BITS_PER_AXIS 10
#define PM_MORTON_CELLS (1 << PM_MORTON_BITS_PER_AXIS) /* 1024 cells per axis */

/* Spreads the low 10 bits of v so that bit b moves to bit 3b (two zero bits between them). */
PM_DEVICE uint morton_expand_bits(uint v)
{
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

/* Interleaves three 10-bit cell coordinates into one 30-bit code. */
PM_DEVICE uint morton_encode(uint x, uint y, uint z)
{
  return (morton_expand_bits(x) << 2) | (morton_expand_bits(y) << 1) | morton_expand_bits(z);
}

/* Cell 0..1023 of coordinate v in [lo, hi]: floor(1024 (v - lo) / (hi - lo)), clamped so that
   v == hi lands in the last cell and points outside the box land in the border cells.
   (v - lo) / extent is at most 1 for v <= hi (rounding is monotonic), so it cannot overflow even
   for a tiny extent. A zero, negative or non-finite extent gives cell 0. A NaN ratio is caught
   by the explicit comparisons (no reliance on fmin/fmax NaN rules, which fast-math may drop). */
PM_DEVICE uint morton_quantize(float v, float lo, float hi)
{
  float extent = hi - lo;
  if (!(extent > 0.0f) || !pm_isfinite(extent)) return 0u;
  float t = (v - lo) / extent * (float)PM_MORTON_CELLS;
  if (!(t > 0.0f)) return 0u; /* also NaN */
  if (t >= (float)(PM_MORTON_CELLS - 1)) return (uint)(PM_MORTON_CELLS - 1);
  return (uint)t;
}

/* Morton code of point p in the box [lo, hi]. */
PM_DEVICE uint morton_code(Vec3 p, Vec3 lo, Vec3 hi)
{
  return morton_encode(morton_quantize(p.x, lo.x, hi.x), morton_quantize(p.y, lo.y, hi.y),
                       morton_quantize(p.z, lo.z, hi.z));
}

#endif
