/* Every device buffer, listed once (X-macro). Each backend expands the list into its kernel
   globals, kernel_globals.h into the KernelGlobals struct the stage functions read, and the host
   into the BufferSlot enum and the buffer table (render/buffer_table.h) that allocates, binds,
   resizes and frees every buffer. Adding a buffer is one line here.

   X(group, type, name, extent, per):
     group   who owns it and how long it lives: scene (uploaded once per renderer), frame (sized
             by the resolution), a method's group (photon, ...: sized by its pass), backend
             (scratch a backend binds itself), test (bound by tests only)
     type    element type, shared with the host (types.h)
     extent  the BufferExtents field that counts its elements, times per; "uploaded" buffers
             are sized by the data uploaded into them */
#ifndef PM_BUFFERS_H
#define PM_BUFFERS_H

/* The bias control's work items per control pixel at most (bias_control.h): its paths shared out
   so that a launch over about a thousand control pixels fills a GPU. */
#define PM_CONTROL_LANES 64u

/* Buffers that take a second role while their first is spent within a photon pass. The hit
   records are read last by the footprints (S3) and the sorted slots too; the photon map's tree is
   built after them, and read until the next pass traces again. The map's n - 1 inner nodes (4
   float4 each, photon_map.h) and then its build links (a parent per inner node and per leaf, n
   words each) fit in the records of its n valid hits (5 float4 each), its visit counters in the
   sorted slots. The sort's input (the valid hits' Morton keys and slots, its scratch once sorted)
   lives in two of the gather arrays, which the footprints write only after the sort. So the map
   holds no memory of its own for any of them. */
#define PM_MAP_NODES(kg) ((kg)->hit_records)
#define PM_MAP_NODE_PARENT(kg, n) ((PM_GLOBAL uint*)((kg)->hit_records + 4u * ((n) - 1u)))
#define PM_MAP_LEAF_PARENT(kg, n) (PM_MAP_NODE_PARENT(kg, n) + (n))
#define PM_MAP_VISITS(kg) ((kg)->sorted_slots)
#define PM_SORT_KEYS_BUFFER map_row_u  /* the buffer that holds the sort's input keys */
#define PM_SORT_SLOTS_BUFFER map_row_v /* and its input slots */
#define PM_SORT_KEYS(kg) ((PM_GLOBAL uint*)((kg)->PM_SORT_KEYS_BUFFER))
#define PM_SORT_SLOTS(kg) ((PM_GLOBAL uint*)((kg)->PM_SORT_SLOTS_BUFFER))

#define PM_BUFFER_LIST(X)                                                                                   \
  /* S0 scene, uploaded once per renderer */                                                               \
  X(scene, float4, scene_nodes, uploaded, 1)  /* BVH2, 4 float4 per node, child boxes in the parent */      \
  X(scene, float4, triangles, uploaded, 1)    /* 3 float4 per triangle in BVH leaf order; v0.w = material */\
  X(scene, Material, materials, uploaded, 1)                                                               \
  X(scene, PointLight, lights, uploaded, 1)   /* re-uploaded when an animated light moves */               \
  /* area lights (area_lights.h), uploaded only when a material emits: null otherwise */                     \
  X(scene, float4, emitters, uploaded, 1)     /* PM_EMITTER_FLOAT4S per emitting triangle */                \
  X(scene, float4, material_emission, uploaded, 1) /* per material: rgb L_e (W sr^-1 m^-2), w = mean */     \
  /* the environment map (environment_map.h), uploaded only for a map: null otherwise */                   \
  X(scene, float4, environment_texels, uploaded, 1) /* W H: rgb radiance, w = pdf_uv; top row first */      \
  X(scene, float, environment_cdf, uploaded, 1) /* H: marginal CDF over rows, then W per row: conditional */\
  /* textures (texture.h), uploaded only when a material has one: null otherwise */                       \
  X(scene, float4, triangle_uvs, uploaded, 1) /* 2 per triangle in leaf order: (u0, v0, u1, v1), (u2, v2) */\
  X(scene, uint4, texture_info, uploaded, 1)  /* per texture: first texel, width, height, wrap bits */      \
  X(scene, uint, texels, uploaded, 1)         /* RGBA8 of every image, top row first; rgb sRGB-encoded */   \
  X(scene, float, texture_srgb_table, uploaded, 1) /* 256: the linear value of each 8-bit sRGB code */      \
  /* S5 camera: one shading point per pixel and mirror depth, [depth * pixels + pixel] */                  \
  X(frame, float2, shade_hit, shading_points, 1) /* x: the ray's distance to the hit, y = the hit */      \
                                                /* triangle (leaf order) as int bits, -1: none */          \
  /* (the position, the normal, the material, the direction towards the viewer and the mirrors' */       \
  /* product are replayed: eye_path_next) */                                                               \
  /* S7 film: direct light once per frame; indirect and caustic summed over passes (rgb); the odd */       \
  /* passes' indirect + caustic for the error estimate in the free w and a plane (film_odd_sum) */          \
  X(frame, float4, film_direct, pixels, 1)       /* w: the odd sum's red */                                 \
  X(frame, float4, film_indirect_sum, pixels, 1) /* w: its green */                                         \
  X(frame, float, film_odd_blue, pixels, 1)      /* its blue */                                             \
  X(frame, float4, film_caustic_sum, caustic_pixels, 1) /* only where mirrors make caustics; w unused */    \
  X(frame, float4, film_error_partials, error_tiles, 1) /* per tile: (sum |even - odd|, sum |all|, 0, 0) */ \
  /* extra layers (film_layers.h), allocated only when asked for: layer_pixels is 0 otherwise */            \
  X(frame, float4, film_albedo, layer_pixels, 1)   /* rgb albedo, w = first hit's material (int bits) */    \
  X(frame, float4, film_normal, layer_pixels, 1)   /* xyz normal, w = depth (camera to first hit) */        \
  X(frame, float4, film_position, layer_pixels, 1) /* xyz first hit, w = its object (int bits) */           \
  /* the error estimate's bias control (bias_control.h), one entry per control pixel */                    \
  X(frame, float4, control_sums, control_pixels, 1) /* paths' rgb sum, w = sum of squared channel means */ \
  X(frame, float4, control_film, control_pixels, 1) /* film's indirect + caustic; w = odd passes' mean */ \
  X(frame, float4, control_partials, control_pixels, PM_CONTROL_LANES) /* per lane of a launch, as control_sums */ \
  /* photon mapping, S1 emitters: per light (first photon of the pass, photon count, 0, 0) */              \
  X(photon, uint4, photon_emitters, uploaded, 1)                                                            \
  /* photon mapping, S2 hits: per slot [photon * hit_slots_per_photon + k] where its hit is recorded; */   \
  /* per record (photon_trace.h: only valid hits have one) the hit */                                      \
  X(photon, uint, hit_slots, hit_slots, 1)       /* PM_HIT_* flags | record << PM_HIT_RECORD_SHIFT, 0: none */\
  X(photon, float4, hit_records, hit_records, 5) /* 5 float4 per record (PM_RECORD_*, photon_trace.h); */ \
                                                 /* the photon map's nodes once spent (PM_MAP_NODES) */     \
  X(photon, uint, hit_record_count, counters, 2) /* [0] records the trace took (atomic), [1] their room; then [0] the footprints at edges (footprint_probes.h) */ \
  /* photon mapping, S3 footprints and S4 photon map: the valid hits in sorted order */                     \
  X(photon, float4, map_partials, bounds_tiles, 2) /* per tile: (lo, area sum), (hi, count) */              \
  X(photon, float4, map_lo, map_hits, 1)       /* footprint AABB; lo.w = footprint area */                  \
  X(photon, float4, map_hi, map_hits, 1)                                                                    \
  X(photon, float4, map_center, map_hits, 1)   /* hit position, w = flags */                                \
  X(photon, float4, map_row_u, map_hits, 1)    /* rows of the inverse ellipsoid basis, w: the first cut */  \
  X(photon, float4, map_row_v, map_hits, 1)                                                                 \
  X(photon, float4, map_row_n, map_hits, 1)                                                                 \
  X(photon, float4, map_power, map_hits, 1)    /* rgb flux / (ellipse area x covered share) */            \
  X(photon, float4, map_incident, map_hits, 1)                                                              \
  X(photon, float4, map_cut, map_hits, 1)      /* second cut of a clipped footprint (footprint_clip.h) */   \
  X(photon, uint, gather_stats, counters, 3)   /* [0] hits accepted, [1] shading points, [2] of them walked */ \
                                               /* with their tile's box (collect_stats) */                  \
  X(photon, float4, gather_tiles, gather_tiles, 2) /* S6 per pixel tile: its first shading points' box (lo, hi) */\
  X(photon, uint, map_tile_offsets, bounds_tiles, 1) /* S4: first compacted key of each tile's valid hits */\
  /* (the sort's input: PM_SORT_KEYS, PM_SORT_SLOTS above) */                                              \
  X(photon, uint, sorted_keys, map_hits, 1)    /* S4 output of the sort: keys ascending */                 \
  X(photon, uint, sorted_slots, map_hits, 1)   /* and their slots (the tree's visit counters later) */     \
  /* vertex link radiosity (render/radiosity/, docs/radiosity.md): the refined mesh, uploaded once */     \
  X(radiosity, float4, rad_elements, uploaded, 1)   /* 2 per element: (position, material bits), normal */ \
  X(radiosity, uint4, rad_element_ranges, uploaded, 1) /* elements + 1: first ring entry, neighbour, link word */\
  X(radiosity, uint, rad_adjacency, uploaded, 1)    /* one-ring entries (triangle << 2 | corner), then */  \
                                                    /* smoothing neighbours (element indices) */           \
  X(radiosity, float, rad_smooth_weights, uploaded, 1) /* per smoothing neighbour: its weight (eq. 5) */   \
  X(radiosity, float4, rad_tree, uploaded, 1)       /* refinement tree, 2 per node (radiosity_mesh.h) */   \
  X(radiosity, uint4, rad_triangles, uploaded, 1)   /* 2 per refined triangle: front, back elements */     \
  X(radiosity, uint, rad_links, uploaded, 1)        /* merged links, one word each (radiosity_links.h) */ \
  X(radiosity, float4, rad_texture_tint, uploaded, 1) /* textured scenes: mean texel rgb per element */  \
  /* vertex link radiosity, the solution: per element, two halves [0, E) and [E, 2E) to ping-pong */      \
  X(radiosity, float4, rad_radiance, elements, 2)   /* outgoing radiance of the last bounce, rgb */        \
  X(radiosity, float4, rad_irradiance, elements, 2) /* gathered indirect irradiance I_total (eq. 3) */     \
  /* vertex link radiosity, link build scratch: one batch of elements */                                  \
  X(radiosity, uint, rad_batch_links, link_scratch, 2) /* (target, weight bits) per ray and corner */      \
  X(radiosity, uint, rad_batch_counts, link_batch, 4)  /* link words, raw links, word offset, links */     \
  /* portable radix sort (OpenCL backend; CUDA uses CUB): bound by its driver to the pairs it sorts */   \
  X(backend, uint, sort_keys, uploaded, 1)                                                                \
  X(backend, uint, sort_values, uploaded, 1)                                                              \
  X(backend, uint, sort_keys_alt, uploaded, 1)                                                            \
  X(backend, uint, sort_values_alt, uploaded, 1)                                                          \
  X(backend, uint, sort_histogram, uploaded, 1)                                                           \
  /* host/device layout agreement check */                                                                 \
  X(test, uint, layout_probe, uploaded, 1)

#endif
