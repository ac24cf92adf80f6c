/* Vertex link radiosity, link generation (section 3.2), one batch of elements at a time:
   1. trace: from every element nC cosine-weighted directions; a ray that hits the refined
      triangle (A, B, C) at x = uA + vB + wC becomes three links, to A, B and C, weighted by
      their barycentric coordinates over nC (which keeps the energy balance);
   2. merge: an element's links to the same element are combined into one (the paper's
      compression, done there on the CPU), sorted by target;
   3. store: the merged links are written compactly (a target delta and a 16-bit weight in one
      word, below) at the offsets the host computed from the counts.
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

/* Where link ray k of element e starts and the normal of the surface there (its hemisphere).
   PM_RADIOSITY_ORIGINS_VERTEX: the vertex, the paper's choice. Its point value is the vertex's
   irradiance, which is wrong for the area the vertex's hat function interpolates over wherever
   the vertex is not a typical point of it: at a concave edge (a floor vertex at the foot of a
   wall starts its rays in the wall's plane, and those towards the wall pass through it at t = 0
   and gather the back of the scene) and where meshes interpenetrate (a floor vertex under a
   column sees the column's inside, dark).
   PM_RADIOSITY_ORIGINS_ONE_RING: a point of the one-ring drawn with density proportional to
   the vertex's hat function phi_v (a triangle in proportion to its area, then the barycentric
   weight b_v of the vertex distributed as the median of three uniforms, CDF 3b^2 - 2b^3, which
   is the marginal of a density proportional to b_v; the other two weights uniform on what
   remains), with the triangle's own normal. With cosine-weighted directions the vertex then
   gathers E_v = integral phi_v E dA / integral phi_v dA, the projection whose linear
   interpolation carries the irradiance's power over the surface (as the light links' one-ring
   integration does for the direct light; radiosity_light.h). No origin lies on an edge of the
   mesh, and only the part of the one-ring that is inside other geometry gathers its darkness. */
PM_DEVICE Vec3 radiosity_link_origin(const KernelGlobals* kg, const LaunchParams* p, uint e, uint k, Vec3* normal)
{
  Vec3 v = radiosity_element_position(kg, e);
  *normal = radiosity_element_normal(kg, e);
  if (p->link_origins != PM_RADIOSITY_ORIGINS_ONE_RING) return v;
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).x, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).x;
  float total = 0.0f;
  for (uint r = first; r < end; ++r) {
    Vec3 b, c, face_n;
    total += radiosity_ring_triangle(kg, e, PM_LOAD(&kg->rad_adjacency[r]), &b, &c, &face_n);
  }
  if (!(total > 0.0f)) return v; /* no area around the vertex: the vertex alone */
  Uniform4 u = rng_uniform4(0u, k, e, 1u, PM_STREAM_RADIOSITY) /* event 0: the rotation */;
  float pick = u.u0 * total;
  for (uint r = first; r < end; ++r) {
    Vec3 b, c, face_n;
    float twice_area = radiosity_ring_triangle(kg, e, PM_LOAD(&kg->rad_adjacency[r]), &b, &c, &face_n);
    if (!(twice_area > 0.0f)) continue;
    if (pick >= twice_area && r + 1u < end) { pick -= twice_area; continue; }
    /* The median of three uniforms; what remains of u0 within this triangle splits the rest. */
    float w_v = pm_fmaxf(pm_fminf(u.u1, u.u2), pm_fminf(pm_fmaxf(u.u1, u.u2), u.u3));
    float split = pm_fminf(pm_fmaxf(pick / twice_area, 0.0f), 1.0f);
    float w_b = (1.0f - w_v) * split;
    *normal = face_n;
    return vec3_add(vec3_add(vec3_scale(v, w_v), vec3_scale(b, w_b)), vec3_scale(c, 1.0f - w_v - w_b));
  }
  return v;
}

/* Hidden origins. Closed objects are wound with their front faces outwards, into the air, as
   modelling tools leave them for renderers that cull back faces. A link ray that starts on the
   front side of its surface (in the air, by that surface's account) and meets the back of a
   triangle (inside a solid, by that one's) close to its origin started inside a closed object
   that crosses its surface: a floor point under a chair's leg, a one-ring reaching into a wall.
   That part of the one-ring is never seen, and what its rays gather (the object's dark inside)
   must not enter the vertex's value. Rays from the back side of a surface are never taken as
   hidden: a room wound outwards is seen from its back sides, and its corners would be. */

/* Whether a ray along d meets triangle `leaf` from behind its winding. */
PM_DEVICE int radiosity_hits_back_face(const KernelGlobals* kg, int leaf, Vec3 d)
{
  Vec3 a = scene_triangle_vertex(kg->triangles, leaf, 0);
  Vec3 b = scene_triangle_vertex(kg->triangles, leaf, 1);
  Vec3 c = scene_triangle_vertex(kg->triangles, leaf, 2);
  return vec3_dot(vec3_cross(vec3_sub(b, a), vec3_sub(c, a)), d) > 0.0f;
}

/* Whether element e lies on the front (winding) side of its surface: its first non-degenerate
   one-ring triangle's winding normal (the ring's corners follow the winding) against the
   element's normal. All of an element's ring triangles are on its one side. */
PM_DEVICE int radiosity_element_on_front(const KernelGlobals* kg, uint e)
{
  uint first = PM_LOAD(&kg->rad_element_ranges[e]).x, end = PM_LOAD(&kg->rad_element_ranges[e + 1u]).x;
  Vec3 v = radiosity_element_position(kg, e);
  for (uint r = first; r < end; ++r) {
    Vec3 b, c, face_n;
    if (!(radiosity_ring_triangle(kg, e, PM_LOAD(&kg->rad_adjacency[r]), &b, &c, &face_n) > 0.0f)) continue;
    return vec3_dot(vec3_cross(vec3_sub(b, v), vec3_sub(c, v)), face_n) > 0.0f;
  }
  return 0;
}

/* One work item per (element of the batch, direction): entries [3 index, 3 index + 3). */
PM_DEVICE void kernel_radiosity_link_trace(const KernelGlobals* kg, const LaunchParams* p, uint index)
{
  uint nc = p->link_directions;
  uint e = p->batch_first + index / nc;
  uint k = index % nc;
  uint entry = 3u * index;
  for (uint c = 0; c < 3u; ++c) radiosity_put_entry(kg, entry + c, PM_RADIOSITY_NONE, 0.0f);

  Vec3 n;
  Vec3 pos = radiosity_link_origin(kg, p, e, k, &n);
  Vec3 d = radiosity_world_direction(n, e, k, nc);
  Ray ray = ray_make(offset_ray_origin(pos, n, ray_offset_distance(pos, 0.0f, p->ray_epsilon)), d);
  SceneHit hit = scene_trace(kg, &ray, 0.0f, 1e30f, 0);
  if (hit.triangle < 0) return;
  if (hit.t < p->link_hidden_distance && radiosity_hits_back_face(kg, hit.triangle, d) &&
      radiosity_element_on_front(kg, e)) {
    radiosity_put_entry(kg, entry, PM_RADIOSITY_HIDDEN, 0.0f);
    return;
  }
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

/* Links are stored as one 32-bit word each, per element sorted by target: the high 16 bits are
   the target's distance from the previous link's target (from 0 for the first), the low 16 bits
   the weight as unorm16. A distance that does not fit (0xffff or more) is written as 0xffff and
   the target follows in a word of its own. Elements are in Morton order, so an element's targets
   are usually close together: most links take 4 bytes instead of 8 (target + float weight). */
#define PM_RADIOSITY_LINK_ESCAPE 0xffffu

/* Words link `target` takes after a link to `previous`. */
PM_DEVICE uint radiosity_link_words(uint previous, uint target)
{
  return target - previous >= PM_RADIOSITY_LINK_ESCAPE ? 2u : 1u;
}

/* One work item per element of the batch: sorts its 3 nC entries by target, sums the weights of
   equal targets into the first entries, and counts the words they will take, the raw (valid)
   entries and the merged links. */
PM_DEVICE void kernel_radiosity_link_merge(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint count = 3u * p->link_directions;
  uint base = item * count;
  radiosity_sort_entries(kg, base, count);
  uint merged = 0, raw = 0, words = 0, previous = 0, hidden = 0;
  for (uint j = 0; j < count; ++j) {
    uint target = radiosity_entry_target(kg, base + j);
    if (target == PM_RADIOSITY_NONE) break; /* empty entries sort last */
    if (target == PM_RADIOSITY_HIDDEN) {
      ++hidden;
      continue;
    }
    float w = PM_AS_FLOAT(kg->rad_batch_links[2u * (base + j) + 1u]);
    ++raw;
    if (merged > 0u && previous == target) {
      uint slot = 2u * (base + merged - 1u) + 1u;
      kg->rad_batch_links[slot] = PM_AS_UINT(PM_AS_FLOAT(kg->rad_batch_links[slot]) + w);
    } else {
      words += radiosity_link_words(previous, target);
      radiosity_put_entry(kg, base + merged, target, w);
      previous = target;
      ++merged;
    }
  }
  /* The rays from the visible part of the one-ring stand for all of it: their weights over the
     visible rays, so the vertex's value is the mean over the part of its one-ring that is seen. */
  if (hidden > 0u && hidden < p->link_directions) {
    float scale = (float)p->link_directions / (float)(p->link_directions - hidden);
    for (uint j = 0; j < merged; ++j) {
      uint slot = 2u * (base + j) + 1u;
      kg->rad_batch_links[slot] = PM_AS_UINT(PM_AS_FLOAT(kg->rad_batch_links[slot]) * scale);
    }
  }
  kg->rad_batch_counts[4u * item] = words;
  kg->rad_batch_counts[4u * item + 1u] = raw;
  kg->rad_batch_counts[4u * item + 2u] = hidden; /* read by the host before it writes the offset */
  kg->rad_batch_counts[4u * item + 3u] = merged;
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

/* One work item per element of the batch: its merged links, encoded, into rad_links from the
   word offset the host put in rad_batch_counts. */
PM_DEVICE void kernel_radiosity_link_store(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  uint base = item * 3u * p->link_directions;
  uint merged = kg->rad_batch_counts[4u * item + 3u];
  uint out = kg->rad_batch_counts[4u * item + 2u];
  float sum = 0.0f;
  uint previous = 0;
  for (uint j = 0; j < merged; ++j) {
    float w = PM_AS_FLOAT(kg->rad_batch_links[2u * (base + j) + 1u]);
    uint target = radiosity_entry_target(kg, base + j);
    uint q = radiosity_quantised_weight(sum, w);
    sum += w;
    if (radiosity_link_words(previous, target) == 1u) {
      kg->rad_links[out++] = ((target - previous) << 16) | q;
    } else {
      kg->rad_links[out++] = (PM_RADIOSITY_LINK_ESCAPE << 16) | q;
      kg->rad_links[out++] = target;
    }
    previous = target;
  }
}

/* Decodes the link at word *at (advancing it past the link): its target after `previous`, and
   its weight as a fraction (the unorm16 value / 65535). */
PM_DEVICE uint radiosity_next_link(PM_GLOBAL const uint* links, uint* at, uint previous, float* weight)
{
  uint word = PM_LOAD(&links[*at]);
  *at += 1u;
  *weight = (float)(word & 0xffffu) * (1.0f / PM_RADIOSITY_WEIGHT_SCALE);
  uint delta = word >> 16;
  if (delta != PM_RADIOSITY_LINK_ESCAPE) return previous + delta;
  uint target = PM_LOAD(&links[*at]);
  *at += 1u;
  return target;
}

#endif
