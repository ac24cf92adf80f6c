/* The order in which work items visit pixels in the per-pixel stages (camera pass, gather, path
   tracing): blocks of PM_TILE_W x PM_TILE_H pixels, tiles in row-major order, so the 32 work
   items of a GPU warp shade a compact 8 x 4 block rather than a 32-pixel strip. Neighbouring
   pixels see nearby surfaces, so their rays and photon-map traversals take similar paths and
   the warp stays together. A launch covers whole tiles; items past the image's edge do nothing.
   Per-pixel buffers stay indexed by pixel (y * width + x): only the visiting order changes. */
#ifndef PM_PIXEL_ORDER_H
#define PM_PIXEL_ORDER_H

#define PM_TILE_W 8u
#define PM_TILE_H 4u

/* Work items of a launch over the image in tile order. */
PM_DEVICE uint pixel_work_items(uint width, uint height)
{
  uint tiles_x = (width + PM_TILE_W - 1u) / PM_TILE_W, tiles_y = (height + PM_TILE_H - 1u) / PM_TILE_H;
  return tiles_x * tiles_y * PM_TILE_W * PM_TILE_H;
}

/* The pixel of work item `item`, or 0 when the item lies past the image's edge. */
PM_DEVICE int pixel_of_work_item(uint item, uint width, uint height, uint* pixel)
{
  uint tile = item / (PM_TILE_W * PM_TILE_H), in_tile = item % (PM_TILE_W * PM_TILE_H);
  uint tiles_x = (width + PM_TILE_W - 1u) / PM_TILE_W;
  uint x = (tile % tiles_x) * PM_TILE_W + in_tile % PM_TILE_W;
  uint y = (tile / tiles_x) * PM_TILE_H + in_tile / PM_TILE_W;
  if (x >= width || y >= height) return 0;
  *pixel = y * width + x;
  return 1;
}

/* The tile (in row-major order) that holds `pixel`: the pixels one warp shades together. */
PM_DEVICE uint tile_of_pixel(uint pixel, uint width)
{
  uint tiles_x = (width + PM_TILE_W - 1u) / PM_TILE_W;
  return (pixel / width / PM_TILE_H) * tiles_x + (pixel % width) / PM_TILE_W;
}

#endif
