// OpenCL error names and info queries (opencl_check.h).
#include "kernels/opencl/opencl_check.h"

#include <CL/cl_ext.h>

#include "render/errors.h"

namespace pm {

const char* cl_error_name(cl_int code) {
  switch (code) {
#define PM_CL_ERROR(name) case name: return #name;
    PM_CL_ERROR(CL_DEVICE_NOT_FOUND) PM_CL_ERROR(CL_DEVICE_NOT_AVAILABLE) PM_CL_ERROR(CL_COMPILER_NOT_AVAILABLE)
    PM_CL_ERROR(CL_MEM_OBJECT_ALLOCATION_FAILURE) PM_CL_ERROR(CL_OUT_OF_RESOURCES) PM_CL_ERROR(CL_OUT_OF_HOST_MEMORY)
    PM_CL_ERROR(CL_BUILD_PROGRAM_FAILURE) PM_CL_ERROR(CL_INVALID_VALUE) PM_CL_ERROR(CL_INVALID_PLATFORM)
    PM_CL_ERROR(CL_INVALID_DEVICE) PM_CL_ERROR(CL_INVALID_CONTEXT) PM_CL_ERROR(CL_INVALID_COMMAND_QUEUE)
    PM_CL_ERROR(CL_INVALID_MEM_OBJECT) PM_CL_ERROR(CL_INVALID_PROGRAM) PM_CL_ERROR(CL_INVALID_KERNEL_NAME)
    PM_CL_ERROR(CL_INVALID_KERNEL) PM_CL_ERROR(CL_INVALID_ARG_INDEX) PM_CL_ERROR(CL_INVALID_ARG_VALUE)
    PM_CL_ERROR(CL_INVALID_ARG_SIZE) PM_CL_ERROR(CL_INVALID_KERNEL_ARGS) PM_CL_ERROR(CL_INVALID_WORK_GROUP_SIZE)
    PM_CL_ERROR(CL_INVALID_BUFFER_SIZE) PM_CL_ERROR(CL_INVALID_GLOBAL_WORK_SIZE) PM_CL_ERROR(CL_INVALID_EVENT)
    PM_CL_ERROR(CL_INVALID_OPERATION) PM_CL_ERROR(CL_PLATFORM_NOT_FOUND_KHR)
#undef PM_CL_ERROR
    default: return "unknown OpenCL error";
  }
}

void cl_check(cl_int code, const char* call, const char* file, int line) {
  if (code == CL_SUCCESS) return;
  throw DeviceError(std::string("OpenCL: ") + call + " failed with " + cl_error_name(code) + " (" +
                    std::to_string(code) + ") at " + file + ":" + std::to_string(line));
}

std::string device_string(cl_device_id device, cl_device_info what) {
  size_t size = 0;
  PM_CL_CHECK(clGetDeviceInfo(device, what, 0, nullptr, &size));
  std::string value(size, '\0');
  PM_CL_CHECK(clGetDeviceInfo(device, what, size, value.data(), nullptr));
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
  size_t size = 0;
  PM_CL_CHECK(clGetPlatformInfo(platform, what, 0, nullptr, &size));
  std::string value(size, '\0');
  PM_CL_CHECK(clGetPlatformInfo(platform, what, size, value.data(), nullptr));
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

}  // namespace pm
