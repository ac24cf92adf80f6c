/* The gather's pixel tiles walking the photon map together (S6, on devices whose lanes run in
   lockstep). A pixel's own walk of the map (photon_map_query_begin at its shading point) takes
   its own path through the tree, so the 32 lanes of a warp meet their candidate photons at
   different steps: the footprint gather ran 11 of 32 lanes per warp instruction, each lane
   loading other photons than its neighbours (docs/benchmarks.md). Here the lanes of a pixel tile
   (pixel_order.h: 8 x 4 pixels, one warp) walk the map with one box, the bounds of the tile's
   first shading points: the same nodes and photons in the same order on every lane, one load
   serving them all, and each lane keeps the photons whose own box holds its point. Those are the
   photons its point query finds, in the order it finds them (photon_map_query_begin_box), so the
   sums are the same bits either way.

   A tile whose points spread wider than the footprints (a silhouette against a far wall, a
   grazing floor) would walk many photons that none of its points needs: when its box's diagonal
   exceeds the pass's reach (p->tile_gather_reach, a multiple of the footprints' mean radius set
   by the host), its points walk alone, as do the points behind mirrors and every point on a CPU,
   where work items do not run in lockstep and the shared walk is only extra work. */
#ifndef PM_GATHER_TILES_H
#define PM_GATHER_TILES_H

#include "camera_pass.h"
#include "kernel_globals.h"
#include "pixel_order.h"

/* Relative margin of a tile's box: the gather replays each position (eye_path_next) by the same
   operations, but a compiler may contract them differently in another kernel, which moves the
   last bits. A wider box only adds candidates, which the lanes' own tests drop. */
#define PM_GATHER_TILE_MARGIN 1e-5f

/* Work item = pixel tile (pixel_order.h): the box of its pixels' first shading points in
   gather_tiles[2 tile] (lo, w = the points' count) and [2 tile + 1] (hi). The points are those of
   the camera pass, replayed as the gather replays them; the box does not change between passes. */
PM_DEVICE void kernel_gather_tile_bounds(const KernelGlobals* kg, const LaunchParams* p, uint tile)
{
  Vec3 lo = vec3_splat(1e30f), hi = vec3_splat(-1e30f);
  float farthest = 0.0f;
  uint points = 0u;
  for (uint i = 0u; i < PM_TILE_W * PM_TILE_H; ++i) {
    uint pixel;
    if (!pixel_of_work_item(tile * (PM_TILE_W * PM_TILE_H) + i, p->width, p->height, &pixel)) continue;
    float2 hit = kg->shade_hit[pixel];
    if (PM_AS_INT(hit.y) < 0) continue;
    Ray camera = camera_primary_ray(&p->camera, pixel % p->width, pixel / p->width, p->width, p->height);
    Vec3 x = vec3_madd(camera.origin, camera.direction, hit.x);
    lo = vec3_min(lo, x);
    hi = vec3_max(hi, x);
    farthest = pm_fmaxf(farthest, hit.x);
    ++points;
  }
  Vec3 eye = vec3_from_float4(p->camera.position);
  float scale = pm_fmaxf(pm_fmaxf(pm_fabsf(eye.x), pm_fabsf(eye.y)), pm_fabsf(eye.z)) + farthest;
  Vec3 margin = vec3_splat(PM_GATHER_TILE_MARGIN * scale);
  kg->gather_tiles[2u * tile] = vec3_to_float4(vec3_sub(lo, margin), (float)points);
  kg->gather_tiles[2u * tile + 1u] = vec3_to_float4(vec3_add(hi, margin), 0.0f);
}

/* Whether the lanes of work item `item`'s tile walk the photon map with their tile's box, and
   that box: a tile with points whose box's diagonal is within the pass's reach. */
PM_DEVICE int gather_tile_box(const KernelGlobals* kg, const LaunchParams* p, uint item, Vec3* lo, Vec3* hi)
{
  if (!(p->tile_gather_reach > 0.0f)) return 0;
  uint tile = item / (PM_TILE_W * PM_TILE_H);
  float4 tile_lo = PM_LOAD(&kg->gather_tiles[2u * tile]), tile_hi = PM_LOAD(&kg->gather_tiles[2u * tile + 1u]);
  if (!(tile_lo.w > 0.0f)) return 0;
  *lo = vec3_from_float4(tile_lo);
  *hi = vec3_from_float4(tile_hi);
  Vec3 diagonal = vec3_sub(*hi, *lo);
  return vec3_dot(diagonal, diagonal) <= p->tile_gather_reach * p->tile_gather_reach;
}

#endif
