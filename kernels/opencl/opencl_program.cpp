// An OpenCL program from the program cache or from source (opencl_program.h).
#include "kernels/opencl/opencl_program.h"

#include <vector>

#include "kernels/opencl/opencl_check.h"
#include "render/errors.h"

namespace pm {

namespace {

std::string build_log(cl_program program, cl_device_id device) {
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
  while (!log.empty() && log.back() == '\0') log.pop_back();
  return log;
}

// The program from a cached binary, or null with why the driver refused it.
cl_program program_from_binary(const OpenclProgramRequest& r, const std::vector<unsigned char>& binary, std::string* why) {
  const size_t size = binary.size();
  const unsigned char* data = binary.data();
  cl_int binary_status = CL_SUCCESS, err = CL_SUCCESS;
  cl_program program = clCreateProgramWithBinary(r.context, 1, &r.device, &size, &data, &binary_status, &err);
  if (err != CL_SUCCESS || binary_status != CL_SUCCESS) {
    if (program) clReleaseProgram(program);
    *why = std::string("the driver refused the binary (") + cl_error_name(err != CL_SUCCESS ? err : binary_status) + ")";
    return nullptr;
  }
  err = clBuildProgram(program, 1, &r.device, r.options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS) {
    clReleaseProgram(program);
    *why = std::string("building the cached binary failed with ") + cl_error_name(err);
    return nullptr;
  }
  return program;
}

cl_program program_from_source(const OpenclProgramRequest& r) {
  cl_int err = CL_SUCCESS;
  const char* source = r.source;
  const size_t length = r.source_size;
  cl_program program = clCreateProgramWithSource(r.context, 1, &source, &length, &err);
  PM_CL_CHECK(err);
  err = clBuildProgram(program, 1, &r.device, r.options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS) {
    const std::string log = build_log(program, r.device);
    clReleaseProgram(program);
    throw DeviceError("OpenCL: building the kernels for " + device_string(r.device, CL_DEVICE_NAME) + " failed with " +
                      cl_error_name(err) + "; build log:\n" + log);
  }
  return program;
}

// The built program's binary for its one device; empty why on success.
std::string program_binary(cl_program program, std::vector<unsigned char>* binary) {
  size_t size = 0;
  cl_int err = clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof(size), &size, nullptr);
  if (err != CL_SUCCESS) return std::string("CL_PROGRAM_BINARY_SIZES: ") + cl_error_name(err);
  if (size == 0) return "the driver gives no program binary";
  binary->resize(size);
  unsigned char* data = binary->data();
  err = clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof(data), &data, nullptr);
  if (err != CL_SUCCESS) return std::string("CL_PROGRAM_BINARIES: ") + cl_error_name(err);
  return "";
}

}  // namespace

ProgramCacheKey opencl_program_key(const OpenclProgramRequest& r) {
  ProgramCacheKey key;
  key.backend = "opencl";
  key.source_fingerprint = source_fingerprint(r.source, r.source_size);
  key.options = r.options;
  key.platform_name = platform_string(r.platform, CL_PLATFORM_NAME);
  key.platform_version = platform_string(r.platform, CL_PLATFORM_VERSION);
  key.device_name = device_string(r.device, CL_DEVICE_NAME);
  key.device_version = device_string(r.device, CL_DEVICE_VERSION);
  key.driver_version = device_string(r.device, CL_DRIVER_VERSION);
  return key;
}

cl_program build_opencl_program(const OpenclProgramRequest& request, const ProgramCache& cache, DeviceStartup& startup) {
  StepClock clock;
  startup.program_cache = ProgramCacheUse::off;
  ProgramCacheKey key;
  if (cache.enabled()) {
    key = opencl_program_key(request);
    startup.cache_path = cache.path_of(key);
    CacheLoad load = cache.load(key);
    if (load.lookup == CacheLookup::hit) {
      if (cl_program program = program_from_binary(request, load.bytes, &load.why)) {
        startup.program_cache = ProgramCacheUse::loaded;
        startup.steps.push_back({"program", clock.lap_ms(), "loaded from the program cache"});
        return program;
      }
      load.lookup = CacheLookup::rejected;
    }
    if (load.lookup == CacheLookup::rejected) {
      startup.cache_entry_rejected = true;
      startup.notes.push_back("program cache: " + load.path + ": " + load.why + "; compiled from source instead");
    }
  }

  cl_program program = program_from_source(request);
  std::string detail = "compiled from source";
  if (cache.enabled()) {
    std::vector<unsigned char> binary;
    CacheStore stored;
    stored.why = program_binary(program, &binary);
    if (stored.why.empty()) stored = cache.store(key, binary);
    if (stored.stored) {
      startup.program_cache = ProgramCacheUse::stored;
      detail += ", stored in the program cache";
    } else {
      startup.program_cache = ProgramCacheUse::not_stored;
      // The first such failure of the process is a warning; later ones (other devices) only notes.
      if (!stored.why.empty() && first_cache_warning_of_process())
        startup.warning = stored.why +
                          "; the kernels will be compiled again in every run (PMRENDER_CACHE_DIR names another "
                          "folder, PMRENDER_PROGRAM_CACHE=off stops trying)";
      else if (!stored.why.empty())
        startup.notes.push_back("program cache: " + stored.why);
    }
  }
  startup.steps.push_back({"program", clock.lap_ms(), detail});
  return program;
}

}  // namespace pm
