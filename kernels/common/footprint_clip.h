/* Footprints that stop at walls (stage S3): a photon's footprint ellipse must not reach across
   geometry that separates it from the photon's hit, e.g. along a floor under a zero-thickness
   wall into a closed box, or past a box's inner corner onto the outside of the adjoining face.

   The footprint is tested against the scene's triangles in a plane lifted a little above it
   (PM_FOOTPRINT_CLIP_HEIGHT of its normal half-axis, on the photon's side): a triangle that
   crosses that plane inside the ellipse is a blocker standing on or rising from the footprint's
   surface, such as a wall. Its crossing segment, seen in the footprint's plane, lies on a line
   w . y = d (w unit and in the plane, pointing away from the hit, y measured from the hit), at
   t = d / s of the ellipse's support s along w (0 <= t < 1). The candidates come from one query
   of the scene BVH with the lifted ellipse's box, so every triangle inside the footprint is seen
   (sampling it with probe rays misses a box corner that pokes in between two rays); the surface
   the photon hit and its coplanar neighbours never cross the lifted plane.
   - The nearest line (smallest t) cuts the ellipse: the gather accepts only points on the hit's
     side of it, and the flux is divided by the kernel mass left inside the cut ellipse
     (footprint_kept_fraction), so no energy is lost or created. Uniform photons on a floor then
     give 69 % of the open-floor estimate at a wall's foot (constant kernel), against 50 % for
     footprints that spill behind the wall; compressing each ellipse against the wall instead
     would leave its rim touching the wall at one point, and the wall's foot dark (0 %).
   - Any further line (a corner, a narrow gap) shrinks the whole ellipse about the hit to its t.
   Cost: one small box query per hit, O(photons), not O(gathers).
   Not seen: blockers lower than the lifted plane, and convex edges, where the surface simply
   ends; there the gather's normal test stops photons reaching the other side (gather_reach.h).
   Concave curved surfaces rise into the lifted plane too, at sqrt(2 R height) from the hit for a
   curvature radius R: with the pd footprints' height |a| / 8 only surfaces curved tighter than
   R = 4 |a| clip them. */
#ifndef PM_FOOTPRINT_CLIP_H
#define PM_FOOTPRINT_CLIP_H

#include "footprint.h"
#include "kernel_globals.h"
#include "scene_traverse.h"

/* Height of the lifted plane, as a fraction of the normal half-axis |a_n|. */
#define PM_FOOTPRINT_CLIP_HEIGHT 0.5f

typedef struct FootprintClip {
  Footprint f;   /* the unclipped ellipse (a_u, a_v in the plane) */
  Vec3 center;   /* the hit */
  Vec3 n;        /* unit normal on the photon's side */
  float height;  /* of the lifted plane above the hit */
  Vec3 cut_w;    /* the nearest line found: w . y <= cut_d, at cut_t of the support */
  float cut_d, cut_t;
  float shrink;  /* the smallest t of the other lines found (1: none) */
} FootprintClip;

/* The cut of a clipped footprint in its unit-disc coordinates (lu, lv) = (row_u . y, row_v . y):
   points with alpha lu + beta lv > gamma lie behind it. No cut: (0, 0, 1). kept: the fraction of
   the kernel's mass on the hit's side. */
typedef struct FootprintCut {
  float alpha, beta, gamma, kept;
} FootprintCut;

/* Kernel mass of the unit disc on the near side of a line at distance t from its centre
   (0 <= t <= 1), as a fraction of the whole. Constant kernel: 1 - (acos t - t sqrt(1 - t^2)) / pi
   (a circular segment). Epanechnikov, 2 (1 - r^2): the mass beyond t is
   int_t^1 (8/3) (1 - x^2)^(3/2) dx = (8/3) (3 pi / 16 - F(t)),
   F(x) = x (5 - 2 x^2) sqrt(1 - x^2) / 8 + 3 asin(x) / 8. */
PM_DEVICE float footprint_kept_fraction(float t, uint kernel_shape)
{
  t = pm_fminf(pm_fmaxf(t, 0.0f), 1.0f);
  float root = pm_sqrtf(pm_fmaxf(1.0f - t * t, 0.0f));
  float beyond;
  if (kernel_shape == PM_KERNEL_EPANECHNIKOV)
    beyond = (8.0f / 3.0f) * (3.0f * PM_FP_PI / 16.0f - (t * (5.0f - 2.0f * t * t) * root / 8.0f + 3.0f * pm_asinf(t) / 8.0f));
  else
    beyond = pm_acosf(t) - t * root;
  return 1.0f - pm_fmaxf(beyond, 0.0f) / PM_FP_PI;
}

/* The in-plane point y (relative to the hit) in the unclipped ellipse's unit-disc coordinates. */
PM_DEVICE void footprint_disc_coordinates(const FootprintClip* c, Vec3 y, float* qu, float* qv)
{
  Vec3 a_u = c->f.axis_u, a_v = c->f.axis_v;
  float area = vec3_dot(vec3_cross(a_u, a_v), c->n); /* rows of the inverse in-plane basis */
  *qu = area != 0.0f ? vec3_dot(vec3_cross(a_v, c->n), y) / area : PM_FOOTPRINT_FAR;
  *qv = area != 0.0f ? vec3_dot(vec3_cross(c->n, a_u), y) / area : PM_FOOTPRINT_FAR;
}

/* Whether the segment between two disc-coordinate points comes inside the unit circle. */
PM_DEVICE int footprint_segment_enters_disc(float ax, float ay, float bx, float by)
{
  float dx = bx - ax, dy = by - ay;
  float len2 = dx * dx + dy * dy;
  float t = len2 > 0.0f ? -(ax * dx + ay * dy) / len2 : 0.0f;
  t = pm_fminf(pm_fmaxf(t, 0.0f), 1.0f);
  float cx = ax + t * dx, cy = ay + t * dy;
  return cx * cx + cy * cy < 1.0f;
}

/* The point where edge (a, b) crosses the lifted plane, given their heights above it. */
PM_DEVICE Vec3 footprint_edge_crossing(Vec3 a, float ha, Vec3 b, float hb)
{
  return vec3_madd(a, vec3_sub(b, a), ha / (ha - hb));
}

/* Notes the line of triangle (v0, v1, v2) if it crosses the lifted plane inside the ellipse. */
PM_DEVICE void footprint_clip_triangle(FootprintClip* c, Vec3 v0, Vec3 v1, Vec3 v2)
{
  float h0 = vec3_dot(c->n, vec3_sub(v0, c->center)) - c->height;
  float h1 = vec3_dot(c->n, vec3_sub(v1, c->center)) - c->height;
  float h2 = vec3_dot(c->n, vec3_sub(v2, c->center)) - c->height;
  Vec3 p[2];
  int k = 0;
  if ((h0 < 0.0f) != (h1 < 0.0f)) p[k++] = footprint_edge_crossing(v0, h0, v1, h1);
  if ((h1 < 0.0f) != (h2 < 0.0f)) p[k++] = footprint_edge_crossing(v1, h1, v2, h2);
  if (k < 2 && (h2 < 0.0f) != (h0 < 0.0f)) p[k++] = footprint_edge_crossing(v2, h2, v0, h0);
  if (k < 2) return;
  /* The crossing segment in the footprint's plane, relative to the hit. */
  Vec3 y0 = vec3_sub(p[0], c->center), y1 = vec3_sub(p[1], c->center);
  y0 = vec3_madd(y0, c->n, -vec3_dot(c->n, y0));
  y1 = vec3_madd(y1, c->n, -vec3_dot(c->n, y1));
  float q0u, q0v, q1u, q1v;
  footprint_disc_coordinates(c, y0, &q0u, &q0v);
  footprint_disc_coordinates(c, y1, &q1u, &q1v);
  if (!footprint_segment_enters_disc(q0u, q0v, q1u, q1v)) return;
  Vec3 w = vec3_cross(c->n, vec3_sub(y1, y0));
  if (!(vec3_dot(w, w) > 0.0f)) w = vec3_add(y0, y1); /* the segment is a point */
  w = vec3_normalize(w);
  float d = vec3_dot(w, y0);
  if (d < 0.0f) {
    w = vec3_neg(w);
    d = -d;
  }
  float su = vec3_dot(c->f.axis_u, w), sv = vec3_dot(c->f.axis_v, w);
  float t = d / pm_sqrtf(su * su + sv * sv);
  if (!pm_isfinite(t) || !(vec3_dot(w, w) > 0.5f) || !(t < 1.0f)) return;
  if (t < c->cut_t) {
    c->shrink = pm_fminf(c->shrink, c->cut_t);
    c->cut_w = w;
    c->cut_d = d;
    c->cut_t = t;
  } else {
    c->shrink = pm_fminf(c->shrink, t);
  }
}

/* Whether the child box (stored in its parent's node, scene_bvh.h) overlaps [lo, hi]. */
PM_DEVICE int footprint_box_overlaps(float4 xy, float z_min, float z_max, Vec3 lo, Vec3 hi)
{
  return xy.x <= hi.x && xy.y >= lo.x && xy.z <= hi.y && xy.w >= lo.y && z_min <= hi.z && z_max >= lo.z;
}

/* Every triangle whose BVH leaf overlaps the lifted ellipse's box. */
PM_DEVICE void footprint_clip_scan(const KernelGlobals* kg, FootprintClip* c)
{
  Vec3 a_u = c->f.axis_u, a_v = c->f.axis_v;
  Vec3 ext = vec3(pm_sqrtf(a_u.x * a_u.x + a_v.x * a_v.x), pm_sqrtf(a_u.y * a_u.y + a_v.y * a_v.y),
                  pm_sqrtf(a_u.z * a_u.z + a_v.z * a_v.z));
  Vec3 mid = vec3_madd(c->center, c->n, c->height);
  Vec3 lo = vec3_sub(mid, ext), hi = vec3_add(mid, ext);
  int stack[PM_TRAVERSAL_STACK];
  int sp = 0, node = 0;
  for (;;) {
    float4 n0 = PM_LOAD(&kg->scene_nodes[4 * node + 0]);
    float4 n1 = PM_LOAD(&kg->scene_nodes[4 * node + 1]);
    float4 n2 = PM_LOAD(&kg->scene_nodes[4 * node + 2]);
    float4 n3 = PM_LOAD(&kg->scene_nodes[4 * node + 3]);
    int child[2], count[2], visit[2];
    child[0] = PM_AS_INT(n3.x);
    child[1] = PM_AS_INT(n3.y);
    count[0] = PM_AS_INT(n3.z);
    count[1] = PM_AS_INT(n3.w);
    visit[0] = child[0] >= 0 && footprint_box_overlaps(n0, n2.x, n2.y, lo, hi);
    visit[1] = child[1] >= 0 && footprint_box_overlaps(n1, n2.z, n2.w, lo, hi);
    for (int side = 0; side < 2; ++side) {
      if (!visit[side] || count[side] == 0) continue;
      for (int t = child[side]; t < child[side] + count[side]; ++t)
        footprint_clip_triangle(c, scene_triangle_vertex(kg->triangles, t, 0), scene_triangle_vertex(kg->triangles, t, 1),
                                scene_triangle_vertex(kg->triangles, t, 2));
      visit[side] = 0;
    }
    if (visit[0] && visit[1]) {
      stack[sp++] = child[1];
      node = child[0];
    } else if (visit[0] || visit[1]) {
      node = visit[0] ? child[0] : child[1];
    } else {
      if (sp == 0) break;
      node = stack[--sp];
    }
  }
}

/* Clips f (in the plane of the unit normal n, which faces the photon's side) against the
   triangles around its hit at `center`: shrinks it in place and returns its cut, in the shrunk
   ellipse's disc coordinates, with the kept fraction of the kernel `kernel_shape`.
   offset: the ray offset of the hit (ray.h), the least height of the lifted plane. */
PM_DEVICE FootprintCut footprint_clip(const KernelGlobals* kg, Footprint* f, Vec3 center, Vec3 n, float offset,
                                      uint kernel_shape)
{
  FootprintClip c;
  c.f = *f;
  c.center = center;
  c.n = n;
  c.height = pm_fmaxf(PM_FOOTPRINT_CLIP_HEIGHT * vec3_length(f->axis_n), offset);
  c.cut_w = vec3_splat(0.0f);
  c.cut_d = 0.0f;
  c.cut_t = 1.0f;
  c.shrink = 1.0f;
  footprint_clip_scan(kg, &c);
  FootprintCut cut;
  cut.alpha = 0.0f;
  cut.beta = 0.0f;
  cut.gamma = 1.0f;
  cut.kept = 1.0f;
  if (c.shrink < 1.0f) {
    f->axis_u = vec3_scale(f->axis_u, c.shrink);
    f->axis_v = vec3_scale(f->axis_v, c.shrink);
    f->axis_n = vec3_scale(f->axis_n, c.shrink);
  }
  if (c.cut_t < 1.0f) {
    /* w . y <= d with y = lu a_u + lv a_v: (w . a_u) lu + (w . a_v) lv <= d. */
    cut.alpha = vec3_dot(c.cut_w, f->axis_u);
    cut.beta = vec3_dot(c.cut_w, f->axis_v);
    cut.gamma = c.cut_d;
    cut.kept = footprint_kept_fraction(c.cut_t / c.shrink, kernel_shape);
  }
  return cut;
}

#endif
