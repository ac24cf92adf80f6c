// The on-disk cache of compiled device programs (OpenCL program binaries): where it lives, what
// keys an entry, and the entry file's format. Backend-neutral: it stores bytes under a key text
// and hands them back only when the file is whole and was written for exactly that key.
//
// Location: $PMRENDER_CACHE_DIR, else $XDG_CACHE_HOME/pmrender, else $HOME/.cache/pmrender;
// PMRENDER_PROGRAM_CACHE=off (or 0) switches it off. Entries are written through a temporary
// file and a rename (render/atomic_file.h), so processes racing to write one entry each leave a
// whole file and a reader never sees half of one. A file that is short, fails its checksum or
// was written for another key is reported as such and never used.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pm {

// Where the cache is and whether it is on, as the environment says.
struct ProgramCacheSettings {
  bool enabled = false;
  std::string directory;  // absolute or relative folder; empty when disabled
  std::string source;     // which variable chose it, for messages ("PMRENDER_CACHE_DIR", ...)
};

// The settings the environment gives (see the file comment). Throws InputError for a
// PMRENDER_PROGRAM_CACHE value other than on, off, 1 or 0.
ProgramCacheSettings program_cache_settings_from_environment();
// The same from given values (null: unset), so the rules can be tested without the environment.
ProgramCacheSettings program_cache_settings(const char* switch_value, const char* cache_dir, const char* xdg_cache_home,
                                            const char* home);

// 64-bit FNV-1a and zlib's CRC-32 of bytes, in hex: together the source's fingerprint in a key.
std::string fnv1a64_hex(const void* data, size_t size);
std::string crc32_hex(const void* data, size_t size);

// Everything that decides whether a compiled program fits this process: the full program source
// (as its fingerprint and size), the build options, and the compiler that built it.
struct ProgramCacheKey {
  std::string backend;  // "opencl"
  std::string source_fingerprint;
  std::string options;
  std::string platform_name, platform_version;
  std::string device_name, device_version, driver_version;

  // One line per field; stored in the entry and compared byte for byte on loading.
  std::string text() const;
  // The entry's file name: backend and a hash of text().
  std::string file_name() const;
};

// The fingerprint of a program source for ProgramCacheKey::source_fingerprint.
std::string source_fingerprint(const char* source, size_t size);

enum class CacheLookup {
  hit,       // bytes returned
  missing,   // no entry (or the cache is off)
  rejected,  // an entry was there but unusable: why says what was wrong with it
};

struct CacheLoad {
  CacheLookup lookup = CacheLookup::missing;
  std::vector<unsigned char> bytes;
  std::string why;   // for rejected: one line
  std::string path;  // the entry's file
};

struct CacheStore {
  bool stored = false;
  // When not stored: one line naming the folder and the reason; empty when a stop request
  // (SIGINT, SIGTERM) ended the write, which is no fault of the folder.
  std::string why;
};

// The cache in one folder. Never throws on file-system trouble: loading reports it as missing or
// rejected, storing as not stored.
class ProgramCache {
 public:
  explicit ProgramCache(ProgramCacheSettings settings) : settings_(std::move(settings)) {}

  bool enabled() const { return settings_.enabled; }
  const ProgramCacheSettings& settings() const { return settings_; }
  std::string path_of(const ProgramCacheKey& key) const;

  CacheLoad load(const ProgramCacheKey& key) const;
  // Writes (or replaces) the entry; an entry the driver refused is simply written over.
  CacheStore store(const ProgramCacheKey& key, const std::vector<unsigned char>& bytes) const;

 private:
  ProgramCacheSettings settings_;
};

// The entry file's bytes for key and payload, and the check of such bytes against a key: what
// ProgramCache writes and reads, separate so that tests can build damaged files.
std::vector<unsigned char> encode_cache_entry(const std::string& key_text, const std::vector<unsigned char>& payload);
// Empty why: whole and for this key (payload filled). Otherwise the one-line reason.
std::string decode_cache_entry(const std::vector<unsigned char>& file, const std::string& key_text,
                               std::vector<unsigned char>* payload);

// The first call in the process returns true, later ones false: an unwritable cache folder is
// worth one warning per process, not one per device or per frame.
bool first_cache_warning_of_process();

}  // namespace pm
