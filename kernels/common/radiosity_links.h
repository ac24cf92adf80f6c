/* Vertex link radiosity, link generation (section 3.2), one batch of elements at a time:
   1. trace: from every element nC cosine-weighted directions; a ray that hits the refined
      triangle (A, B, C) at x = uA + vB + wC becomes three links, to A, B and C, weighted by
      their barycentric coordinates over nC (which keeps the energy balance);
   2. merge: an element's links to the same element are combined into one (the paper's
      compression, done there on the CPU), sorted by target;
   3. store: the merged links are written compactly (target, 16-bit weight) at the offsets the
      host computed from the merged counts.
   Link weights w carry the visibility and geometry terms of eq. 3: with cosine-weighted
   directions, the irradiance an element gathers is E = pi * sum_links w * L_target, and its
   weights sum to the fraction of its rays that hit something (1 in a closed scene), i.e. pi
   times them is the hemisphere integral of cos theta. */
#ifndef PM_RADIOSITY_LINKS_H
#define PM_RADIOSITY_LINKS_H

#include "radiosity_mesh.h"

/* Quantisation of a link weight in [0, 1]. */
#define PM_RADIOSITY_WEIGHT_SCALE 65535.0f

PM_DEVICE void radiosity_put_entry(const KernelGlobals* kg, uint entry, uint target, float weight)
{
  kg->rad_batch_links[2u * entry] = target;
  kg->rad_batch_links[2u * entry + 1u] = PM_AS_UINT(weight);
}

/* One work item per (element of the batch, direction): entries [3 index, 3 index + 3). */
PM_DEVICE void kernel_radiosity_link_trace(const KernelGlobals* kg, const LaunchParams* p, uint index)
{
  uint nc = p->link_directions;
  uint e = p->batch_first + index / nc;
  uint k = index % nc;
  uint entry = 3u * index;
  for (uint c = 0; c < 3u; ++c) radiosity_put_entry(kg, entry + c, PM_RADIOSITY_NONE, 0.0f);

  Vec3 pos = radiosity_element_position(kg, e), n = radiosity_element_normal(kg, e);
  Vec3 d = radiosity_world_direction(n, e, k, nc);
  Ray ray = ray_make(offset_ray_origin(pos, n), d);
  SceneHit hit = scene_trace(kg->scene_nodes, kg->triangles, &ray, 0.0f, 1e30f, 0);
  if (hit.triangle < 0) return;
  Vec3 x = vec3_madd(ray.origin, d, hit.t);
  uint targets[3];
  /* The side of the hit surface that faces the ray's origin. */
  RadiosityLocation loc = radiosity_surface_point(kg, hit.triangle, x, vec3_neg(d), targets);
  float scale = 1.0f / (float)nc;
  for (uint c = 0; c < 3u; ++c)
    if (targets[c] != PM_RADIOSITY_NONE && loc.w[c] > 0.0f) radiosity_put_entry(kg, entry + c, targets[c], loc.w[c] * scale);
}

PM_DEVICE uint radiosity_entry_target(const KernelGlobals* kg, uint entry) { return kg->rad_batch_links[2u * entry]; }

PM_DEVICE void radiosity_swap_entries(const KernelGlobals* kg, uint a, uint b)
{
  uint t = kg->rad_batch_links[2u * a], w = kg->rad_batch_links[2u * a + 1u];
  kg->rad_batch_links[2u * a] = kg->rad_batch_links[2u * b];
  kg->rad_batch_links[2u * a + 1u] = kg->rad_batch_links[2u * b + 1u];
  kg->rad_batch_links[2u * b] = t;
  kg->rad_batch_links[2u * b + 1u] = w;
}

/* Moves entry `root` down the max-heap of entries [base, base + end) by target. */
PM_DEVICE void radiosity_sift_down(const KernelGlobals* kg, uint base, uint root, uint end)
{
  for (;;) {
    uint child = 2u * root + 1u;
    if (child >= end) return;
    if (child + 1u < end && radiosity_entry_target(kg, base + child) < radiosity_entry_target(kg, base + child + 1u))
      ++child;
    if (radiosity_entry_target(kg, base + root) >= radiosity_entry_target(kg, base + child)) return;
    radiosity_swap_entries(kg, base + root, base + child);
    root = child;
  }
}

/* Heap sort of entries [base, base + count) by target, in place: no scratch memory, and
   O(n log n) whatever the order the rays produced. */
PM_DEVICE void radiosity_sort_entries(const KernelGlobals* kg, uint base, uint count)
{
  for (uint start = count / 2u; start > 0u; --start) radiosity_sift_down(kg, base, start - 1u, count);
  for (uint end = count; end > 1u; --end) {
    radiosity_swap_entries(kg, base, base + end - 1u);
    radiosity_sift_down(kg, base, 0u, end - 1u);
  }
}

/* One work item per element of the batch: sorts its 3 nC entries by target, sums the weights of
   equal targets into the first entries, and counts merged and raw (valid) links. */
PM_DEVICE void kernel_radiosity_link_merge(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint count = 3u * p->link_directions;
  uint base = item * count;
  radiosity_sort_entries(kg, base, count);
  uint merged = 0, raw = 0;
  for (uint j = 0; j < count; ++j) {
    uint target = radiosity_entry_target(kg, base + j);
    if (target == PM_RADIOSITY_NONE) break; /* empty entries sort last */
    float w = PM_AS_FLOAT(kg->rad_batch_links[2u * (base + j) + 1u]);
    ++raw;
    if (merged > 0u && radiosity_entry_target(kg, base + merged - 1u) == target) {
      uint slot = 2u * (base + merged - 1u) + 1u;
      kg->rad_batch_links[slot] = PM_AS_UINT(PM_AS_FLOAT(kg->rad_batch_links[slot]) + w);
    } else {
      radiosity_put_entry(kg, base + merged, target, w);
      ++merged;
    }
  }
  kg->rad_batch_counts[4u * item] = merged;
  kg->rad_batch_counts[4u * item + 1u] = raw;
}

/* Unorm16 weight of merged link j, rounded so that the element's weights keep their sum: each
   is the difference of the rounded running sums (error diffusion), never off by a whole unit. */
PM_DEVICE uint radiosity_quantised_weight(float sum_before, float w)
{
  float lo = pm_floorf(sum_before * PM_RADIOSITY_WEIGHT_SCALE + 0.5f);
  float hi = pm_floorf((sum_before + w) * PM_RADIOSITY_WEIGHT_SCALE + 0.5f);
  float q = hi - lo;
  return q <= 0.0f ? 0u : (q >= PM_RADIOSITY_WEIGHT_SCALE ? 65535u : (uint)q);
}

/* One work item per element of the batch: its merged links to rad_link_targets/weights from the
   offset in rad_batch_counts (even, so no two elements share a weight word); an odd count is
   padded by a zero-weight link to the element itself. */
PM_DEVICE void kernel_radiosity_link_store(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint count = 3u * p->link_directions;
  uint base = item * count;
  uint merged = kg->rad_batch_counts[4u * item];
  uint offset = kg->rad_batch_counts[4u * item + 2u];
  uint e = p->batch_first + item;
  float sum = 0.0f;
  uint packed = 0u;
  for (uint j = 0; j < merged + (merged & 1u); ++j) {
    uint target = e, q = 0u;
    if (j < merged) {
      float w = PM_AS_FLOAT(kg->rad_batch_links[2u * (base + j) + 1u]);
      target = radiosity_entry_target(kg, base + j);
      q = radiosity_quantised_weight(sum, w);
      sum += w;
    }
    kg->rad_link_targets[offset + j] = target;
    if ((j & 1u) == 0u) packed = q;
    else kg->rad_link_weights[(offset + j) >> 1] = packed | (q << 16);
  }
}

/* Weight of link j as a fraction (its unorm16 value / 65535). */
PM_DEVICE float radiosity_link_weight(PM_GLOBAL const uint* weights, uint j)
{
  uint word = PM_LOAD(&weights[j >> 1]);
  return (float)((j & 1u) ? (word >> 16) : (word & 0xffffu)) * (1.0f / PM_RADIOSITY_WEIGHT_SCALE);
}

#endif
