// Error handling and info queries shared by the OpenCL backend's files: every failing call
// becomes a DeviceError naming the call, its error code and where it was made.
#pragma once

#include <CL/cl.h>

#include <string>

namespace pm {

// The CL_* name of an OpenCL error code ("unknown OpenCL error" for codes not listed).
const char* cl_error_name(cl_int code);
// Throws DeviceError unless code is CL_SUCCESS.
void cl_check(cl_int code, const char* call, const char* file, int line);
#define PM_CL_CHECK(call) ::pm::cl_check((call), #call, __FILE__, __LINE__)

// A string-valued device or platform property, without its terminating NULs.
std::string device_string(cl_device_id device, cl_device_info what);
std::string platform_string(cl_platform_id platform, cl_platform_info what);

}  // namespace pm
