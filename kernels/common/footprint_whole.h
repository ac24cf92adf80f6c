/* Footprints wholly on their own surface (stage S3): the coverage probes' answer known without
   tracing them. A footprint whose ellipse lies on the flat surface its photon hit, with nothing
   over it, is covered everywhere: each of its probe rays (footprint_coverage.h) comes down along
   -n from above the ellipse and meets that surface first, one the gather accepts (it is the
   photon's own plane), so every probe counts and the covered share is exactly 1. On floors, walls
   and other large flat surfaces that is many footprints, and their 16 rays each were spent for
   nothing.

   The proof is one query of the scene BVH over the box of the probes' cylinder (the ellipse swept
   along n from the highest probe start above the plane to as far below). In the ellipse's disc
   coordinates q (projected along n the ellipse is the unit disc), every triangle in the box is
   one of:
   - in the photon's plane (every vertex within the ray offset of it): part of its surface. The
     surface covers the disc if no edge of it crosses the disc unpaired: each edge of a plane
     triangle that reaches into the disc (with a margin) must be the edge of another plane
     triangle lying on its other side. Edges are paired by a key of their end points (identical
     floats where triangles share vertices), added from one side and subtracted from the other;
     an edge at the surface's rim, a hole or a T-junction leaves the sum unbalanced. (A 32-bit sum
     of such keys can balance by chance, about once in 2^31 footprints that have unpaired edges;
     such a footprint would be counted as covered where its probes would have found it partly
     covered.) A masked triangle of the plane (alpha holes) ends the proof;
   - below the plane: the probes meet the plane first;
   - wholly above the highest probe start, or outside the disc: no probe meets it;
   - anything else stands over the disc (a wall at its rim, a column, a step) and ends the proof.
   The own triangle must be among those of the plane (it holds the hit). Where the proof holds
   the probes return exactly 1 (footprint_covered_share: every kept probe covered); elsewhere the
   footprint goes to the probes as before. */
#ifndef PM_FOOTPRINT_WHOLE_H
#define PM_FOOTPRINT_WHOLE_H

#include "footprint.h"
#include "kernel_globals.h"
#include "scene_traverse.h"

/* How far inside the own triangle's edges the unit disc must stay, in disc radii: probes never
   land on an edge, where a ray may pass between two triangles' tests. */
#define PM_FOOTPRINT_WHOLE_MARGIN 1.0e-3f

/* Squared distance from the origin to the segment (ax, ay)-(bx, by). */
PM_DEVICE float footprint_origin_segment_distance2(float ax, float ay, float bx, float by)
{
  float dx = bx - ax, dy = by - ay;
  float len2 = dx * dx + dy * dy;
  float s = len2 > 0.0f ? pm_fminf(pm_fmaxf(-(ax * dx + ay * dy) / len2, 0.0f), 1.0f) : 0.0f;
  float px = ax + s * dx, py = ay + s * dy;
  return px * px + py * py;
}

/* Whether the triangle with disc coordinates (x[i], y[i]) reaches within `radius` of the origin. */
PM_DEVICE int footprint_triangle_reaches(const float* x, const float* y, float radius)
{
  float c0 = x[0] * y[1] - x[1] * y[0], c1 = x[1] * y[2] - x[2] * y[1], c2 = x[2] * y[0] - x[0] * y[2];
  if ((c0 >= 0.0f && c1 >= 0.0f && c2 >= 0.0f) || (c0 <= 0.0f && c1 <= 0.0f && c2 <= 0.0f)) return 1; /* holds it */
  float r2 = radius * radius;
  for (int e = 0; e < 3; ++e) {
    int f = e == 2 ? 0 : e + 1;
    if (footprint_origin_segment_distance2(x[e], y[e], x[f], y[f]) <= r2) return 1;
  }
  return 0;
}

/* Whether the unit disc lies inside the triangle with disc coordinates (x[i], y[i]), each edge's
   line at least 1 + PM_FOOTPRINT_WHOLE_MARGIN from the origin, on the inner side. */
PM_DEVICE int footprint_disc_inside(const float* x, const float* y)
{
  float orient = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (!(pm_fabsf(orient) > 0.0f)) return 0;
  float sign = orient > 0.0f ? 1.0f : -1.0f;
  for (int e = 0; e < 3; ++e) {
    int f = e == 2 ? 0 : e + 1;
    float dx = x[f] - x[e], dy = y[f] - y[e];
    /* The origin's side of the edge, times its length: (b - a) x (0 - a), positive inside a
       counter-clockwise triangle. */
    float side = sign * (x[e] * dy - y[e] * dx);
    if (!(side >= (1.0f + PM_FOOTPRINT_WHOLE_MARGIN) * pm_sqrtf(dx * dx + dy * dy))) return 0;
  }
  return 1;
}

/* A key for the edge between points a and b, the same whichever way round: an interior edge of
   the surface is met twice, once from each side. */
PM_DEVICE uint footprint_mix(uint x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  return x ^ (x >> 16);
}

PM_DEVICE uint footprint_edge_key(Vec3 a, Vec3 b)
{
  uint ka = footprint_mix(PM_AS_UINT(a.x) ^ footprint_mix(PM_AS_UINT(a.y) ^ footprint_mix(PM_AS_UINT(a.z))));
  uint kb = footprint_mix(PM_AS_UINT(b.x) ^ footprint_mix(PM_AS_UINT(b.y) ^ footprint_mix(PM_AS_UINT(b.z))));
  return (ka + kb) | 1u;
}

/* Whether every probe of footprint f (centre `center` on triangle `own`, unit normal n facing the
   photon's side, ray offset `offset`) would meet the photon's own surface first: then its covered
   share is 1 without the probes. */
PM_DEVICE int footprint_wholly_on_own_surface(const KernelGlobals* kg, const Footprint* f, Vec3 center, Vec3 n,
                                               float offset, int own)
{
  if (own < 0) return 0;
  Vec3 a_u = f->axis_u, a_v = f->axis_v;
  float area = vec3_dot(vec3_cross(a_u, a_v), n);
  if (!(pm_fabsf(area) > 0.0f) || !pm_isfinite(area)) return 0;
  Vec3 row_u = vec3_scale(vec3_cross(a_v, n), 1.0f / area), row_v = vec3_scale(vec3_cross(n, a_u), 1.0f / area);
  float reach = 1.0f + PM_FOOTPRINT_WHOLE_MARGIN;

  /* The probes' cylinder: from `top` above the plane (the highest probe start) to as far below. */
  float top = vec3_length(f->axis_n) + offset;
  Vec3 ext = vec3(pm_sqrtf(a_u.x * a_u.x + a_v.x * a_v.x) + pm_fabsf(n.x) * top,
                  pm_sqrtf(a_u.y * a_u.y + a_v.y * a_v.y) + pm_fabsf(n.y) * top,
                  pm_sqrtf(a_u.z * a_u.z + a_v.z * a_v.z) + pm_fabsf(n.z) * top);
  Vec3 lo = vec3_sub(center, ext), hi = vec3_add(center, ext);
  uint unpaired = 0u; /* edges of the photon's plane inside the disc, + from one side, - from the other */
  int own_seen = 0;
  int stack[PM_TRAVERSAL_STACK];
  int sp = 0, node = 0;
  for (;;) {
    float4 n0 = PM_LOAD(&kg->scene_nodes[4 * node + 0]);
    float4 n1 = PM_LOAD(&kg->scene_nodes[4 * node + 1]);
    float4 n2 = PM_LOAD(&kg->scene_nodes[4 * node + 2]);
    float4 n3 = PM_LOAD(&kg->scene_nodes[4 * node + 3]);
    int child0 = PM_AS_INT(n3.x), child1 = PM_AS_INT(n3.y);
    int count0 = PM_AS_INT(n3.z), count1 = PM_AS_INT(n3.w);
    int visit0 = child0 >= 0 && n0.x <= hi.x && n0.y >= lo.x && n0.z <= hi.y && n0.w >= lo.y && n2.x <= hi.z &&
                 n2.y >= lo.z;
    int visit1 = child1 >= 0 && n1.x <= hi.x && n1.y >= lo.x && n1.z <= hi.y && n1.w >= lo.y && n2.z <= hi.z &&
                 n2.w >= lo.z;
    for (int side = 0; side < 2; ++side) {
      int first = side ? child1 : child0, count = side ? count1 : count0;
      if (!(side ? visit1 : visit0) || count == 0) continue;
      for (int t = first; t < first + count; ++t) {
        Vec3 v[3];
        float h[3], x[3], y[3];
        for (int i = 0; i < 3; ++i) {
          v[i] = scene_triangle_vertex(kg->triangles, t, i);
          Vec3 d = vec3_sub(v[i], center);
          h[i] = vec3_dot(n, d);
          x[i] = vec3_dot(row_u, d);
          y[i] = vec3_dot(row_v, d);
        }
        float h_max = pm_fmaxf(h[0], pm_fmaxf(h[1], h[2])), h_min = pm_fminf(h[0], pm_fminf(h[1], h[2]));
        if (h_min > top) continue; /* above every probe's start */
        int in_plane = h_max <= offset && h_min >= -offset;
        if (!in_plane && h_max <= offset) continue; /* below: the probes meet the plane first */
        if (!footprint_triangle_reaches(x, y, reach)) continue;
        if (!in_plane) return 0; /* standing over the disc */
        /* A masked triangle of the plane lets probes through its holes. */
        if (PM_AS_UINT(PM_LOAD(&kg->triangles[3 * t]).w) & PM_TRIANGLE_MASKED) return 0;
        own_seen |= t == own;
        for (int e = 0; e < 3; ++e) {
          int g = e == 2 ? 0 : e + 1, o = e == 0 ? 2 : e - 1;
          if (footprint_origin_segment_distance2(x[e], y[e], x[g], y[g]) > reach * reach) continue;
          /* Which side of the edge this triangle lies on, the edge taken in a fixed direction. */
          int forward = x[e] < x[g] || (x[e] == x[g] && y[e] < y[g]);
          float cross = (x[g] - x[e]) * (y[o] - y[e]) - (y[g] - y[e]) * (x[o] - x[e]);
          uint key = footprint_edge_key(v[e], v[g]);
          unpaired += ((cross > 0.0f) == forward) ? key : 0u - key;
        }
      }
      if (side) visit1 = 0;
      else visit0 = 0;
    }
    if (visit0 && visit1) {
      stack[sp++] = child1;
      node = child0;
    } else if (visit0 || visit1) {
      node = visit0 ? child0 : child1;
    } else {
      if (sp == 0) break;
      node = stack[--sp];
    }
  }
  return own_seen && unpaired == 0u;
}

#endif
