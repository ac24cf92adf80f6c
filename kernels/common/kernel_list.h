/* Every device kernel, listed once (X-macro). Kernel NAME is the shared function
   kernel_NAME(const KernelGlobals*, const LaunchParams*, uint index) in kernels/common/;
   backends generate their entry points from this list and the host its KernelId enum. */
#ifndef PM_KERNEL_LIST_H
#define PM_KERNEL_LIST_H

#define PM_KERNEL_LIST(K)                                                                     \
  K(camera_pass)       /* S5: eye rays, mirror recursion, direct light, shading points */    \
  K(photon_trace)      /* S1+S2: emit, trace, record hits with differentials */              \
  K(photon_footprint_scale) /* S3: per-tile footprint area at s = 1 (automatic smoothing) */ \
  K(photon_footprint)  /* S3: footprints of the sorted hits, clipped, stashed for the probes */ \
  K(photon_footprint_probe)      /* S3: coverage, one work item per probe of the first pattern */ \
  K(photon_footprint_pattern)    /* S3: coverage, the first pattern's sums; footprints at edges */ \
  K(photon_footprint_edge_probe) /* S3: coverage, the second pattern of footprints at edges */   \
  K(photon_footprint_coverage)   /* S3: coverage, both patterns of a footprint in one work item (CPUs) */ \
  K(photon_footprint_rim)        /* S3: coverage, the share and rim of footprints at edges */    \
  K(photon_footprint_store)      /* S3: AABBs, gather data and area of the sorted hits */       \
  K(photon_reduce)     /* S4: per-tile hit bounds and count (Morton bounds, compaction) */  \
  K(photon_morton)     /* S4: 30-bit Morton keys (empty slots sort last) */                  \
  K(photon_map_nodes)  /* S4: Karras radix tree inner nodes */                               \
  K(photon_map_bottom_up) /* S4: boxes, counts, leaf fusion under T */                       \
  K(photon_map_area)      /* S3: per-tile footprint area of the sorted hits (T_auto) */       \
  K(gather_tile_bounds) /* S6: per pixel tile, its first shading points' box (gather_tiles.h) */ \
  K(gather)            /* S6: indirect and caustic radiance at every shading point */        \
  K(facet_gather)      /* S6 with --facet-weighting: photons weighed by what they deliver on tilted facets */ \
  K(knn_gather)        /* S6 for knn: the k nearest photons over their region's covered area */ \
  K(final_gather)      /* S6 with final gathering: rays from every shading point, the map at their hits */ \
  K(path_trace)        /* path tracer: paths from every shading point into film_indirect_sum */ \
  K(film_layers)       /* S7: albedo, normal, depth, position, ids from the shading points */  \
  K(film_error_tiles)  /* S7: per-tile sums for the error estimate from even and odd passes */ \
  K(bias_control)      /* S7: paths at sparse control pixels beside the film, for the error's bias */ \
  K(bias_control_sum)  /* S7: the control's lanes summed per control pixel, the film read there */ \
  K(radiosity_link_trace)   /* radiosity: nC rays per element of a batch, barycentric links */ \
  K(radiosity_link_merge)   /* radiosity: an element's links to one element combined */        \
  K(radiosity_link_store)   /* radiosity: merged links, compact, at host-computed offsets */   \
  K(radiosity_light_links)  /* radiosity: eq. 2 from every light, bounce-0 radiance */         \
  K(radiosity_gather)       /* radiosity: one bounce over the links (eq. 3, 4) */              \
  K(radiosity_smooth)       /* radiosity: one-ring smoothing within alpha_f (eq. 5, 6) */      \
  K(radiosity_interpolate)  /* radiosity: vertex irradiance at the shading points, film */     \
  K(radiosity_final_gather) /* radiosity with final gathering: rays from every shading point, the solution at their hits */ \
  K(radiosity_bias_probe)   /* radiosity with final gathering: its bias along the control's paths (--method auto) */ \
  K(sort_histogram)    /* portable radix sort: per tile and digit, its count, added to totals */\
  K(sort_scatter)      /* portable radix sort: per tile and digit, its keys moved in order */\
  K(layout_probe)      /* writes sizeof/offsetof of shared structs for the layout test */

#endif
