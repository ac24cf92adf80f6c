// Output targets are checked before anything is rendered: a path that cannot or must not be
// written is a one-line input error (exit code 2), the device is never opened, and whatever the
// path named (a pipe, a link to a device, an input image) is left as it was.
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/exr_io.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

class OutputChecks : public test::PmrenderProcessTest {
 protected:
  // --device 99 does not exist: an output error reported instead of that one proves the output
  // was checked before the device was opened.
  void expect_refused(const std::string& args, const std::string& expect) {
    SCOPED_TRACE(args);
    const ProcessResult r = pmrender("render --backend opencl --device 99 --resolution 8x8 --photons 0 " + args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  std::string at(const std::string& name) { return (dir_ / name).string(); }
};

TEST_F(OutputChecks, AFifoIsRefusedAndStaysAFifo) {
  ASSERT_EQ(::mkfifo(at("pipe.exr").c_str(), 0644), 0);
  expect_refused("-o " + at("pipe.exr"), "is a FIFO, not a regular file");
  EXPECT_TRUE(fs::is_fifo(at("pipe.exr")));
}

TEST_F(OutputChecks, ALinkToADeviceIsRefusedAndStaysALink) {
  fs::create_symlink("/dev/null", at("null.exr"));
  expect_refused("-o " + at("null.exr"), "is a character device, not a regular file");
  EXPECT_TRUE(fs::is_symlink(at("null.exr")));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST_F(OutputChecks, FoldersAreRefused) {
  fs::create_directories(dir_ / "somedir.exr");
  expect_refused("-o " + at("somedir.exr"), "is a folder");
  expect_refused("-o " + at("somedir/"), "is a folder name");
}

TEST_F(OutputChecks, AParentThatIsAFileIsRefused) {
  std::ofstream(dir_ / "plain.txt") << "x";
  expect_refused("-o " + at("plain.txt/sub/f_####.exr"), "'" + at("plain.txt") + "' is a file, not a folder");
}

TEST_F(OutputChecks, AFolderWhereNoFileCanBeCreatedIsRefused) {
  // sysfs refuses new files even to root (access() would say it is writable).
  ASSERT_TRUE(fs::is_directory("/sys"));
  expect_refused("-o /sys/f.exr", "no file can be created in '/sys'");
  expect_refused("-o /sys/new_folder/f.exr", "no file can be created in '/sys'");
}

TEST_F(OutputChecks, ANameTooLongForTheTemporaryIsRefused) {
  expect_refused("-o " + at(std::string(240, 'a') + ".exr"), "has a file name of 244 bytes");
}

TEST_F(OutputChecks, NonExrNamesAreRefused) {
  expect_refused("-o " + at("a.png"), "must end in .exr: pmrender writes OpenEXR (for a PNG, add --preview NAME.png)");
  expect_refused("-o " + at("frames_####"), "must end in .exr");
  expect_refused("-o " + at("a.exr") + " --preview " + at("a.jpg"), "--preview: '" + at("a.jpg") + "' must end in .png");
  EXPECT_FALSE(fs::exists(at("a.png")));
}

TEST_F(OutputChecks, EveryFrameOfASequenceIsChecked) {
  // Frame 3's name is a FIFO: the sequence is refused before frame 1 is rendered.
  ASSERT_EQ(::mkfifo(at("f_3.exr").c_str(), 0644), 0);
  const ProcessResult r = pmrender("render --backend opencl --resolution 8x8 --photons 0 --frames 1-4 -o " + at("f_#.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("f_3.exr' is a FIFO"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(at("f_1.exr")));
}

TEST_F(OutputChecks, AWritableTargetStillRenders) {
  const ProcessResult r = pmrender("render --backend opencl --resolution 8x8 --photons 0 -o " + at("new/sub/F.EXR"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(at("new/sub/F.EXR")));
  for (const auto& entry : fs::recursive_directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".pmrender-probe"), std::string::npos) << entry.path();
}

TEST_F(OutputChecks, APreviewIsWrittenBesideTheExr) {
  const ProcessResult r = pmrender("render --backend opencl --resolution 8x6 --photons 0 --frames 0-1 -o " +
                                   at("f_#.exr") + " --preview " + at("p_#.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"p_0.png", "p_1.png"}) {
    const std::string png = test::read_text(dir_ / name);
    ASSERT_GT(png.size(), 8u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
  }
}

// compare --diff naming one of its inputs would overwrite it.
class CompareDiff : public test::PmrenderProcessTest {};

TEST_F(CompareDiff, ADiffNamingAnInputIsRefusedAndTheInputKept) {
  FrameImage image;
  image.width = 4;
  image.height = 2;
  image.layers.push_back({"", std::vector<float>(24, 0.5f)});
  const std::string a = (dir_ / "a.exr").string(), b = (dir_ / "b.exr").string();
  write_exr(a, image, true);
  write_exr(b, image, true);
  const auto size_before = fs::file_size(a);
  const auto time_before = fs::last_write_time(a);
  for (const std::string& diff : {a, (dir_ / "." / "a.exr").string(), b}) {
    SCOPED_TRACE(diff);
    const ProcessResult r = pmrender("compare " + a + " " + b + " --diff " + diff);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--diff: '" + diff + "' is the "), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(fs::file_size(a), size_before);
  EXPECT_EQ(fs::last_write_time(a), time_before);
  EXPECT_EQ(pmrender("compare " + a + " " + b + " --diff " + (dir_ / "d.exr").string()).exit_code, 0);
}

}  // namespace
}  // namespace pm
