// A 1000-frame sequence holds flat host and device memory: what pmrender render -v reports after
// the first frame and at the end differs by no more than allocator noise on the host and not at
// all on the device. The numbers are printed for the record.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <string>

#include "support/pmrender_process.h"

namespace pm {
namespace {

class SequenceMemory : public test::PmrenderProcessTest {};

// "310.2 MiB" or "12 KiB" in MiB.
double mib(const std::string& value, const std::string& unit) {
  const double v = std::stod(value);
  return unit == "GiB" ? v * 1024 : unit == "MiB" ? v : v / 1024;
}

TEST_F(SequenceMemory, AThousandFramesHoldFlatHostAndDeviceMemory) {
  // The error estimate's control runs every frame, with a few paths: its buffers are what
  // counts here, and its default 1024 paths a control pixel would take most of the time.
  const test::ProcessResult r =
      pmrender("render --backend opencl --resolution 16x16 --photons 500 --no-photon-reuse --frames 0-999 -v "
               "--control-paths 16 -o " + (dir_ / "f_####.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rendered 1000 of 1000 frames"), std::string::npos) << r.out;
  const std::regex line("memory: host ([0-9.]+) (KiB|MiB|GiB) after the first frame, ([0-9.]+) (KiB|MiB|GiB) at the end "
                        "\\(peak ([0-9.]+) (KiB|MiB|GiB)\\); device ([0-9.]+) (KiB|MiB|GiB) after the first frame, "
                        "([0-9.]+) (KiB|MiB|GiB) at the end \\(peak ([0-9.]+) (KiB|MiB|GiB)\\)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out.substr(r.out.size() > 600 ? r.out.size() - 600 : 0);
  std::printf("%s\n", m[0].str().c_str());
  const double host_first = mib(m[1], m[2]), host_end = mib(m[3], m[4]);
  const double device_first = mib(m[7], m[8]), device_end = mib(m[9], m[10]), device_peak = mib(m[11], m[12]);
  EXPECT_LT(host_end - host_first, 4.0) << "host memory grew over 999 frames";
  EXPECT_EQ(device_end, device_first);
  EXPECT_EQ(device_peak, device_first);
}

}  // namespace
}  // namespace pm
