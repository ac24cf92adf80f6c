// The program cache on its own (render/program_cache.h): where the environment puts it, that an
// entry comes back only for its exact key and only when whole, that an unwritable folder is
// reported instead of thrown, and that processes racing to write one entry leave a whole file.
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/errors.h"
#include "render/program_cache.h"
#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

ProgramCacheKey example_key() {
  ProgramCacheKey key;
  key.backend = "opencl";
  const std::string source = "kernel void k(global int* a) { a[0] = X; }";
  key.source_fingerprint = source_fingerprint(source.data(), source.size());
  key.options = "-cl-std=CL1.2 -D X=1";
  key.platform_name = "Example Platform";
  key.platform_version = "OpenCL 3.0 example";
  key.device_name = "example device";
  key.device_version = "OpenCL 3.0";
  key.driver_version = "1.2.3";
  return key;
}

std::vector<unsigned char> example_program(size_t size, unsigned char seed) {
  std::vector<unsigned char> bytes(size);
  for (size_t i = 0; i < size; ++i) bytes[i] = static_cast<unsigned char>(seed + 31 * i + (i >> 7));
  return bytes;
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

class ProgramCacheFiles : public test::FolderTest {
 protected:
  ProgramCacheFiles() : FolderTest("program_cache_") {}
  ProgramCache cache() const { return ProgramCache(program_cache_settings(nullptr, dir_.c_str(), nullptr, nullptr)); }
};

TEST(ProgramCacheSettings, FollowTheEnvironmentsOrderOfFolders) {
  ProgramCacheSettings s = program_cache_settings(nullptr, "/cache/dir", "/xdg", "/home/u");
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.directory, "/cache/dir");
  s = program_cache_settings(nullptr, "", "/xdg", "/home/u");
  EXPECT_EQ(s.directory, "/xdg/pmrender");
  s = program_cache_settings("on", nullptr, nullptr, "/home/u");
  EXPECT_EQ(s.directory, "/home/u/.cache/pmrender");
  EXPECT_TRUE(s.enabled);
  EXPECT_FALSE(program_cache_settings(nullptr, nullptr, nullptr, nullptr).enabled);
}

TEST(ProgramCacheSettings, OffSwitchesItOffAndOtherValuesAreRefused) {
  EXPECT_FALSE(program_cache_settings("off", "/cache/dir", "/xdg", "/home/u").enabled);
  EXPECT_FALSE(program_cache_settings("0", "/cache/dir", "/xdg", "/home/u").enabled);
  EXPECT_TRUE(program_cache_settings("1", "/cache/dir", "/xdg", "/home/u").enabled);
  EXPECT_THROW(program_cache_settings("maybe", "/cache/dir", nullptr, nullptr), InputError);
}

TEST(ProgramCacheKeys, EveryFieldChangesTheFileName) {
  const ProgramCacheKey base = example_key();
  std::vector<ProgramCacheKey> changed(7, base);
  changed[0].source_fingerprint = source_fingerprint("x", 1);
  changed[1].options = "-cl-std=CL1.2 -D X=2";
  changed[2].platform_name = "Other";
  changed[3].platform_version = "OpenCL 3.0 other";
  changed[4].device_name = "other device";
  changed[5].device_version = "OpenCL 1.2";
  changed[6].driver_version = "1.2.4";
  for (const ProgramCacheKey& key : changed) EXPECT_NE(key.file_name(), base.file_name()) << key.text();
  // One changed byte anywhere in the source changes its fingerprint.
  std::string source(5000, 'a');
  const std::string before = source_fingerprint(source.data(), source.size());
  source[2500] = 'b';
  EXPECT_NE(source_fingerprint(source.data(), source.size()), before);
}

TEST_F(ProgramCacheFiles, AnEntryComesBackForItsKey) {
  const ProgramCacheKey key = example_key();
  const std::vector<unsigned char> program = example_program(4096, 7);
  EXPECT_EQ(cache().load(key).lookup, CacheLookup::missing);
  const CacheStore stored = cache().store(key, program);
  ASSERT_TRUE(stored.stored) << stored.why;
  const CacheLoad load = cache().load(key);
  ASSERT_EQ(load.lookup, CacheLookup::hit) << load.why;
  EXPECT_EQ(load.bytes, program);
  EXPECT_TRUE(fs::exists(cache().path_of(key)));
}

TEST_F(ProgramCacheFiles, AnotherKeyDoesNotReuseTheEntry) {
  const ProgramCacheKey key = example_key();
  ASSERT_TRUE(cache().store(key, example_program(1000, 1)).stored);
  ProgramCacheKey other = key;
  other.options = "-cl-std=CL1.2 -D X=2";
  EXPECT_EQ(cache().load(other).lookup, CacheLookup::missing);
  // The entry under the other key's name (a hash collision, or a file copied there) is refused:
  // the key inside the file is compared in full.
  fs::copy_file(cache().path_of(key), cache().path_of(other));
  const CacheLoad load = cache().load(other);
  EXPECT_EQ(load.lookup, CacheLookup::rejected);
  EXPECT_NE(load.why.find("another key"), std::string::npos) << load.why;
}

TEST_F(ProgramCacheFiles, TruncatedEntriesAreRejected) {
  const ProgramCacheKey key = example_key();
  ASSERT_TRUE(cache().store(key, example_program(3000, 3)).stored);
  const std::vector<unsigned char> whole = read_bytes(cache().path_of(key));
  for (size_t size : {size_t(0), size_t(1), size_t(31), size_t(32), size_t(100), whole.size() / 2, whole.size() - 1}) {
    write_bytes(cache().path_of(key), std::vector<unsigned char>(whole.begin(), whole.begin() + std::ptrdiff_t(size)));
    const CacheLoad load = cache().load(key);
    EXPECT_EQ(load.lookup, CacheLookup::rejected) << "truncated to " << size;
    EXPECT_FALSE(load.why.empty());
  }
  std::vector<unsigned char> longer = whole;
  longer.push_back(0);
  write_bytes(cache().path_of(key), longer);
  EXPECT_EQ(cache().load(key).lookup, CacheLookup::rejected);
}

TEST_F(ProgramCacheFiles, AFlippedByteAnywhereIsRejected) {
  const ProgramCacheKey key = example_key();
  const std::vector<unsigned char> program = example_program(700, 5);
  const std::vector<unsigned char> whole = encode_cache_entry(key.text(), program);
  std::vector<unsigned char> payload;
  ASSERT_EQ(decode_cache_entry(whole, key.text(), &payload), "");
  ASSERT_EQ(payload, program);
  for (size_t at = 0; at < whole.size(); ++at)
    for (unsigned char flip : {0x01, 0x80}) {
      std::vector<unsigned char> damaged = whole;
      damaged[at] ^= flip;
      EXPECT_NE(decode_cache_entry(damaged, key.text(), &payload), "") << "byte " << at << " ^ " << int(flip);
    }
  // And through the file: a flipped byte in the middle of the program.
  ASSERT_TRUE(cache().store(key, program).stored);
  std::vector<unsigned char> file = read_bytes(cache().path_of(key));
  file[file.size() - program.size() / 2] ^= 0x10;
  write_bytes(cache().path_of(key), file);
  const CacheLoad load = cache().load(key);
  EXPECT_EQ(load.lookup, CacheLookup::rejected);
  EXPECT_NE(load.why.find("checksum"), std::string::npos) << load.why;
}

TEST_F(ProgramCacheFiles, AnUnwritableFolderIsReportedNotThrown) {
  // A folder below a regular file cannot be created, not even by root.
  const std::string blocker = write("not-a-folder", "x");
  const ProgramCache unwritable(program_cache_settings(nullptr, (blocker + "/cache").c_str(), nullptr, nullptr));
  const ProgramCacheKey key = example_key();
  CacheStore stored;
  EXPECT_NO_THROW(stored = unwritable.store(key, example_program(100, 9)));
  EXPECT_FALSE(stored.stored);
  EXPECT_NE(stored.why.find(blocker), std::string::npos) << stored.why;
  EXPECT_EQ(unwritable.load(key).lookup, CacheLookup::missing);
}

TEST_F(ProgramCacheFiles, ProcessesRacingToWriteOneEntryLeaveAWholeFile) {
  const ProgramCacheKey key = example_key();
  const int writers = 4, rounds = 8;
  std::vector<std::vector<unsigned char>> programs;
  for (int w = 0; w < writers; ++w) programs.push_back(example_program(256 * 1024 + 17 * w, static_cast<unsigned char>(w)));
  std::vector<pid_t> children;
  for (int w = 0; w < writers; ++w) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      bool all = true;
      for (int r = 0; r < rounds; ++r) all &= cache().store(key, programs[size_t(w)]).stored;
      _exit(all ? 0 : 1);
    }
    children.push_back(pid);
  }
  // While they write, every read sees no entry or one writer's whole program.
  std::vector<int> statuses(children.size(), -1);
  for (size_t running = children.size(); running > 0;) {
    const CacheLoad load = cache().load(key);
    EXPECT_NE(load.lookup, CacheLookup::rejected) << load.why;
    if (load.lookup == CacheLookup::hit) {
      EXPECT_NE(std::find(programs.begin(), programs.end(), load.bytes), programs.end());
    }
    running = 0;
    for (size_t c = 0; c < children.size(); ++c) {
      if (statuses[c] != -1) continue;
      int status = 0;
      if (waitpid(children[c], &status, WNOHANG) == children[c]) statuses[c] = status;
      else ++running;
    }
  }
  for (int status : statuses) EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a writer failed";
  const CacheLoad last = cache().load(key);
  ASSERT_EQ(last.lookup, CacheLookup::hit) << last.why;
  EXPECT_NE(std::find(programs.begin(), programs.end(), last.bytes), programs.end());
  // Only the entry is left: no writer's temporary.
  int files = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace pm
