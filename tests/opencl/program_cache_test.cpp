// The OpenCL program cache end to end (kernels/opencl/opencl_program.h) on the machine's first
// OpenCL device (PoCL in CI): a second opening loads the program from the cache, a damaged entry
// is detected, compiled again and renders the same image, other build options or another source
// never reuse an entry, and an unwritable cache folder still renders. Every test points the cache
// at a folder of its own. Observed through DeviceStartup::program_cache, not through timing.
#include <gtest/gtest.h>

#include <CL/cl.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "kernels/opencl/opencl_program.h"
#include "render/program_cache.h"
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/render_settings.h"
#include "support/same_image.h"
#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

// An environment variable set for one test and put back afterwards.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A tiny Cornell box frame with photons: every stage's kernels run.
FrameImage tiny_frame(Device& device) {
  PhotonSettings photons;
  photons.photons = 2000;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = 12;
  settings.height = 12;
  const Scene scene = builtin_cornell_box();
  Renderer renderer(device, scene, settings);
  return renderer.render_frame(0);
}

std::vector<fs::path> entries(const fs::path& folder) {
  std::vector<fs::path> found;
  std::error_code ignored;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ignored)) found.push_back(e.path());
  return found;
}

class OpenclProgramCache : public test::FolderTest {
 protected:
  OpenclProgramCache() : FolderTest("opencl_program_cache_") {}
  void SetUp() override {
    FolderTest::SetUp();
    cache_dir_.emplace("PMRENDER_CACHE_DIR", dir_.string());
  }
  void TearDown() override {
    cache_dir_.reset();
    FolderTest::TearDown();
  }
  std::unique_ptr<Device> open() {
    std::unique_ptr<Device> device = test::open_first_device("opencl");
    if (!device) ADD_FAILURE() << "no OpenCL device: install pocl-opencl-icd";
    return device;
  }
  std::optional<ScopedEnvironment> cache_dir_;
};

TEST_F(OpenclProgramCache, TheSecondOpeningLoadsTheProgramAndRendersTheSameImage) {
  std::unique_ptr<Device> first = open();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->startup().program_cache, ProgramCacheUse::stored);
  ASSERT_EQ(entries(dir_).size(), 1u);
  EXPECT_EQ(entries(dir_)[0].string(), first->startup().cache_path);
  const FrameImage compiled = tiny_frame(*first);
  first.reset();

  std::unique_ptr<Device> second = open();
  EXPECT_EQ(second->startup().program_cache, ProgramCacheUse::loaded);
  EXPECT_FALSE(second->startup().cache_entry_rejected);
  EXPECT_TRUE(second->startup().notes.empty());
  test::expect_same_image(compiled, tiny_frame(*second), "program from the cache");
}

TEST_F(OpenclProgramCache, DamagedEntriesAreCompiledAgainAndRenderTheSameImage) {
  std::unique_ptr<Device> device = open();
  ASSERT_TRUE(device);
  const FrameImage compiled = tiny_frame(*device);
  const fs::path entry = device->startup().cache_path;
  device.reset();
  std::vector<unsigned char> whole;
  {
    std::ifstream in(entry, std::ios::binary);
    whole.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(whole.size(), 64u);

  auto expect_rebuilt = [&](const std::vector<unsigned char>& damaged, const std::string& what) {
    std::ofstream(entry, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(damaged.data()), damaged.size());
    std::unique_ptr<Device> d = open();
    EXPECT_EQ(d->startup().program_cache, ProgramCacheUse::stored) << what;
    EXPECT_TRUE(d->startup().cache_entry_rejected) << what;
    ASSERT_EQ(d->startup().notes.size(), 1u) << what;
    EXPECT_EQ(d->startup().notes[0].find('\n'), std::string::npos) << "a note is one line: " << d->startup().notes[0];
    test::expect_same_image(compiled, tiny_frame(*d), what);
    d.reset();
    EXPECT_EQ(open()->startup().program_cache, ProgramCacheUse::loaded) << what << ": the entry was written again";
  };
  expect_rebuilt(std::vector<unsigned char>(whole.begin(), whole.begin() + std::ptrdiff_t(whole.size() / 2)), "truncated");
  std::vector<unsigned char> flipped = whole;
  for (size_t at = whole.size() / 3; at < whole.size() / 3 + 8; ++at) flipped[at] ^= 0x5a;
  expect_rebuilt(flipped, "flipped bytes");
  // A whole file for the right key whose program is not one: the driver refuses it.
  const std::string key_text(whole.begin() + 32, whole.begin() + 32 + std::ptrdiff_t(whole[12] | whole[13] << 8));
  expect_rebuilt(encode_cache_entry(key_text, std::vector<unsigned char>(4096, 0x42)), "a program the driver refuses");
}

TEST_F(OpenclProgramCache, AnUnwritableFolderStillRenders) {
  const std::string blocker = write("not-a-folder", "x");
  ScopedEnvironment unwritable("PMRENDER_CACHE_DIR", blocker + "/cache");
  std::unique_ptr<Device> device = open();
  ASSERT_TRUE(device);
  EXPECT_EQ(device->startup().program_cache, ProgramCacheUse::not_stored);
  const FrameImage image = tiny_frame(*device);
  EXPECT_EQ(image.width, 12);
}

TEST_F(OpenclProgramCache, SwitchedOffItWritesNothing) {
  ScopedEnvironment off("PMRENDER_PROGRAM_CACHE", "off");
  std::unique_ptr<Device> device = open();
  ASSERT_TRUE(device);
  EXPECT_EQ(device->startup().program_cache, ProgramCacheUse::off);
  EXPECT_TRUE(entries(dir_).empty());
}

// A small program straight through build_opencl_program, on the first OpenCL device.
class OpenclProgramKeys : public test::FolderTest {
 protected:
  OpenclProgramKeys() : FolderTest("opencl_program_keys_") {}
  void SetUp() override {
    FolderTest::SetUp();
    cl_uint platforms = 0;
    ASSERT_EQ(clGetPlatformIDs(1, &platform_, &platforms), CL_SUCCESS);
    ASSERT_EQ(clGetDeviceIDs(platform_, CL_DEVICE_TYPE_ALL, 1, &device_, nullptr), CL_SUCCESS);
    cl_int err = CL_SUCCESS;
    context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &err);
    ASSERT_EQ(err, CL_SUCCESS);
  }
  void TearDown() override {
    if (context_) clReleaseContext(context_);
    FolderTest::TearDown();
  }

  // Builds source with options through the cache and runs its kernel: what it wrote, and how the
  // program was obtained.
  std::pair<int, ProgramCacheUse> build_and_run(const std::string& source, const std::string& options) {
    OpenclProgramRequest request;
    request.context = context_;
    request.device = device_;
    request.platform = platform_;
    request.source = source.c_str();
    request.source_size = source.size();
    request.options = options;
    DeviceStartup startup;
    const ProgramCache cache(program_cache_settings(nullptr, dir_.c_str(), nullptr, nullptr));
    cl_program program = build_opencl_program(request, cache, startup);
    cl_int err = CL_SUCCESS;
    cl_kernel kernel = clCreateKernel(program, "answer", &err);
    EXPECT_EQ(err, CL_SUCCESS);
    cl_mem out = clCreateBuffer(context_, CL_MEM_WRITE_ONLY, sizeof(cl_int), nullptr, &err);
    cl_command_queue queue = clCreateCommandQueue(context_, device_, 0, &err);
    clSetKernelArg(kernel, 0, sizeof(out), &out);
    const size_t one = 1;
    EXPECT_EQ(clEnqueueNDRangeKernel(queue, kernel, 1, nullptr, &one, &one, 0, nullptr, nullptr), CL_SUCCESS);
    cl_int value = -1;
    clEnqueueReadBuffer(queue, out, CL_TRUE, 0, sizeof(value), &value, 0, nullptr, nullptr);
    clReleaseCommandQueue(queue);
    clReleaseMemObject(out);
    clReleaseKernel(kernel);
    clReleaseProgram(program);
    return {value, startup.program_cache};
  }

  cl_platform_id platform_ = nullptr;
  cl_device_id device_ = nullptr;
  cl_context context_ = nullptr;
};

TEST_F(OpenclProgramKeys, OtherOptionsOrAnotherSourceNeverReuseAnEntry) {
  const std::string source = "kernel void answer(global int* out) { out[0] = VALUE; }\n";
  EXPECT_EQ(build_and_run(source, "-D VALUE=1"), std::make_pair(1, ProgramCacheUse::stored));
  EXPECT_EQ(build_and_run(source, "-D VALUE=1"), std::make_pair(1, ProgramCacheUse::loaded));
  // The same source with other options: compiled, and its own value, not the cached program's.
  EXPECT_EQ(build_and_run(source, "-D VALUE=2"), std::make_pair(2, ProgramCacheUse::stored));
  EXPECT_EQ(build_and_run(source, "-D VALUE=2"), std::make_pair(2, ProgramCacheUse::loaded));
  // Another source with the first options.
  const std::string other = "kernel void answer(global int* out) { out[0] = VALUE + 40; }\n";
  EXPECT_EQ(build_and_run(other, "-D VALUE=1"), std::make_pair(41, ProgramCacheUse::stored));
  EXPECT_EQ(entries(dir_).size(), 3u);
}

}  // namespace
}  // namespace pm
