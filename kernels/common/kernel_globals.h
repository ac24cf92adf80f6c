/* The buffers a stage function sees: one pointer per entry of PM_BUFFER_LIST. The CUDA backend
   keeps one KernelGlobals in constant memory, written when the host's bindings change (once per
   frame); the OpenCL backend gathers its kernel arguments into one per launch. Unbound buffers
   are null. */
#ifndef PM_KERNEL_GLOBALS_H
#define PM_KERNEL_GLOBALS_H

#include "buffers.h"
#include "types.h"

typedef struct KernelGlobals {
#define PM_GLOBALS_MEMBER(group, type, name, extent, per) PM_GLOBAL type* name;
  PM_BUFFER_LIST(PM_GLOBALS_MEMBER)
#undef PM_GLOBALS_MEMBER
} KernelGlobals;

#endif
