/* Every device kernel, listed once (X-macro). Kernel NAME is the shared function
   kernel_NAME(const KernelGlobals*, const LaunchParams*, uint index) in kernels/common/;
   backends generate their entry points from this list and the host its KernelId enum. */
#ifndef PM_KERNEL_LIST_H
#define PM_KERNEL_LIST_H

#define PM_KERNEL_LIST(K)                                                                     \
  K(camera_pass)       /* S5: eye rays, mirror recursion, direct light, shading points */    \
  K(film_resolve)      /* S7: combined = direct + indirect + caustic, NaN guard */           \
  K(sort_histogram)    /* portable radix sort: per-tile digit counts */                      \
  K(sort_scan_chunks)  /* portable radix sort: exclusive scan within chunks of counts */     \
  K(sort_scan_totals)  /* portable radix sort: exclusive scan of chunk totals */             \
  K(sort_scatter)      /* portable radix sort: stable scatter of one digit */               \
  K(layout_probe)      /* writes sizeof/offsetof of shared structs for the layout test */

#endif
