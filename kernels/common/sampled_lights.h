/* Next-event estimation of the lights that are sampled rather than evaluated: the area lights
   (area_lights.h) and the environment (environment_light.h). Both give a light sample of the
   same type (a direction, the irradiance estimate it carries and its density per solid angle),
   so one code path turns samples into reflected radiance for the camera pass (light samples
   alone) and for the path tracer (light samples weighed by MIS against BSDF sampling). */
#ifndef PM_SAMPLED_LIGHTS_H
#define PM_SAMPLED_LIGHTS_H

#include "area_lights.h"
#include "environment_light.h"

#define PM_SAMPLED_AREA_LIGHTS 0u
#define PM_SAMPLED_ENVIRONMENT 1u
#define PM_SAMPLED_LIGHT_KINDS 2u

/* Whether the scene has lights of this kind. */
PM_DEVICE int sampled_light_present(const LaunchParams* p, uint kind)
{
  return kind == PM_SAMPLED_AREA_LIGHTS ? p->emitter_count > 0u : p->environment != PM_ENVIRONMENT_NONE;
}

/* The random-number stream of this kind's samples. */
PM_DEVICE uint sampled_light_stream(uint kind)
{
  return kind == PM_SAMPLED_AREA_LIGHTS ? PM_STREAM_AREA : PM_STREAM_ENVIRONMENT;
}

/* One light sample of this kind seen from x (unit normal n; shadow ray `offset` off the surface). */
PM_DEVICE AreaLightSample sampled_light_sample(const KernelGlobals* kg, const LaunchParams* p, uint kind, Vec3 x, Vec3 n,
                                               float offset, Uniform4 u)
{
  return kind == PM_SAMPLED_AREA_LIGHTS ? area_light_sample(kg, p, x, n, offset, u)
                                        : environment_light_sample(kg, p, x, n, offset, u);
}

/* Radiance reflected towards wo from `samples` light samples of this kind, shadowed (camera pass:
   no BSDF sampling to combine with). Random numbers keyed by (seed, frame), counter (index,
   event + k, the kind's stream, extra). */
PM_DEVICE Vec3 sampled_light_direct(const KernelGlobals* kg, const LaunchParams* p, uint kind, const Material* m, Vec3 x,
                                    Vec3 n, Vec3 wo, float offset, uint samples, uint index, uint event, uint extra)
{
  Vec3 sum = vec3_splat(0.0f);
  if (!sampled_light_present(p, kind) || samples == 0u) return sum;
  for (uint k = 0; k < samples; ++k) {
    Uniform4 u = rng_uniform4_bits(rng_bits4(p->seed, p->frame, index, event + k, sampled_light_stream(kind), extra));
    AreaLightSample s = sampled_light_sample(kg, p, kind, x, n, offset, u);
    if (vec3_max_component(s.irradiance) <= 0.0f) continue;
    sum = vec3_add(sum, vec3_mul(brdf_eval(m, n, s.wi, wo), s.irradiance));
  }
  return vec3_scale(sum, 1.0f / (float)samples);
}

#endif
