/* Reports the device compiler's view of the shared structs and echoes the launch parameters it
   received, so a test can prove host and device agree on every size, offset and the by-value
   argument passing (portable-kernels rule 4); tests/support/device_checks.h reads the slots. */
#ifndef PM_LAYOUT_PROBE_H
#define PM_LAYOUT_PROBE_H

#include "kernel_globals.h"

#define PM_OFFSET_OF(object, member) ((uint)((char*)&(object).member - (char*)&(object)))

PM_DEVICE void kernel_layout_probe(const KernelGlobals* kg, const LaunchParams* p, uint unused)
{
  LaunchParams probe;
  PM_GLOBAL uint* out = kg->layout_probe;
  out[0] = (uint)sizeof(Material);
  out[1] = (uint)sizeof(PointLight);
  out[2] = (uint)sizeof(CameraParams);
  out[3] = (uint)sizeof(LaunchParams);
  out[4] = PM_OFFSET_OF(probe, width);
  out[5] = PM_OFFSET_OF(probe, mirror_depth);
  out[6] = PM_OFFSET_OF(probe, ray_epsilon);
  out[7] = PM_OFFSET_OF(probe, sort_tile_count);
  /* Echo of by-value arguments: the host sets recognisable values. */
  out[8] = p->width;
  out[9] = p->sort_tile_count;
  out[10] = PM_AS_UINT(p->camera.up.w);
  out[11] = PM_AS_UINT(p->ray_epsilon);
}

#endif
