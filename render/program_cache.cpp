// The program cache's location rules, key text and entry files (program_cache.h).
//
// An entry file is a 32-byte header, the key text and the program's bytes:
//   0  "PMPROGC\n"            magic
//   8  u32 format version     kFormatVersion
//   12 u32 key text bytes
//   16 u64 program bytes
//   24 u32 CRC-32 of key text and program bytes
//   28 u32 CRC-32 of bytes 0-27
// all little-endian. The key text inside is compared with the expected one byte for byte, so a
// file name that two keys share (a hash collision) or an entry copied from elsewhere is refused.
#include "render/program_cache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "render/atomic_file.h"
#include "render/errors.h"
#include "render/interruption.h"

namespace pm {

namespace {

const char kMagic[8] = {'P', 'M', 'P', 'R', 'O', 'G', 'C', '\n'};
const uint32_t kFormatVersion = 1;
const size_t kHeaderBytes = 32;
// Larger is not a program any driver here writes; refusing it keeps a damaged length field from
// asking for gigabytes.
const uint64_t kMaxProgramBytes = uint64_t(1) << 30;

void put_u32(std::vector<unsigned char>& out, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_u64(std::vector<unsigned char>& out, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) out[at + i] = static_cast<unsigned char>(v >> (8 * i));
}
uint32_t get_u32(const std::vector<unsigned char>& in, size_t at) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t(in[at + i]) << (8 * i);
  return v;
}
uint64_t get_u64(const std::vector<unsigned char>& in, size_t at) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(in[at + i]) << (8 * i);
  return v;
}

uint32_t crc32_of(const unsigned char* data, size_t size, uint32_t crc = 0) {
  // zlib takes at most a uInt per call.
  uLong value = crc == 0 ? crc32(0L, Z_NULL, 0) : crc;
  while (size > 0) {
    const uInt chunk = size > (1u << 30) ? (1u << 30) : uInt(size);
    value = crc32(value, data, chunk);
    data += chunk;
    size -= chunk;
  }
  return uint32_t(value);
}

std::string hex(uint64_t value, int digits) {
  char text[17];
  std::snprintf(text, sizeof(text), "%0*llx", digits, static_cast<unsigned long long>(value));
  return text;
}

bool is_set(const char* value) { return value && *value; }

// The file's bytes; "" when read, "missing" when there is none, else why it could not be read.
std::string read_whole_file(const std::string& path, std::vector<unsigned char>* bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  // ENOTDIR: a path component is a file, so no entry can be there either.
  if (fd < 0) return errno == ENOENT || errno == ENOTDIR ? "missing" : errno_text("cannot open");
  std::string problem;
  struct stat info {};
  if (::fstat(fd, &info) != 0) problem = errno_text("cannot stat");
  else if (uint64_t(info.st_size) > kHeaderBytes + (uint64_t(1) << 20) + kMaxProgramBytes) problem = "too large";
  bytes->resize(problem.empty() ? size_t(info.st_size) : 0);
  size_t done = 0;
  while (problem.empty() && done < bytes->size()) {
    const ssize_t n = ::read(fd, bytes->data() + done, bytes->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) problem = errno_text("read error");
    if (n <= 0) break;  // shorter than fstat said: a writer of a non-atomic copy; the size checks tell
    done += size_t(n);
  }
  bytes->resize(done);
  ::close(fd);
  return problem;
}

}  // namespace

ProgramCacheSettings program_cache_settings(const char* switch_value, const char* cache_dir, const char* xdg_cache_home,
                                            const char* home) {
  ProgramCacheSettings s;
  const std::string on = switch_value ? switch_value : "";
  if (on == "off" || on == "0") return s;
  if (!on.empty() && on != "on" && on != "1")
    throw InputError("PMRENDER_PROGRAM_CACHE: expected on or off, got '" + on + "'");
  if (is_set(cache_dir)) {
    s.directory = cache_dir;
    s.source = "PMRENDER_CACHE_DIR";
  } else if (is_set(xdg_cache_home)) {
    s.directory = std::string(xdg_cache_home) + "/pmrender";
    s.source = "XDG_CACHE_HOME";
  } else if (is_set(home)) {
    s.directory = std::string(home) + "/.cache/pmrender";
    s.source = "HOME";
  } else {
    return s;  // nowhere to keep it: off, as if asked
  }
  s.enabled = true;
  return s;
}

ProgramCacheSettings program_cache_settings_from_environment() {
  return program_cache_settings(std::getenv("PMRENDER_PROGRAM_CACHE"), std::getenv("PMRENDER_CACHE_DIR"),
                                std::getenv("XDG_CACHE_HOME"), std::getenv("HOME"));
}

std::string fnv1a64_hex(const void* data, size_t size) {
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  uint64_t hash = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ull;
  }
  return hex(hash, 16);
}

std::string crc32_hex(const void* data, size_t size) {
  return hex(crc32_of(static_cast<const unsigned char*>(data), size), 8);
}

std::string source_fingerprint(const char* source, size_t size) {
  // Two unrelated 64- and 32-bit hashes and the length: a changed source that keeps all three is
  // not a practical worry for a cache (nothing here defends against crafted collisions).
  return "fnv1a64=" + fnv1a64_hex(source, size) + " crc32=" + crc32_hex(source, size) + " bytes=" + std::to_string(size);
}

std::string ProgramCacheKey::text() const {
  return "backend: " + backend + "\nsource: " + source_fingerprint + "\noptions: " + options + "\nplatform: " +
         platform_name + "\nplatform version: " + platform_version + "\ndevice: " + device_name +
         "\ndevice version: " + device_version + "\ndriver: " + driver_version + "\n";
}

std::string ProgramCacheKey::file_name() const {
  const std::string t = text();
  return backend + "-" + fnv1a64_hex(t.data(), t.size()) + ".bin";
}

std::vector<unsigned char> encode_cache_entry(const std::string& key_text, const std::vector<unsigned char>& payload) {
  std::vector<unsigned char> out(kHeaderBytes + key_text.size() + payload.size());
  std::memcpy(out.data(), kMagic, sizeof(kMagic));
  put_u32(out, 8, kFormatVersion);
  put_u32(out, 12, uint32_t(key_text.size()));
  put_u64(out, 16, payload.size());
  std::copy(key_text.begin(), key_text.end(), out.begin() + kHeaderBytes);
  std::copy(payload.begin(), payload.end(), out.begin() + std::ptrdiff_t(kHeaderBytes + key_text.size()));
  put_u32(out, 24, crc32_of(out.data() + kHeaderBytes, out.size() - kHeaderBytes));
  put_u32(out, 28, crc32_of(out.data(), 28));
  return out;
}

std::string decode_cache_entry(const std::vector<unsigned char>& file, const std::string& key_text,
                               std::vector<unsigned char>* payload) {
  if (file.size() < kHeaderBytes)
    return "truncated (" + std::to_string(file.size()) + " bytes, shorter than its header)";
  if (std::memcmp(file.data(), kMagic, sizeof(kMagic)) != 0) return "not a pmrender program cache file";
  if (crc32_of(file.data(), 28) != get_u32(file, 28)) return "header checksum mismatch";
  if (get_u32(file, 8) != kFormatVersion) return "cache format version " + std::to_string(get_u32(file, 8));
  const uint64_t key_bytes = get_u32(file, 12), program_bytes = get_u64(file, 16);
  if (program_bytes == 0 || program_bytes > kMaxProgramBytes)
    return "program size " + std::to_string(program_bytes) + " out of range";
  const uint64_t expected = kHeaderBytes + key_bytes + program_bytes;
  if (file.size() != expected)
    return (file.size() < expected ? "truncated (" : "too long (") + std::to_string(file.size()) + " bytes, header says " +
           std::to_string(expected) + ")";
  if (crc32_of(file.data() + kHeaderBytes, file.size() - kHeaderBytes) != get_u32(file, 24)) return "checksum mismatch";
  if (key_bytes != key_text.size() || std::memcmp(file.data() + kHeaderBytes, key_text.data(), key_text.size()) != 0)
    return "written for another key (another source, options or driver)";
  payload->assign(file.begin() + std::ptrdiff_t(kHeaderBytes + key_bytes), file.end());
  return "";
}

std::string ProgramCache::path_of(const ProgramCacheKey& key) const { return settings_.directory + "/" + key.file_name(); }

CacheLoad ProgramCache::load(const ProgramCacheKey& key) const {
  CacheLoad result;
  if (!enabled()) return result;
  result.path = path_of(key);
  std::vector<unsigned char> file;
  const std::string problem = read_whole_file(result.path, &file);
  if (problem == "missing") return result;
  result.why = problem.empty() ? decode_cache_entry(file, key.text(), &result.bytes) : problem;
  result.lookup = result.why.empty() ? CacheLookup::hit : CacheLookup::rejected;
  return result;
}

CacheStore ProgramCache::store(const ProgramCacheKey& key, const std::vector<unsigned char>& bytes) const {
  CacheStore result;
  if (!enabled()) return result;
  const std::vector<unsigned char> file = encode_cache_entry(key.text(), bytes);
  try {
    AtomicFile out(path_of(key));  // creates the folder; a temporary of its own per writer
    out.write(file.data(), file.size());
    out.commit();
    result.stored = true;
  } catch (const Interrupted&) {
    // Stopping is not the folder's fault: no warning; the temporary is gone with `out`.
  } catch (const std::exception& e) {
    result.why = "cannot write the program cache in '" + settings_.directory + "' (from " + settings_.source +
                 "): " + e.what();
  }
  return result;
}

bool first_cache_warning_of_process() {
  static std::atomic<bool> warned{false};
  return !warned.exchange(true);
}

}  // namespace pm
