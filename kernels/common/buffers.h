/* Every device buffer, listed once (X-macro). Each backend expands the list into kernel
   parameters, kernel_globals.h into the KernelGlobals struct the stage functions read, and the
   host into the BufferSlot enum it binds allocations to. Adding a buffer is one line here. */
#ifndef PM_BUFFERS_H
#define PM_BUFFERS_H

#define PM_BUFFER_LIST(X)                                                                      \
  /* S0 scene, uploaded once per sequence */                                                   \
  X(float4, scene_nodes)    /* BVH2, 4 float4 per node, child boxes stored in the parent */    \
  X(float4, triangles)      /* 3 float4 per triangle in BVH leaf order; v0.w = material */     \
  X(Material, materials)                                                                       \
  X(PointLight, lights)                                                                        \
  /* S5 camera: one shading point per pixel and mirror depth, [depth * pixels + pixel] */     \
  X(float4, shade_position) /* xyz, w = material index as int bits, -1 when the path ended */  \
  X(float4, shade_normal)   /* xyz geometric normal facing the viewer */                      \
  X(float4, shade_outgoing) /* xyz direction towards the viewer */                            \
  X(float4, shade_weight)   /* rgb product of mirror reflectances along the eye path */       \
  /* S7 film layers, one float4 per pixel (rgb, w unused) */                                  \
  X(float4, film_direct)                                                                       \
  X(float4, film_indirect)                                                                     \
  X(float4, film_caustic)                                                                      \
  X(float4, film_combined)                                                                     \
  /* portable radix sort (OpenCL backend; CUDA uses CUB) */                                   \
  X(uint, sort_keys)                                                                           \
  X(uint, sort_values)                                                                         \
  X(uint, sort_keys_alt)                                                                       \
  X(uint, sort_values_alt)                                                                     \
  X(uint, sort_histogram)                                                                      \
  /* host/device layout agreement check */                                                     \
  X(uint, layout_probe)

#endif
