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
  /* S2 photon hits, slot order [photon * hit_slots_per_photon + k] */                       \
  X(float4, hit_position)   /* xyz */                                                         \
  X(float4, hit_normal)     /* xyz facing the photon's side, w = PM_HIT_* flags as uint bits */\
  X(float4, hit_incident)   /* xyz unit direction back towards where it came from, w = Delta */\
  X(float4, hit_flux)       /* rgb watts */                                                   \
  X(float4, hit_dp_u)       /* positional differentials (eq. 8 scaling) */                    \
  X(float4, hit_dp_v)                                                                          \
  /* S3 footprints, slot order */                                                              \
  X(float4, footprint_lo)   /* AABB of the footprint ellipsoid */                             \
  X(float4, footprint_hi)                                                                      \
  X(float4, footprint_center) /* xyz hit position, w = flags */                               \
  X(float4, footprint_row_u)  /* rows of the inverse ellipsoid basis: local = rows . (x - c) */\
  X(float4, footprint_row_v)                                                                   \
  X(float4, footprint_row_n)                                                                   \
  X(float4, footprint_power)  /* rgb flux / footprint area (irradiance of a uniform kernel) */ \
  X(float4, footprint_cut)    /* second cut (mu, mv, t) of a clipped footprint, footprint_clip.h */\
  X(float4, footprint_partials) /* per tile: (bounds lo, area sum), (bounds hi, valid count) */\
  /* S4 photon map, sorted order */                                                            \
  X(float4, map_nodes)      /* 4 float4 per inner node, photon_map.h */                       \
  X(uint, map_node_parent)                                                                     \
  X(uint, map_leaf_parent)                                                                     \
  X(uint, map_visits)                                                                          \
  X(float4, map_lo)         /* sorted footprint AABBs */                                      \
  X(float4, map_hi)                                                                            \
  X(float4, map_center)     /* sorted copies of the footprint_* gather data */               \
  X(float4, map_row_u)                                                                         \
  X(float4, map_row_v)                                                                         \
  X(float4, map_row_n)                                                                         \
  X(float4, map_power)                                                                         \
  X(float4, map_incident)                                                                      \
  X(float4, map_cut)                                                                           \
  X(uint, gather_stats)     /* [0] hits accepted, [1] shading points, when collect_stats */   \
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
