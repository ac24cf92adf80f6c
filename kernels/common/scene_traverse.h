/* Per-ray traversal of the scene BVH built on the host (render/scene_bvh.h documents the node
   layout: 4 float4 per node with both child boxes stored in the parent). One private stack of
   PM_TRAVERSAL_STACK entries per ray; the builder guarantees the depth fits. Triangles whose
   material has an alpha mask (PM_TRIANGLE_MASKED in their record) are hit only where the mask
   lets them be (texture.h), so every kind of ray passes through the same holes; other
   triangles cost no more than before. */
#ifndef PM_SCENE_TRAVERSE_H
#define PM_SCENE_TRAVERSE_H

#include "kernel_globals.h"
#include "ray.h"
#include "texture.h"
#include "triangles.h"
#include "types.h"

typedef struct SceneHit {
  float t;
  int triangle; /* leaf-order index, -1 for a miss */
} SceneHit;

/* Intersects triangles [first, first + count) and narrows hit->t. Returns 1 on any hit. */
PM_DEVICE int scene_intersect_leaf(const KernelGlobals* kg, const Ray* ray, int first, int count, float t_min,
                                   SceneHit* hit)
{
  PM_GLOBAL const float4* triangles = kg->triangles;
  int found = 0;
  for (int i = first; i < first + count; ++i) {
    float4 v0 = PM_LOAD(&triangles[3 * i]);
    float t;
    if (ray_triangle(ray, vec3(v0.x, v0.y, v0.z), scene_triangle_vertex(triangles, i, 1),
                     scene_triangle_vertex(triangles, i, 2), t_min, hit->t, &t)) {
      uint record = PM_AS_UINT(v0.w);
      if ((record & PM_TRIANGLE_MASKED) &&
          !surface_alpha_visible(kg, (int)(record & PM_TRIANGLE_MATERIAL_BITS), i, vec3_madd(ray->origin, ray->direction, t)))
        continue;
      hit->t = t;
      hit->triangle = i;
      found = 1;
    }
  }
  return found;
}

/* The node after one whose children were tested: the nearer of its inner children still in front
   of the closest hit (the farther one onto the stack), else the top of the stack; -1 when nothing
   is left. A leaf hit may have shortened the ray past an inner child's entry, hence the test
   against hit_t. */
PM_DEVICE int scene_next_node(int visit_left, int visit_right, float t_left, float t_right, float hit_t,
                              int left, int right, int* stack, int* sp)
{
  visit_left = visit_left && t_left < hit_t;
  visit_right = visit_right && t_right < hit_t;
  if (visit_left && visit_right) {
    stack[(*sp)++] = t_left <= t_right ? right : left;
    return t_left <= t_right ? left : right;
  }
  if (visit_left) return left;
  if (visit_right) return right;
  return *sp == 0 ? -1 : stack[--*sp];
}

/* Closest hit in (t_min, t_max), or with any_hit set the first one found (shadow rays), among the
   triangles under inner node `root` (0: the whole scene; scene_node_holding).

   Where PM_TRAVERSE_LEAVES_TOGETHER (compat.h: CUDA and NVIDIA's OpenCL), two loops, after Aila &
   Laine 2009 ("while-while"): the inner one walks inner nodes until it reaches a node with a leaf
   child that the ray enters, the outer one intersects that node's leaves, so that a warp's lanes
   intersect their leaves together, once each has found one, instead of the few that found one at
   this step while the others wait. Measured on an H200 (docs/benchmarks.md, "Leaves intersected
   together"): the photon trace 28 %, the coverage probes 28-34 %, the path tracer 36 % and the
   final gathers 12-26 % faster than one loop. Elsewhere (PoCL, CPUs) one loop that intersects a
   node's leaf children as it meets them: there the two loops, or one loop written with shared
   helpers, made the photon trace and the coverage probes 10-27 % slower on a 2-core CPU
   (docs/benchmarks.md, "Leaves intersected together on PoCL"); the two forms are kept apart, each
   as measured. Both visit the same nodes and triangles in the same order
   (tests/unit/scene_traverse_test.cpp checks the first against one loop), so the hits are the same
   bits. scene_trace_from is the same traversal out of line. */
PM_DEVICE SceneHit scene_traverse(const KernelGlobals* kg, int root, const Ray* ray, float t_min, float t_max,
                                  int any_hit)
{
  PM_GLOBAL const float4* nodes = kg->scene_nodes;
  SceneHit hit;
  hit.t = t_max;
  hit.triangle = -1;
  int stack[PM_TRAVERSAL_STACK];
  int sp = 0;
  int node = root;
#if PM_TRAVERSE_LEAVES_TOGETHER
  while (node >= 0) {
    int child[2];
    int count[2];
    float t_left, t_right;
    int visit_left, visit_right;
    /* Inner nodes, until one has a leaf child the ray enters (node stays on it) or none is left. */
    for (;;) {
      float4 n0 = PM_LOAD(&nodes[4 * node + 0]);
      float4 n1 = PM_LOAD(&nodes[4 * node + 1]);
      float4 n2 = PM_LOAD(&nodes[4 * node + 2]);
      float4 n3 = PM_LOAD(&nodes[4 * node + 3]);
      child[0] = PM_AS_INT(n3.x);
      child[1] = PM_AS_INT(n3.y);
      count[0] = PM_AS_INT(n3.z);
      count[1] = PM_AS_INT(n3.w);
      t_left = ray_box_entry(ray, vec3(n0.x, n0.z, n2.x), vec3(n0.y, n0.w, n2.y), hit.t);
      t_right = ray_box_entry(ray, vec3(n1.x, n1.z, n2.z), vec3(n1.y, n1.w, n2.w), hit.t);
      visit_left = t_left < 1e38f && child[0] >= 0;
      visit_right = t_right < 1e38f && child[1] >= 0;
      if ((visit_left && count[0] > 0) || (visit_right && count[1] > 0)) break;
      node = scene_next_node(visit_left, visit_right, t_left, t_right, hit.t, child[0], child[1], stack, &sp);
      if (node < 0) break;
    }
    if (node < 0) break;
    /* Leaves are intersected from their parent; only inner nodes go on the stack. */
    if (visit_left && count[0] > 0) {
      if (scene_intersect_leaf(kg, ray, child[0], count[0], t_min, &hit) && any_hit) return hit;
      visit_left = 0;
    }
    if (visit_right && count[1] > 0) {
      if (scene_intersect_leaf(kg, ray, child[1], count[1], t_min, &hit) && any_hit) return hit;
      visit_right = 0;
    }
    node = scene_next_node(visit_left, visit_right, t_left, t_right, hit.t, child[0], child[1], stack, &sp);
  }
#else
  for (;;) {
    float4 n0 = PM_LOAD(&nodes[4 * node + 0]);
    float4 n1 = PM_LOAD(&nodes[4 * node + 1]);
    float4 n2 = PM_LOAD(&nodes[4 * node + 2]);
    float4 n3 = PM_LOAD(&nodes[4 * node + 3]);
    int child[2];
    int count[2];
    child[0] = PM_AS_INT(n3.x);
    child[1] = PM_AS_INT(n3.y);
    count[0] = PM_AS_INT(n3.z);
    count[1] = PM_AS_INT(n3.w);
    float t_left = ray_box_entry(ray, vec3(n0.x, n0.z, n2.x), vec3(n0.y, n0.w, n2.y), hit.t);
    float t_right = ray_box_entry(ray, vec3(n1.x, n1.z, n2.z), vec3(n1.y, n1.w, n2.w), hit.t);
    int visit_left = t_left < 1e38f && child[0] >= 0;
    int visit_right = t_right < 1e38f && child[1] >= 0;

    /* Leaves are intersected at once; only inner nodes go on the stack. */
    if (visit_left && count[0] > 0) {
      if (scene_intersect_leaf(kg, ray, child[0], count[0], t_min, &hit) && any_hit) return hit;
      visit_left = 0;
    }
    if (visit_right && count[1] > 0) {
      if (scene_intersect_leaf(kg, ray, child[1], count[1], t_min, &hit) && any_hit) return hit;
      visit_right = 0;
    }
    /* A leaf hit may have shortened the ray past an inner child's entry. */
    visit_left = visit_left && t_left < hit.t;
    visit_right = visit_right && t_right < hit.t;

    if (visit_left && visit_right) {
      int near_child = t_left <= t_right ? child[0] : child[1];
      int far_child = t_left <= t_right ? child[1] : child[0];
      stack[sp++] = far_child;
      node = near_child;
    } else if (visit_left) {
      node = child[0];
    } else if (visit_right) {
      node = child[1];
    } else {
      if (sp == 0) break;
      node = stack[--sp];
    }
  }
#endif
  return hit;
}

/* scene_traverse as a function of its own on CUDA and NVIDIA's OpenCL (PM_DEVICE_CALLED), with its
   own registers: inlined, it shares the 64 registers of kernels that do much else (the camera
   pass, the photon trace, the path tracer, the final gathers) and spills into their loops; inlined
   there, the two loops made the final gather over photons 12-16 % slower than one loop, out of line
   12-16 % faster. The coverage probes, which do little but trace, inline it (footprint_coverage.h). */
PM_DEVICE_CALLED SceneHit scene_trace_from(const KernelGlobals* kg, int root, const Ray* ray, float t_min,
                                           float t_max, int any_hit)
{
  return scene_traverse(kg, root, ray, t_min, t_max, any_hit);
}

PM_DEVICE SceneHit scene_trace(const KernelGlobals* kg, const Ray* ray, float t_min, float t_max, int any_hit)
{
  return scene_trace_from(kg, 0, ray, t_min, t_max, any_hit);
}

/* Whether box [lo, hi] meets the box [b_lo, b_hi] (an empty child's inverted box meets nothing). */
PM_DEVICE int scene_boxes_meet(Vec3 lo, Vec3 hi, Vec3 b_lo, Vec3 b_hi)
{
  return b_lo.x <= hi.x && b_lo.y <= hi.y && b_lo.z <= hi.z && lo.x <= b_hi.x && lo.y <= b_hi.y && lo.z <= b_hi.z;
}

/* The deepest inner node under which lie all the triangles whose boxes meet [lo, hi]: from the
   root down while exactly one child's box meets it and that child is an inner node. Rays that
   stay inside [lo, hi] find from there what they find from the root, since they can enter no
   box that they skip, with none of the descent: the footprint's coverage probes, tens of short
   rays in one small box, start there (footprint_probes.h). */
PM_DEVICE int scene_node_holding(const KernelGlobals* kg, Vec3 lo, Vec3 hi)
{
  PM_GLOBAL const float4* nodes = kg->scene_nodes;
  int node = 0;
  for (int level = 0; level < PM_TRAVERSAL_STACK; ++level) {
    float4 n0 = PM_LOAD(&nodes[4 * node + 0]);
    float4 n1 = PM_LOAD(&nodes[4 * node + 1]);
    float4 n2 = PM_LOAD(&nodes[4 * node + 2]);
    float4 n3 = PM_LOAD(&nodes[4 * node + 3]);
    int left = scene_boxes_meet(lo, hi, vec3(n0.x, n0.z, n2.x), vec3(n0.y, n0.w, n2.y));
    int right = scene_boxes_meet(lo, hi, vec3(n1.x, n1.z, n2.z), vec3(n1.y, n1.w, n2.w));
    if (left == right) return node; /* both, or neither (nothing there to find) */
    int child = PM_AS_INT(left ? n3.x : n3.y), count = PM_AS_INT(left ? n3.z : n3.w);
    if (count > 0 || child < 0) return node; /* a leaf is intersected from its parent */
    node = child;
  }
  return node;
}

#endif
