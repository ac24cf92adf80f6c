/* The buffers a stage function sees: one pointer per entry of PM_BUFFER_LIST, gathered into a
   private struct by the backend's entry point. Unbound buffers are null. */
#ifndef PM_KERNEL_GLOBALS_H
#define PM_KERNEL_GLOBALS_H

#include "buffers.h"
#include "types.h"

typedef struct KernelGlobals {
#define PM_GLOBALS_MEMBER(type, name) PM_GLOBAL type* name;
  PM_BUFFER_LIST(PM_GLOBALS_MEMBER)
#undef PM_GLOBALS_MEMBER
} KernelGlobals;

#endif
