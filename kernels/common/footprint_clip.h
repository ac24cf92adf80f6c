/* Footprints that stop at walls (stage S3): a photon's footprint ellipse must not reach across
   geometry that separates it from the photon's hit, e.g. along a floor under a zero-thickness
   wall into a closed box, or past a box's inner corner onto the outside of the adjoining face.

   The footprint is tested against the scene's triangles in a plane lifted a little above it
   (PM_FOOTPRINT_CLIP_HEIGHT of its normal half-axis, on the photon's side): a triangle that
   crosses that plane inside the ellipse is a blocker standing on or rising from the footprint's
   surface, such as a wall. The candidates come from one query of the scene BVH with the lifted
   ellipse's box, so every triangle inside the footprint is seen (probe rays miss a box corner
   that pokes in between two of them); the surface the photon hit and its coplanar neighbours
   never cross the lifted plane. Everything below is in the ellipse's unit-disc coordinates q
   (x - hit = q_u a_u + q_v a_v + ...), where the footprint is the unit disc.
   - A blocker's crossing segment that enters the disc hides what lies behind it: the cut
     m . q <= t drops the part of the disc beyond the segment's line (normal m, at distance t < 1
     from the hit), also beyond the segment's ends, so that around a box corner poking into the
     disc both faces cut and nothing of the box's inside is reached.
   - Up to PM_FOOTPRINT_CUTS cuts are kept, the nearest ones. Cuts within 25 degrees of each other
     are one wall (the facets of a curved wall, such as a ring of 64 segments, or the triangles of
     one wall), of which the nearest is kept. A further distinct wall (a third one) shrinks the
     whole disc about the hit to its t.
   - The flux is divided by the kernel mass left inside the cut disc (footprint_kept_fraction),
     so no energy is lost or created. Uniform photons on a floor then give 69 % of the open-floor
     estimate at a wall's foot (constant kernel), against 50 % for footprints that spill behind
     the wall; compressing each ellipse against the wall instead leaves the foot dark (0 %).
   Cost: one small box query per hit, O(photons), not O(gathers).
   Not seen: blockers lower than the lifted plane, triangles of alpha-masked materials (texture.h:
   light passes their holes, so they are not walls), and convex edges, where the surface simply
   ends; there the gather's normal test stops photons reaching the other side (gather_reach.h).
   Concave curved surfaces rise into the lifted plane too, at sqrt(2 R height) from the hit for a
   curvature radius R: with the pd footprints' height |a| / 8 only surfaces curved tighter than
   R = 4 |a| cut them. */
#ifndef PM_FOOTPRINT_CLIP_H
#define PM_FOOTPRINT_CLIP_H

#include "footprint.h"
#include "kernel_globals.h"
#include "scene_traverse.h"

/* Height of the lifted plane, as a fraction of the normal half-axis |a_n|. */
#define PM_FOOTPRINT_CLIP_HEIGHT 0.5f
/* Cuts kept per footprint (the gather tests each). */
#define PM_FOOTPRINT_CUTS 2
/* Cuts closer in direction than this cosine (25 degrees) count as one wall. */
#define PM_FOOTPRINT_SAME_WALL_COS 0.906f

/* The cuts of a footprint: the gather accepts a point whose disc coordinates q satisfy
   m_k . q <= t_k for every cut k; no cut: m = 0, t = 1. kept: the fraction of the kernel's mass
   left inside the disc. */
typedef struct FootprintCut {
  float mu[PM_FOOTPRINT_CUTS], mv[PM_FOOTPRINT_CUTS], t[PM_FOOTPRINT_CUTS];
  int count;
  float shrink; /* the disc was scaled about the hit by this (1: not) */
  float kept;
} FootprintCut;

typedef struct FootprintClip {
  Vec3 a_u, a_v; /* the unclipped ellipse's in-plane semiaxes */
  Vec3 row_u, row_v; /* their reciprocal rows: q = (row_u . y, row_v . y) */
  Vec3 center, n;
  float height;
  FootprintCut cut;
  Vec3 cut_direction[PM_FOOTPRINT_CUTS]; /* of each kept cut, in the plane (footprint_cut_direction) */
} FootprintClip;

/* No cuts: the whole disc, all of the kernel's mass. */
PM_DEVICE FootprintCut footprint_uncut(void)
{
  FootprintCut cut;
  for (int k = 0; k < PM_FOOTPRINT_CUTS; ++k) {
    cut.mu[k] = 0.0f;
    cut.mv[k] = 0.0f;
    cut.t[k] = 1.0f;
  }
  cut.count = 0;
  cut.shrink = 1.0f;
  cut.kept = 1.0f;
  return cut;
}

/* Green's theorem: the kernel mass of a region is the integral of Q dy around its boundary
   (counter-clockwise), with dQ/dx = K. Constant kernel K = 1: Q = x. Epanechnikov
   K = 2 (1 - x^2 - y^2): Q = 2 (x - x^3 / 3 - x y^2), which is (4/3) x^3 on the unit circle. */
PM_DEVICE float footprint_green_q(float x, float y, uint shape)
{
  return shape == PM_KERNEL_EPANECHNIKOV ? 2.0f * (x - x * x * x / 3.0f - x * y * y) : x;
}

/* Integral of Q dy along the segment a -> b (Q is at most cubic along it: two-point Gauss). */
PM_DEVICE float footprint_green_segment(float ax, float ay, float bx, float by, uint shape)
{
  const float g0 = 0.2113248654f, g1 = 0.7886751346f; /* (1 -+ 1/sqrt(3)) / 2 */
  float q0 = footprint_green_q(ax + g0 * (bx - ax), ay + g0 * (by - ay), shape);
  float q1 = footprint_green_q(ax + g1 * (bx - ax), ay + g1 * (by - ay), shape);
  return 0.5f * (q0 + q1) * (by - ay);
}

/* Antiderivative of Q dy along the unit circle at angle phi: int cos^2 = phi/2 + sin(2 phi)/4;
   Epanechnikov (4/3) int cos^4 = (4/3) (3 phi / 8 + sin(2 phi) / 4 + sin(4 phi) / 32). */
PM_DEVICE float footprint_green_arc(float phi, uint shape)
{
  if (shape == PM_KERNEL_EPANECHNIKOV)
    return (4.0f / 3.0f) * (0.375f * phi + 0.25f * pm_sinf(2.0f * phi) + pm_sinf(4.0f * phi) / 32.0f);
  return 0.5f * phi + 0.25f * pm_sinf(2.0f * phi);
}

/* Fraction of the kernel's mass in the unit disc that satisfies every cut m_k . q <= t_k
   (m_k unit, 0 <= t_k): the region's boundary is the part of each cut's chord inside the other
   cuts, and the arcs of the circle inside all of them. */
PM_DEVICE float footprint_kept_fraction(const float* mu, const float* mv, const float* t, int count, uint shape)
{
  float mass = 0.0f;
  /* Chords, traversed along m rotated by +90 degrees (the kept side on the left). */
  for (int k = 0; k < count; ++k) {
    if (!(t[k] < 1.0f)) continue;
    float s = pm_sqrtf(pm_fmaxf(1.0f - t[k] * t[k], 0.0f));
    float ax = t[k] * mu[k] + s * mv[k], ay = t[k] * mv[k] - s * mu[k];
    float bx = t[k] * mu[k] - s * mv[k], by = t[k] * mv[k] + s * mu[k];
    float lo = 0.0f, hi = 1.0f;
    for (int j = 0; j < count; ++j) {
      if (j == k) continue;
      float fa = mu[j] * ax + mv[j] * ay - t[j], fb = mu[j] * bx + mv[j] * by - t[j];
      if (fa > 0.0f && fb > 0.0f) hi = -1.0f;
      else if (fa > 0.0f) lo = pm_fmaxf(lo, fa / (fa - fb));
      else if (fb > 0.0f) hi = pm_fminf(hi, fa / (fa - fb));
    }
    if (!(hi > lo)) continue;
    mass += footprint_green_segment(ax + lo * (bx - ax), ay + lo * (by - ay), ax + hi * (bx - ax), ay + hi * (by - ay),
                                    shape);
  }
  /* Arcs: each cut forbids the angles within acos(t) of its direction; the allowed arc of the
     first runs from theta + a for 2 pi - 2 a, and the others clip it. */
  float start = 0.0f, length = PM_TWO_PI;
  int first = -1;
  for (int k = 0; k < count; ++k)
    if (t[k] < 1.0f) {
      first = k;
      break;
    }
  if (first < 0) return 1.0f;
  float a0 = pm_acosf(pm_fminf(pm_fmaxf(t[first], -1.0f), 1.0f));
  start = pm_atan2f(mv[first], mu[first]) + a0;
  length = PM_TWO_PI - 2.0f * a0;
  /* Up to two pieces [begin, end) relative to start, clipped by the other cuts in turn. */
  float piece_begin[2], piece_end[2];
  int pieces = 1;
  piece_begin[0] = 0.0f;
  piece_end[0] = length;
  for (int k = 0; k < count; ++k) {
    if (k == first || !(t[k] < 1.0f)) continue;
    float a = pm_acosf(pm_fminf(pm_fmaxf(t[k], -1.0f), 1.0f));
    /* Cut k's allowed arc, relative to start, as [b, b + 2 pi - 2 a) taken modulo 2 pi. */
    float b = pm_atan2f(mv[k], mu[k]) + a - start;
    b = b - PM_TWO_PI * pm_floorf(b / (PM_TWO_PI));
    float e = b + PM_TWO_PI - 2.0f * a;
    float out_begin[2], out_end[2];
    int out = 0;
    for (int p = 0; p < pieces; ++p) {
      /* The allowed arc covers [b, e) and, when e wraps past 2 pi, [0, e - 2 pi). */
      float lo1 = pm_fmaxf(piece_begin[p], b), hi1 = pm_fminf(piece_end[p], e);
      if (hi1 > lo1 && out < 2) { out_begin[out] = lo1; out_end[out] = hi1; ++out; }
      float lo2 = piece_begin[p], hi2 = pm_fminf(piece_end[p], e - PM_TWO_PI);
      if (hi2 > lo2 && out < 2) { out_begin[out] = lo2; out_end[out] = hi2; ++out; }
    }
    pieces = out;
    for (int p = 0; p < pieces; ++p) {
      piece_begin[p] = out_begin[p];
      piece_end[p] = out_end[p];
    }
  }
  for (int p = 0; p < pieces; ++p)
    mass += footprint_green_arc(start + piece_end[p], shape) - footprint_green_arc(start + piece_begin[p], shape);
  return pm_fminf(pm_fmaxf(mass / PM_PI, 0.0f), 1.0f);
}

/* The same for a single cut at distance t in [0, 1) from the centre, in closed form: the segment
   beyond the chord holds (acos t - t sqrt(1 - t^2)) / pi of the constant kernel's mass and
   (acos t - t (5 - 2 t^2) sqrt(1 - t^2) / 3) / pi of Epanechnikov's (the integral of
   (8 / 3) (1 - x^2)^(3/2) from t to 1, over pi). The gather's per-candidate path: no arcs, no
   loops. */
PM_DEVICE float footprint_kept_one_cut(float t, uint shape)
{
  t = pm_fminf(pm_fmaxf(t, 0.0f), 1.0f);
  float s = pm_sqrtf(pm_fmaxf(1.0f - t * t, 0.0f));
  float chord = shape == PM_KERNEL_EPANECHNIKOV ? t * (5.0f - 2.0f * t * t) * s * (1.0f / 3.0f) : t * s;
  return 1.0f - (pm_acosf(t) - chord) * (1.0f / PM_PI);
}

/* The direction, in the footprint's plane, of the normal of the line m . q = t in disc
   coordinates q = (row_u . y, row_v . y): angles between walls are judged there, since disc
   coordinates distort them (two perpendicular walls can look parallel to an elongated ellipse). */
PM_DEVICE Vec3 footprint_cut_direction(const FootprintClip* clip, float mu, float mv)
{
  return vec3_normalize(vec3_add(vec3_scale(clip->row_u, mu), vec3_scale(clip->row_v, mv)));
}

/* Adds the cut m . q <= t (m unit in disc coordinates, 0 <= t < 1) to the clip's cuts. A cut
   within 25 degrees of a kept one is the same wall (the facets of a curved wall, such as a ring
   of 64 segments, or the two triangles of one wall): the nearer of the two is kept, and the
   sliver between them is not cut (shrinking instead would make every footprint along a curved
   wall tiny). Otherwise it is kept if among the PM_FOOTPRINT_CUTS nearest; a distinct wall that
   is not kept shrinks the disc to its t. */
PM_DEVICE void footprint_add_cut(FootprintClip* clip, float mu, float mv, float t)
{
  FootprintCut* c = &clip->cut;
  Vec3 w = footprint_cut_direction(clip, mu, mv);
  int slot = -1;
  for (int k = 0; k < c->count && slot < 0; ++k)
    if (vec3_dot(w, clip->cut_direction[k]) > PM_FOOTPRINT_SAME_WALL_COS) slot = k;
  if (slot < 0 && c->count < PM_FOOTPRINT_CUTS) {
    slot = c->count++;
    c->t[slot] = 2.0f;
  }
  if (slot < 0) {
    slot = 0; /* the kept cut with the largest t gives way when this one is nearer */
    for (int k = 1; k < c->count; ++k)
      if (c->t[k] > c->t[slot]) slot = k;
    c->shrink = pm_fminf(c->shrink, pm_fmaxf(t, c->t[slot]));
  }
  if (t < c->t[slot]) {
    c->mu[slot] = mu;
    c->mv[slot] = mv;
    c->t[slot] = t;
    clip->cut_direction[slot] = w;
  }
}

/* The point where edge (a, b) crosses the lifted plane, given their heights above it. */
PM_DEVICE Vec3 footprint_edge_crossing(Vec3 a, float ha, Vec3 b, float hb)
{
  return vec3_madd(a, vec3_sub(b, a), ha / (ha - hb));
}

/* Cuts at triangle (v0, v1, v2), whose heights above the lifted plane are h0, h1, h2 and not all
   of one sign, if its crossing segment enters the disc. */
PM_DEVICE void footprint_clip_triangle(FootprintClip* c, Vec3 v0, Vec3 v1, Vec3 v2, float h0, float h1, float h2)
{
  Vec3 p[2];
  int k = 0;
  if ((h0 < 0.0f) != (h1 < 0.0f)) p[k++] = footprint_edge_crossing(v0, h0, v1, h1);
  if ((h1 < 0.0f) != (h2 < 0.0f)) p[k++] = footprint_edge_crossing(v1, h1, v2, h2);
  if (k < 2 && (h2 < 0.0f) != (h0 < 0.0f)) p[k++] = footprint_edge_crossing(v2, h2, v0, h0);
  if (k < 2) return;
  /* The crossing segment in disc coordinates (the rows ignore the normal component). */
  Vec3 y0 = vec3_sub(p[0], c->center), y1 = vec3_sub(p[1], c->center);
  float ax = vec3_dot(c->row_u, y0), ay = vec3_dot(c->row_v, y0);
  float bx = vec3_dot(c->row_u, y1), by = vec3_dot(c->row_v, y1);
  /* A segment that enters the disc cuts away everything beyond its line. (Beyond its ends too:
     around the corner of a box that pokes into the disc, both faces' lines cut, so nothing of
     the box's inside is reached.) */
  float dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  float s = len2 > 0.0f ? pm_fminf(pm_fmaxf(-(ax * dx + ay * dy) / len2, 0.0f), 1.0f) : 0.0f;
  float qx = ax + s * dx, qy = ay + s * dy;
  float nearest = pm_sqrtf(qx * qx + qy * qy);
  if (!(nearest < 1.0f)) return;
  float mu, mv, t;
  if (len2 > 0.0f) {
    float len = pm_sqrtf(len2);
    mu = -dy / len;
    mv = dx / len;
    t = mu * ax + mv * ay;
    if (t < 0.0f) {
      mu = -mu;
      mv = -mv;
      t = -t;
    }
  } else if (nearest > 0.0f) {
    mu = qx / nearest;
    mv = qy / nearest;
    t = nearest;
  } else {
    return;
  }
  footprint_add_cut(c, mu, mv, t);
}

/* Cuts at the triangle of records (r0, r1, r2) (triangles.h) if it crosses the lifted plane
   n . x = level. Masked triangles (foliage, fences) are no walls: light passes their holes, and
   a cut would darken what lies behind them everywhere, holes included. */
PM_DEVICE void footprint_clip_record(FootprintClip* c, float4 r0, float4 r1, float4 r2, Vec3 n, float level)
{
  if (PM_AS_UINT(r0.w) & PM_TRIANGLE_MASKED) return;
  Vec3 v0 = vec3_from_float4(r0), v1 = vec3_from_float4(r1), v2 = vec3_from_float4(r2);
  float h0 = vec3_dot(n, v0) - level, h1 = vec3_dot(n, v1) - level, h2 = vec3_dot(n, v2) - level;
  if ((h0 < 0.0f) == (h1 < 0.0f) && (h1 < 0.0f) == (h2 < 0.0f)) return;
  footprint_clip_triangle(c, v0, v1, v2, h0, h1, h2);
}

/* Whether the child box (stored in its parent's node, scene_bvh.h) overlaps [lo, hi] and
   straddles the lifted plane n . x = level: a box wholly on one side holds no triangle that
   crosses it (the surface the photon hit, its coplanar neighbours, a ceiling above). */
PM_DEVICE int footprint_box_overlaps(float4 xy, float z_min, float z_max, Vec3 lo, Vec3 hi, Vec3 n, float level)
{
  if (!scene_boxes_meet(lo, hi, vec3(xy.x, xy.z, z_min), vec3(xy.y, xy.w, z_max))) return 0;
  float cx = 0.5f * (xy.x + xy.y), cy = 0.5f * (xy.z + xy.w), cz = 0.5f * (z_min + z_max);
  float reach = 0.5f * (pm_fabsf(n.x) * (xy.y - xy.x) + pm_fabsf(n.y) * (xy.w - xy.z) + pm_fabsf(n.z) * (z_max - z_min));
  return pm_fabsf(n.x * cx + n.y * cy + n.z * cz - level) <= reach;
}

/* Every triangle whose BVH leaf overlaps the lifted ellipse's box. The traversal keeps its
   values in locals (the clip state is touched only for triangles that cross the lifted plane). */
PM_DEVICE void footprint_clip_scan(const KernelGlobals* kg, FootprintClip* c)
{
  Vec3 a_u = c->a_u, a_v = c->a_v, n = c->n;
  Vec3 ext = vec3(pm_sqrtf(a_u.x * a_u.x + a_v.x * a_v.x), pm_sqrtf(a_u.y * a_u.y + a_v.y * a_v.y),
                  pm_sqrtf(a_u.z * a_u.z + a_v.z * a_v.z));
  Vec3 mid = vec3_madd(c->center, n, c->height);
  Vec3 lo = vec3_sub(mid, ext), hi = vec3_add(mid, ext);
  float level = vec3_dot(n, mid);
  int stack[PM_TRAVERSAL_STACK];
  int sp = 0, node = 0;
  for (;;) {
    float4 n0 = PM_LOAD(&kg->scene_nodes[4 * node + 0]);
    float4 n1 = PM_LOAD(&kg->scene_nodes[4 * node + 1]);
    float4 n2 = PM_LOAD(&kg->scene_nodes[4 * node + 2]);
    float4 n3 = PM_LOAD(&kg->scene_nodes[4 * node + 3]);
    int child0 = PM_AS_INT(n3.x), child1 = PM_AS_INT(n3.y);
    int count0 = PM_AS_INT(n3.z), count1 = PM_AS_INT(n3.w);
    int visit0 = child0 >= 0 && footprint_box_overlaps(n0, n2.x, n2.y, lo, hi, n, level);
    int visit1 = child1 >= 0 && footprint_box_overlaps(n1, n2.z, n2.w, lo, hi, n, level);
    for (int side = 0; side < 2; ++side) {
      int first = side ? child1 : child0, count = side ? count1 : count0;
      if (!(side ? visit1 : visit0) || count == 0) continue;
      /* Two triangles a step, both loaded before either is tested: a footprint that meets
         hundreds of small triangles runs alone at the end of the launch, where each step waits
         for its loads (docs/benchmarks.md, "the footprint stage's spread"). */
      for (int t = first; t < first + count; t += 2) {
        int second = t + 1 < first + count ? t + 1 : t;
        float4 a0 = PM_LOAD(&kg->triangles[3 * t]), a1 = PM_LOAD(&kg->triangles[3 * t + 1]);
        float4 a2 = PM_LOAD(&kg->triangles[3 * t + 2]);
        float4 b0 = PM_LOAD(&kg->triangles[3 * second]), b1 = PM_LOAD(&kg->triangles[3 * second + 1]);
        float4 b2 = PM_LOAD(&kg->triangles[3 * second + 2]);
        footprint_clip_record(c, a0, a1, a2, n, level);
        if (second != t) footprint_clip_record(c, b0, b1, b2, n, level);
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
}

/* Clips f (in the plane of the unit normal n, which faces the photon's side) against the
   triangles around its hit at `center`: shrinks f in place when a third wall asks for it and
   returns the cuts in the disc coordinates of the result, with the kept fraction of the kernel
   `shape`. offset: the ray offset of the hit (ray.h), the least height of the lifted plane. */
PM_DEVICE FootprintCut footprint_clip(const KernelGlobals* kg, Footprint* f, Vec3 center, Vec3 n, float offset,
                                      uint shape)
{
  FootprintClip c;
  c.a_u = f->axis_u;
  c.a_v = f->axis_v;
  c.center = center;
  c.n = n;
  c.height = pm_fmaxf(PM_FOOTPRINT_CLIP_HEIGHT * vec3_length(f->axis_n), offset);
  c.cut = footprint_uncut();
  float area = vec3_dot(vec3_cross(c.a_u, c.a_v), n);
  if (!(pm_fabsf(area) > 0.0f) || !pm_isfinite(area)) return c.cut;
  c.row_u = vec3_scale(vec3_cross(c.a_v, n), 1.0f / area);
  c.row_v = vec3_scale(vec3_cross(n, c.a_u), 1.0f / area);
  footprint_clip_scan(kg, &c);
  FootprintCut cut = c.cut;
  if (cut.shrink < 1.0f) {
    f->axis_u = vec3_scale(f->axis_u, cut.shrink);
    f->axis_v = vec3_scale(f->axis_v, cut.shrink);
    f->axis_n = vec3_scale(f->axis_n, cut.shrink);
    for (int k = 0; k < cut.count; ++k) cut.t[k] /= cut.shrink; /* disc coordinates grow by 1 / shrink */
  }
  cut.kept = footprint_kept_fraction(cut.mu, cut.mv, cut.t, cut.count, shape);
  for (int k = cut.count; k < PM_FOOTPRINT_CUTS; ++k) {
    cut.mu[k] = 0.0f;
    cut.mv[k] = 0.0f;
    cut.t[k] = 1.0f;
  }
  return cut;
}

#endif
