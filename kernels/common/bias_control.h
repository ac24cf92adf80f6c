/* The bias control of the error estimate: a sparse, unbiased check of whatever method filled the
   film. One control pixel per control_stride x control_stride block of the image (its position
   in the block drawn per frame) gets control_samples more paths of the reference path tracer
   (path_trace.h) from the camera pass's shading points, with the same mirror weights as the film.
   Their sums are kept per control pixel across launches, so the control grows more precise the
   longer a frame renders; the host compares them with the film's indirect + caustic light at the
   same pixels (render/bias_control.cpp). A photon or radiosity image that is 15 % too dark in its
   corners then says so, where the even/odd noise estimate alone (film.h) cannot see a bias at all.

   Per control pixel, control_sums holds (sum of the paths' indirect radiance rgb, sum of the
   squares of their channel means) over every launch of the frame (the host counts the paths),
   and control_film the film's resolved indirect + caustic light there at the latest launch, with
   its odd passes' mean (channel mean) in w when film_odd_passes is set, from which the host
   tells the film's own noise there from its bias. A launch shares each control pixel's paths
   out over control_lanes work items (a thousand control pixels alone would leave a GPU nearly
   idle, one thread running every path of its pixel in turn), each writing its sums to control_partials; a second kernel
   adds the lanes in order, so the sums do not depend on the device's scheduling. Random numbers: the path
   tracer's stream, keyed by (seed ^ PM_STREAM_CONTROL, frame), so the control never shares a path
   with a --method path render of the same seed. */
#ifndef PM_BIAS_CONTROL_H
#define PM_BIAS_CONTROL_H

#include "path_trace.h"

#define PM_STREAM_CONTROL 0x43544c52u /* "CTLR" */

/* The pixel of control item c, or 0 when the block lies outside the image. */
PM_DEVICE int control_pixel(const LaunchParams* p, uint c, uint* pixel)
{
  uint stride = p->control_stride > 0u ? p->control_stride : 1u;
  uint blocks_x = (p->width + stride - 1u) / stride;
  uint bx = c % blocks_x, by = c / blocks_x;
  uint x0 = bx * stride, y0 = by * stride;
  if (y0 >= p->height) return 0;
  uint w = pm_min_u(stride, p->width - x0), h = pm_min_u(stride, p->height - y0);
  Uniform4 u = rng_uniform4(p->seed ^ PM_STREAM_CONTROL, p->frame, c, 0u, PM_STREAM_CONTROL);
  uint x = x0 + pm_min_u((uint)(u.u0 * (float)w), w - 1u);
  uint y = y0 + pm_min_u((uint)(u.u1 * (float)h), h - 1u);
  *pixel = y * p->width + x;
  return 1;
}

/* Work item = (control pixel c, lane l), item = c * control_lanes + l: the lane's share of the
   launch's paths, samples l, l + lanes, ... (its first and stride), at the pixel, and the
   parameters its paths take (the control's stream). Returns 0 when the block lies outside the
   image. */
typedef struct ControlLane {
  uint pixel, first, stride;
} ControlLane;

PM_DEVICE int control_lane(const LaunchParams* p, uint item, ControlLane* lane, LaunchParams* paths)
{
  uint lanes = p->control_lanes > 0u ? p->control_lanes : 1u;
  if (!control_pixel(p, item / lanes, &lane->pixel)) return 0;
  lane->first = item % lanes;
  lane->stride = lanes;
  *paths = *p;
  paths->seed = p->seed ^ PM_STREAM_CONTROL;
  paths->path_frame = p->frame;
  return 1;
}

/* One path's value into a lane's sums: its rgb, and the square of its channel mean. */
PM_DEVICE void control_add_path(Vec3 value, Vec3* sum, float* squares)
{
  if (!pm_isfinite(value.x + value.y + value.z)) return; /* counted, as zero: never poisons the sums */
  *sum = vec3_add(*sum, value);
  float mean = (value.x + value.y + value.z) * (1.0f / 3.0f);
  *squares += mean * mean;
}

/* The lane's paths of the reference path tracer, their sums into control_partials[item]. */
PM_DEVICE void kernel_bias_control(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  ControlLane lane;
  LaunchParams q;
  if (!control_lane(p, item, &lane, &q)) return;
  Vec3 sum = vec3_splat(0.0f);
  float squares = 0.0f;
  for (uint s = lane.first; s < p->control_samples; s += lane.stride) {
    Vec3 path = vec3_splat(0.0f);
    EyePath eye = eye_path_begin(lane.pixel);
    ShadingPoint sp;
    for (uint depth = 0; eye_path_next(kg, p, &eye, &sp); ++depth) {
      Vec3 l = path_radiance(kg, &q, &sp.material, sp.position, sp.normal, sp.outgoing, lane.pixel, depth,
                             p->control_first_sample + s);
      path = vec3_add(path, vec3_mul(sp.weight, l));
    }
    control_add_path(path, &sum, &squares);
  }
  kg->control_partials[item] = vec3_to_float4(sum, squares);
}

/* Work item = control pixel: the launch's lanes added to its sums in lane order (none when the
   launch had no paths: control_samples 0 only reads the film), and the film read there. */
PM_DEVICE void kernel_bias_control_sum(const KernelGlobals* kg, const LaunchParams* p, uint c)
{
  uint pixel;
  if (!control_pixel(p, c, &pixel)) return;
  if (p->control_samples > 0u) {
    uint lanes = p->control_lanes > 0u ? p->control_lanes : 1u;
    float4 total = kg->control_sums[c];
    for (uint lane = 0; lane < lanes; ++lane) {
      float4 part = kg->control_partials[c * lanes + lane];
      total = PM_MAKE_FLOAT4(total.x + part.x, total.y + part.y, total.z + part.z, total.w + part.w);
    }
    kg->control_sums[c] = total;
  }
  float inv_passes = 1.0f / (float)(p->film_passes > 0u ? p->film_passes : 1u);
  Vec3 film = vec3_scale(vec3_add(vec3_from_float4(kg->film_indirect_sum[pixel]), film_caustic(kg, p, pixel)), inv_passes);
  float odd_mean = 0.0f;
  if (p->film_odd_passes > 0u) {
    Vec3 odd = film_odd_sum(kg, pixel);
    odd_mean = (odd.x + odd.y + odd.z) * (1.0f / 3.0f) / (float)p->film_odd_passes;
  }
  kg->control_film[c] = vec3_to_float4(film, odd_mean);
}

#endif
