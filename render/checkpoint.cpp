// Checkpoint state files: a text header (magic, frame, size, passes, seconds, fingerprint), then
// the three film sums as raw little-endian float4 arrays.
#include "render/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "render/atomic_file.h"

namespace pm {

namespace {

const char kMagic[] = "pmrender checkpoint 1";

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

std::optional<FrameCheckpoint> read_checkpoint(const std::string& path, int frame, int width, int height,
                                               const std::string& fingerprint, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<FrameCheckpoint> {
    if (why) *why = reason;
    return std::nullopt;
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("no checkpoint");
  std::string line;
  if (!std::getline(in, line) || line != kMagic) return fail("not a pmrender checkpoint");
  FrameCheckpoint c;
  std::string key;
  bool ended = false;
  while (!ended && std::getline(in, line)) {
    std::istringstream words(line);
    words >> key;
    if (key == "frame") words >> c.frame;
    else if (key == "size") words >> c.width >> c.height;
    else if (key == "passes") words >> c.sums.passes >> c.sums.odd_passes;
    else if (key == "seconds") words >> c.seconds;
    else if (key == "fingerprint") c.fingerprint = line.size() > 12 ? line.substr(12) : "";
    else if (key == "end") ended = true;
    else return fail("unknown header line '" + line.substr(0, 40) + "'");
    if (key != "fingerprint" && key != "end" && !words) return fail("bad header line '" + line.substr(0, 40) + "'");
  }
  if (!ended) return fail("truncated header");
  if (c.frame != frame) return fail("it is frame " + std::to_string(c.frame) + "'s");
  if (c.width != width || c.height != height) return fail("it has another resolution");
  if (c.fingerprint != fingerprint) return fail("it was rendered with other settings or another scene");
  if (c.sums.passes < 1) return fail("it holds no pass");
  const size_t pixels = size_t(width) * size_t(height);
  for (std::vector<float4>* sum : {&c.sums.indirect, &c.sums.caustic, &c.sums.odd}) {
    sum->resize(pixels);
    if (!in.read(reinterpret_cast<char*>(sum->data()), std::streamsize(pixels * sizeof(float4))))
      return fail("truncated film sums");
  }
  if (in.peek() != std::char_traits<char>::eof()) return fail("trailing bytes after the film sums");
  return c;
}

}  // namespace pm
