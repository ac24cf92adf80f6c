/* The bias of final gathering over a radiosity solution, measured directly (--method auto's
   floor under it; render/error_forecast.h). Final gathering reads the solution one bounce from
   the shading point, so its image converges to E[f L_s(y)], L_s the radiance the solution and
   the exact direct light send from the gather ray's hit y, where the truth is E[f L(y)]; the
   difference is a bias that more gather rays cannot remove. The error control's paths
   (bias_control.h) sample the same first directions from the same lobes with the same weights
   (path_first_direction), so along each control path
       delta = path_radiance(x) - beta * final_gather_ray(x, dir)
   has, per pixel, the truth there less the mean of final gathering's image: its bias negated, with no
   noise of final gathering's own rays in it, and the direct light at y the same exact shadow rays
   in both terms (point and spot lights cancel; area lights and the environment are sampled once
   in each). The host reads these sums as the paths of a control against a film
   of zeros, whose error is then the estimate less the truth (render/bias_control.cpp, paired_bias).

   Work item = (control pixel c, lane l), item = c * control_lanes + l, as kernel_bias_control: the
   lane's share of the launch's paths (the control's stream, samples control_first_sample + l,
   + lanes, ...), its sum of delta (rgb) and of the squares of delta's channel mean into
   control_partials[item]; kernel_bias_control_sum adds the lanes. */
#ifndef PM_RADIOSITY_BIAS_PROBE_H
#define PM_RADIOSITY_BIAS_PROBE_H

#include "bias_control.h"
#include "final_gather.h"

PM_DEVICE void kernel_radiosity_bias_probe(const KernelGlobals* kg, const LaunchParams* p, uint item)
{
  ControlLane lane;
  LaunchParams q;
  if (!control_lane(p, item, &lane, &q)) return;
  Vec3 sum = vec3_splat(0.0f);
  float squares = 0.0f;
  for (uint s = lane.first; s < p->control_samples; s += lane.stride) {
    uint path = p->control_first_sample + s;
    Vec3 delta = vec3_splat(0.0f);
    EyePath eye = eye_path_begin(lane.pixel);
    ShadingPoint sp;
    for (uint depth = 0; eye_path_next(kg, p, &eye, &sp); ++depth) {
      const Material* m = &sp.material;
      Vec3 dir;
      Vec3 beta = path_first_direction(&q, m, sp.normal, sp.outgoing, lane.pixel, depth, path, &dir);
      if (vec3_max_component(beta) <= 0.0f) continue;
      Vec3 origin = offset_ray_origin(sp.position, sp.normal, ray_offset_distance(sp.position, 0.0f, p->ray_epsilon));
      uint accepted = 0;
      Vec3 gathered = vec3_mul(beta, final_gather_ray(kg, &q, origin, dir, lane.pixel, depth << 8, path, &accepted,
                                                      PM_FINAL_GATHER_RADIOSITY));
      Vec3 traced = path_radiance(kg, &q, m, sp.position, sp.normal, sp.outgoing, lane.pixel, depth, path);
      delta = vec3_add(delta, vec3_mul(sp.weight, vec3_sub(traced, gathered)));
    }
    control_add_path(delta, &sum, &squares);
  }
  kg->control_partials[item] = vec3_to_float4(sum, squares);
}

#endif
