// Checkpoint state files: a text header (magic, frame, size, passes, seconds, fingerprint, each
// line once), then the three film sums as raw little-endian float4 arrays. The reader trusts
// nothing in the file: numbers are plain decimal and in range, the pass counts are the ones the
// pass loop produces, the sums are exactly as long as the size says and finite.
#include "render/checkpoint.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "render/atomic_file.h"

namespace pm {

namespace {

const char kMagic[] = "pmrender checkpoint 1";
// The header's keys, in the order they are written; each must appear once before "end".
const char* const kKeys[] = {"frame", "size", "passes", "seconds", "fingerprint"};
const int kKeyCount = 5;

// The whole of text as one number of type T (std::from_chars: no sign for unsigned types, no
// blanks, nothing after it).
template <typename T>
bool parse_whole(const std::string& text, T* value) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return !text.empty() && result.ec == std::errc() && result.ptr == end;
}

// text split at every space ("4 3" -> {"4", "3"}; "4  3" -> {"4", "", "3"}).
std::vector<std::string> fields(const std::string& text) {
  std::vector<std::string> out;
  for (size_t start = 0;;) {
    const size_t space = text.find(' ', start);
    out.push_back(text.substr(start, space == std::string::npos ? std::string::npos : space - start));
    if (space == std::string::npos) return out;
    start = space + 1;
  }
}

// One header line's value into c; false when it is malformed or out of range.
bool parse_value(int key, const std::string& value, FrameCheckpoint& c) {
  const std::vector<std::string> f = fields(value);
  switch (key) {
    case 0:
      return parse_whole(value, &c.frame);
    case 1:
      return f.size() == 2 && parse_whole(f[0], &c.width) && parse_whole(f[1], &c.height) && c.width > 0 &&
             c.height > 0;
    case 2:
      return f.size() == 2 && parse_whole(f[0], &c.sums.passes) && parse_whole(f[1], &c.sums.odd_passes);
    case 3:
      return parse_whole(value, &c.seconds) && std::isfinite(c.seconds) && c.seconds >= 0;
    default:
      c.fingerprint = value;
      return true;
  }
}

bool finite_sums(const std::vector<float4>& sum) {
  for (const float4& v : sum)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
  return true;
}

}  // namespace

std::string checkpoint_state_path(const std::string& image_path) { return image_path + ".pmstate"; }

void write_checkpoint(const std::string& path, const FrameCheckpoint& c) {
  std::ostringstream header;
  header.precision(17);
  header << kMagic << "\n"
         << "frame " << c.frame << "\n"
         << "size " << c.width << " " << c.height << "\n"
         << "passes " << c.sums.passes << " " << c.sums.odd_passes << "\n"
         << "seconds " << c.seconds << "\n"
         << "fingerprint " << c.fingerprint << "\n"
         << "end\n";
  const std::string text = header.str();
  AtomicFile file(path);
  file.write(text.data(), text.size());
  for (const std::vector<float4>* sum : {&c.sums.indirect, &c.sums.caustic, &c.sums.odd})
    file.write(sum->data(), sum->size() * sizeof(float4));
  file.commit();
}

namespace {

// The header from the start of in up to and including its "end" line (parsed as
// read_checkpoint_header describes), leaving in at the first byte of the film sums.
std::optional<FrameCheckpoint> parse_header(std::istream& in, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<FrameCheckpoint> {
    if (why) *why = reason;
    return std::nullopt;
  };
  std::string line;
  if (!std::getline(in, line) || line != kMagic) return fail("not a pmrender checkpoint");
  FrameCheckpoint c;
  bool seen[kKeyCount] = {};
  while (std::getline(in, line)) {
    if (line == "end") {
      for (int k = 0; k < kKeyCount; ++k)
        if (!seen[k]) return fail(std::string("no ") + kKeys[k] + " line in the header");
      // Passes are numbered from 0, so of n passes n / 2 have an odd number.
      if (c.sums.passes < 1) return fail("it holds no pass");
      if (c.sums.odd_passes != c.sums.passes / 2) return fail("its pass counts disagree");
      return c;
    }
    const std::string shown = "'" + line.substr(0, 40) + "'";
    const size_t space = line.find(' ');
    const std::string name = line.substr(0, space);
    int key = 0;
    while (key < kKeyCount && name != kKeys[key]) ++key;
    if (key == kKeyCount || space == std::string::npos) return fail("unknown header line " + shown);
    if (seen[key]) return fail("repeated header line " + shown);
    seen[key] = true;
    if (!parse_value(key, line.substr(space + 1), c)) return fail("bad header line " + shown);
  }
  return fail("truncated header");
}

}  // namespace

std::optional<FrameCheckpoint> read_checkpoint_header(const std::string& path, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (why) *why = "no checkpoint";
    return std::nullopt;
  }
  return parse_header(in, why);
}

std::optional<FrameCheckpoint> read_checkpoint(const std::string& path, int frame, int width, int height,
                                               const std::string& fingerprint, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<FrameCheckpoint> {
    if (why) *why = reason;
    return std::nullopt;
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("no checkpoint");
  std::optional<FrameCheckpoint> c = parse_header(in, why);
  if (!c) return c;
  if (c->frame != frame) return fail("it is frame " + std::to_string(c->frame) + "'s");
  if (c->width != width || c->height != height) return fail("it has another resolution");
  if (c->fingerprint != fingerprint) return fail("it was rendered with other settings or another scene");
  // The film sums must fill the rest of the file exactly: measured before anything is allocated.
  const size_t pixels = size_t(width) * size_t(height);
  if (in.eof()) return fail("truncated film sums");  // the file ends in its "end" line
  const std::streamoff sums_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff file_end = in.tellg();
  if (sums_start < 0 || file_end < sums_start) return fail("unreadable film sums");
  // Divided rather than multiplied: width x height x 48 bytes can exceed 64 bits.
  const uint64_t bytes = uint64_t(file_end - sums_start), per_pixel = 3 * sizeof(float4);
  if (bytes / per_pixel < pixels) return fail("truncated film sums");
  if (bytes / per_pixel > pixels || bytes % per_pixel != 0) return fail("trailing bytes after the film sums");
  in.seekg(sums_start);
  for (std::vector<float4>* sum : {&c->sums.indirect, &c->sums.caustic, &c->sums.odd}) {
    sum->resize(pixels);
    if (!in.read(reinterpret_cast<char*>(sum->data()), std::streamsize(pixels * sizeof(float4))))
      return fail("truncated film sums");
    if (!finite_sums(*sum)) return fail("its film sums are not finite");
  }
  return c;
}

}  // namespace pm
