// Requests that cannot fit in memory are refused with the numbers (exit code 2) before the first
// frame, instead of std::bad_alloc or PoCL's assertion (exit code 134) when a buffer is first
// touched. The limit is the process's address space (ulimit -v), as a user or a batch system
// would set it; under it the driver does not start before the checks. (Not for AddressSanitizer
// builds: their shadow memory does not fit such limits.)
#include <sys/wait.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

#include "support/pmrender_process.h"

namespace pm {
namespace {

class MemoryLimits : public test::PmrenderProcessTest {
 protected:
  test::ProcessResult render_under_limit(const std::string& limit_kb, const std::string& args) {
    const std::string out = (dir_ / "stdout.txt").string(), err = (dir_ / "stderr.txt").string();
    const std::string cmd = "ulimit -v " + limit_kb + "; exec " + test::pmrender_binary() + " render " + args + " -o " +
                            (dir_ / "f.exr").string() + " </dev/null >" + out + " 2>" + err;
    const int status = std::system(cmd.c_str());
    test::ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = test::read_text(out);
    r.err = test::read_text(err);
    return r;
  }
  // The OpenCL index of a CPU device (PoCL, buffers in host memory) as `pmrender devices` numbers
  // it under the limit (a GPU driver may not start under it, which renumbers the rest); -1: none.
  int cpu_opencl_device_under_limit(const std::string& limit_kb) {
    const std::string out = (dir_ / "devices.txt").string();
    const std::string cmd = "ulimit -v " + limit_kb + "; exec " + test::pmrender_binary() + " devices >" + out + " 2>&1";
    if (std::system(cmd.c_str()) != 0) return -1;
    std::istringstream lines(test::read_text(out));
    std::string line;
    int index = -1;
    while (std::getline(lines, line))
      if (line.rfind("opencl  --device ", 0) == 0 && line.find("(host memory)") != std::string::npos)
        index = std::atoi(line.c_str() + std::strlen("opencl  --device "));
    return index;
  }
  void expect_refused(const test::ProcessResult& r, const std::string& expect) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("GiB are available (RLIMIT_AS (ulimit -v))"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "f.exr"));
  }
};

TEST_F(MemoryLimits, AFrameTooLargeForTheHostIsRefusedBeforeTheDeviceOpens) {
  // 8192x8192 at 128 bytes a pixel: 8 GiB, under a 2 GB address space. --device 99 does not exist:
  // the memory refusal comes first.
  expect_refused(render_under_limit("2000000", "--backend opencl --device 99 --resolution 8192x8192 --photons 1000"),
                 "--resolution 8192x8192: a frame needs about 8.0 GiB of host memory, but ");
}

TEST_F(MemoryLimits, DeviceBuffersThatDoNotFitTheHostAreRefusedBeforeTheFirstFrame) {
  // The frame's 8 GiB fit under 9 GB, but not beside a CPU device's buffers (2.8 GiB, host memory:
  // 44 bytes a pixel in a box without mirrors: the film's two float4 and a float, and one shading
  // point's float2).
  // PoCL 3 creates the buffers lazily, and the total is refused; PoCL 5 derives its one-buffer
  // limit from the address space, and the first buffer over it is refused. Either way: exit 2,
  // one line with the numbers, before the first frame.
  const int cpu = cpu_opencl_device_under_limit("9000000");
  ASSERT_GE(cpu, 0) << "this test needs an OpenCL CPU device (PoCL)";
  const test::ProcessResult r = render_under_limit(
      "9000000", "--backend opencl --device " + std::to_string(cpu) + " --resolution 8192x8192 --photons 1000");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("; lower --resolution or --photons"), std::string::npos) << r.err;
  const bool total = r.err.find("the render needs 2.8 GiB of device memory and 8.0 GiB for the frame on the host; "
                                "the buffers of ") != std::string::npos &&
                     r.err.find("GiB are available (RLIMIT_AS (ulimit -v))") != std::string::npos;
  const bool one_buffer = r.err.find(" in one buffer, but ") != std::string::npos &&
                          r.err.find("(CL_DEVICE_MAX_MEM_ALLOC_SIZE)") != std::string::npos;
  EXPECT_TRUE(total || one_buffer) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "f.exr"));
}

TEST_F(MemoryLimits, AFittingRequestRendersUnderTheSameKindOfLimit) {
  const test::ProcessResult r = render_under_limit("4000000", "--backend opencl --resolution 64x64 --photons 1000 -v");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "f.exr"));
  // The driver did not start beside the scene load, ahead of the memory checks
  // (cli/scene_beside_driver.h): its mappings would count against the limit.
  EXPECT_NE(r.out.find("the driver starts with the device: the address space is limited"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace pm
