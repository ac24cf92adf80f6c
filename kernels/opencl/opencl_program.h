// Building a device's OpenCL program: from the on-disk program cache (render/program_cache.h)
// when it holds a binary for exactly this source, these build options and this driver, else from
// source, writing the binary to the cache for the next process. Compiling the kernels from source
// takes seconds on NVIDIA's OpenCL; a cached binary skips the OpenCL C compiler.
#pragma once

#include <CL/cl.h>

#include <cstddef>
#include <string>

#include "render/program_cache.h"
#include "render/startup_timing.h"

namespace pm {

struct OpenclProgramRequest {
  cl_context context = nullptr;
  cl_device_id device = nullptr;
  cl_platform_id platform = nullptr;
  const char* source = nullptr;
  size_t source_size = 0;
  std::string options;  // clBuildProgram's options, part of the cache key
};

// Everything that decides whether a cached binary fits the request.
ProgramCacheKey opencl_program_key(const OpenclProgramRequest& request);

// The built program (the caller releases it). Adds a "program" step to startup saying where the
// program came from, sets startup.program_cache, and on trouble with the cache adds a note (an
// entry refused: rebuilt from source) or sets the once-per-process warning (the cache folder is
// not writable); the cache never makes it fail. Throws DeviceError with the driver's build log
// when the source does not build.
cl_program build_opencl_program(const OpenclProgramRequest& request, const ProgramCache& cache, DeviceStartup& startup);

}  // namespace pm
