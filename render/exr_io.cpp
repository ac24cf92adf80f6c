// OpenEXR output and input of FrameImage: atomic scanline writing (half or float, ZIP), reading
// every RGB layer back, and the completeness check used by --resume and `frames check`. The only
// file that talks to OpenEXR; host code only, never compiled by nvcc.
#include "render/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "render/atomic_file.h"
#include "render/errors.h"
#include "render/exr_header_check.h"
#include "render/interruption.h"

namespace pm {

const char* const kCheckpointAttribute = "pmrender/checkpoint";

namespace {

namespace fs = std::filesystem;

constexpr float kHalfMax = 65504.0f;  // largest finite half; anything above would become Inf
constexpr std::array<const char*, 3> kComponents = {"R", "G", "B"};

std::string channel_name(const std::string& layer, const char* component) {
  return layer.empty() ? std::string(component) : layer + "." + component;
}

std::string layer_label(const std::string& layer) {
  return layer.empty() ? "combined" : "'" + layer + "'";
}

// A malformed image is a bug in the caller; catch it before anything touches the disk.
void check_image_shape(const std::string& path, const FrameImage& image) {
  auto fail = [&](const std::string& why) {
    throw DeviceError("cannot write EXR file '" + path + "': " + why);
  };
  if (image.width <= 0 || image.height <= 0) {
    fail("image size is " + std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  if (image.layers.empty()) fail("image has no layers");
  const size_t pixels = size_t(image.width) * size_t(image.height);
  const size_t expected = pixels * 3;
  std::set<std::string> seen, channels;
  for (const ImageLayer& layer : image.layers) {
    if (!seen.insert(layer.name).second) fail("duplicate layer " + layer_label(layer.name));
    if (layer.rgb.size() != expected) {
      fail("layer " + layer_label(layer.name) + " has " + std::to_string(layer.rgb.size()) +
           " values, expected " + std::to_string(expected));
    }
    for (const char* component : kComponents) channels.insert(channel_name(layer.name, component));
  }
  for (const DataLayer& layer : image.data_layers) {
    if (layer.channels.empty()) fail("data layer " + layer_label(layer.name) + " has no channels");
    if (layer.values.size() != pixels * layer.channels.size()) {
      fail("data layer " + layer_label(layer.name) + " has " + std::to_string(layer.values.size()) +
           " values, expected " + std::to_string(pixels * layer.channels.size()));
    }
    for (size_t c = 0; c < layer.channels.size(); ++c)
      if (!channels.insert(layer.channel_name(c)).second) fail("duplicate channel '" + layer.channel_name(c) + "'");
  }
}

void check_finite(const std::string& path, const FrameImage& image) {
  for (const ImageLayer& layer : image.layers) {
    for (size_t i = 0; i < layer.rgb.size(); ++i) {
      if (std::isfinite(layer.rgb[i])) continue;
      const size_t pixel = i / 3;
      throw DeviceError("refusing to write NaN/Inf to '" + path + "': layer " +
                        layer_label(layer.name) + " pixel (" +
                        std::to_string(pixel % size_t(image.width)) + ", " +
                        std::to_string(pixel / size_t(image.width)) + ") channel " +
                        kComponents[i % 3] + " is " + std::to_string(layer.rgb[i]));
    }
  }
  for (const DataLayer& layer : image.data_layers) {
    for (size_t i = 0; i < layer.values.size(); ++i) {
      if (std::isfinite(layer.values[i])) continue;
      const size_t pixel = i / layer.channels.size();
      throw DeviceError("refusing to write NaN/Inf to '" + path + "': channel '" +
                        layer.channel_name(i % layer.channels.size()) + "' pixel (" +
                        std::to_string(pixel % size_t(image.width)) + ", " +
                        std::to_string(pixel / size_t(image.width)) + ") is " + std::to_string(layer.values[i]));
    }
  }
}

// Writes through AtomicFile rather than std::ofstream so that the data can be fsync'ed before
// the rename, and so that no error is lost: OutputFile's destructor writes the line offset table
// and swallows any exception doing so, hence the remembered first error.
class AtomicFileOStream : public Imf::OStream {
 public:
  explicit AtomicFileOStream(AtomicFile& file) : Imf::OStream(file.temporary_path().c_str()), file_(file) {}

  void write(const char c[], int n) override {
    try {
      file_.write(c, size_t(n));
    } catch (const std::exception& e) {
      remember(e.what());
      throw;
    }
    position_ += uint64_t(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override {
    try {
      file_.seek(size_t(pos));
    } catch (const std::exception& e) {
      remember(e.what());
      throw;
    }
    position_ = pos;
  }
  const std::string& first_error() const { return first_error_; }

 private:
  void remember(const std::string& message) {
    if (first_error_.empty()) first_error_ = message;
  }
  AtomicFile& file_;
  uint64_t position_ = 0;
  std::string first_error_;
};

// Threads that compress an image's line blocks in parallel (ZIP compression of a 1920 x 1080 frame's
// four layers is most of a frame's time on a fast GPU otherwise). OpenEXR's global pool, sized once,
// shared by every frame being written: with several devices, several frames are written at once.
int compression_threads() {
  static const int threads = [] {
    const int n = int(std::min(64u, std::max(1u, std::thread::hardware_concurrency())));
    Imf::setGlobalThreadCount(n);
    return n;
  }();
  return threads;
}

void write_exr_atomically(const std::string& path, const FrameImage& image, bool full_float) {
  const Imf::PixelType type = full_float ? Imf::FLOAT : Imf::HALF;
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [name, value] : image.attributes) {
    header.insert(name, Imf::StringAttribute(value));
  }

  // Half pixels need converted copies; float pixels are read straight from the layers.
  std::vector<std::vector<half>> half_copies;
  const size_t value_size = full_float ? sizeof(float) : sizeof(half);
  const size_t x_stride = 3 * value_size;
  const size_t y_stride = x_stride * size_t(image.width);
  Imf::FrameBuffer frame_buffer;
  for (const ImageLayer& layer : image.layers) {
    char* base = nullptr;
    if (full_float) {
      // OutputFile only reads through the slice; Slice just has no const pointer type.
      base = reinterpret_cast<char*>(const_cast<float*>(layer.rgb.data()));
    } else {
      std::vector<half>& copy = half_copies.emplace_back(layer.rgb.size());
      for (size_t i = 0; i < layer.rgb.size(); ++i) {
        copy[i] = half(std::clamp(layer.rgb[i], -kHalfMax, kHalfMax));
      }
      base = reinterpret_cast<char*>(copy.data());
    }
    for (size_t c = 0; c < kComponents.size(); ++c) {
      const std::string channel = channel_name(layer.name, kComponents[c]);
      header.channels().insert(channel, Imf::Channel(type));
      frame_buffer.insert(channel, Imf::Slice(type, base + c * value_size, x_stride, y_stride));
    }
  }
  // Data layers: the same pixel type, except the ones that must stay float (integer ids).
  for (const DataLayer& layer : image.data_layers) {
    const bool as_float = full_float || layer.full_float;
    const Imf::PixelType layer_type = as_float ? Imf::FLOAT : Imf::HALF;
    const size_t size = as_float ? sizeof(float) : sizeof(half);
    const size_t stride = layer.channels.size() * size;
    char* base = nullptr;
    if (as_float) {
      base = reinterpret_cast<char*>(const_cast<float*>(layer.values.data()));  // read only, as above
    } else {
      std::vector<half>& copy = half_copies.emplace_back(layer.values.size());
      for (size_t i = 0; i < layer.values.size(); ++i) copy[i] = half(std::clamp(layer.values[i], -kHalfMax, kHalfMax));
      base = reinterpret_cast<char*>(copy.data());
    }
    for (size_t c = 0; c < layer.channels.size(); ++c) {
      header.channels().insert(layer.channel_name(c), Imf::Channel(layer_type));
      frame_buffer.insert(layer.channel_name(c),
                          Imf::Slice(layer_type, base + c * size, stride, stride * size_t(image.width)));
    }
  }

  AtomicFile file(path);
  AtomicFileOStream stream(file);
  {
    Imf::OutputFile output(stream, header, compression_threads());
    output.setFrameBuffer(frame_buffer);
    output.writePixels(image.height);
  }  // the destructor writes the offset table; its errors only show in the stream
  throw_if_interrupted();
  if (!stream.first_error().empty()) throw std::runtime_error(stream.first_error());
  file.commit();
}

FrameImage read_exr_layers(const std::string& path) {
  check_exr_header(path);
  Imf::InputFile file(path.c_str());
  const Imf::Header& header = file.header();
  const Imath::Box2i window = header.dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) throw InputError("EXR file '" + path + "' has an empty image");

  // Which of R, G, B each prefix has, and its other channels. std::map sorts "" (the combined
  // layer) first.
  std::map<std::string, std::array<bool, 3>> groups;
  std::map<std::string, DataLayer> data_groups;
  const Imf::ChannelList& channels = header.channels();
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    const std::string name = it.name();
    const size_t dot = name.rfind('.');
    const std::string prefix = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string component = dot == std::string::npos ? name : name.substr(dot + 1);
    const auto found = std::find_if(kComponents.begin(), kComponents.end(),
                                    [&](const char* c) { return component == c; });
    const bool subsampled = it.channel().xSampling != 1 || it.channel().ySampling != 1;
    if (found == kComponents.end()) {  // A, Z, N.X and other non-colour channels
      if (subsampled) continue;
      DataLayer& data = data_groups[prefix];
      data.name = prefix;
      data.full_float = (data.channels.empty() || data.full_float) && it.channel().type == Imf::FLOAT;
      data.channels.push_back(component);
      continue;
    }
    if (subsampled) {
      throw InputError("EXR file '" + path + "': subsampled channel '" + name +
                       "' is not supported");
    }
    groups[prefix][size_t(found - kComponents.begin())] = true;
  }
  if (groups.empty()) throw InputError("EXR file '" + path + "' has no R, G, B channels");

  FrameImage image;
  image.width = int(width);
  image.height = int(height);
  image.layers.reserve(groups.size());
  Imf::FrameBuffer frame_buffer;
  for (const auto& [prefix, present] : groups) {
    for (size_t c = 0; c < kComponents.size(); ++c) {
      if (!present[c]) {
        throw InputError("EXR file '" + path + "': layer " + layer_label(prefix) + " has no " +
                         kComponents[c] + " channel");
      }
    }
    ImageLayer& layer = image.layers.emplace_back();
    layer.name = prefix;
    layer.rgb.resize(size_t(width) * size_t(height) * 3);
    for (size_t c = 0; c < kComponents.size(); ++c) {
      // Make() offsets the pointer by the data window's origin, which need not be (0, 0).
      frame_buffer.insert(channel_name(prefix, kComponents[c]),
                          Imf::Slice::Make(Imf::FLOAT, layer.rgb.data() + c, window,
                                           3 * sizeof(float), 3 * sizeof(float) * size_t(width)));
    }
  }
  for (auto& [prefix, data] : data_groups) {
    DataLayer& layer = image.data_layers.emplace_back(std::move(data));
    const size_t count = layer.channels.size();
    layer.values.resize(size_t(width) * size_t(height) * count);
    for (size_t c = 0; c < count; ++c) {
      frame_buffer.insert(layer.channel_name(c),
                          Imf::Slice::Make(Imf::FLOAT, layer.values.data() + c, window, count * sizeof(float),
                                           count * sizeof(float) * size_t(width)));
    }
  }
  file.setFrameBuffer(frame_buffer);
  file.readPixels(window.min.y, window.max.y);

  for (auto it = header.begin(); it != header.end(); ++it) {
    // Compare the type name instead of dynamic_cast: RTTI across the shared library boundary
    // is not something to depend on.
    if (std::strcmp(it.attribute().typeName(), Imf::StringAttribute::staticTypeName()) == 0) {
      image.attributes.emplace_back(it.name(),
                                    static_cast<const Imf::StringAttribute&>(it.attribute()).value());
    }
  }
  return image;
}

}  // namespace

void write_exr(const std::string& path, const FrameImage& image, bool full_float) {
  check_image_shape(path, image);
  check_finite(path, image);
  try {
    write_exr_atomically(path, image, full_float);
  } catch (const std::exception& e) {
    // OpenEXR may rewrap the exception a stopped write threw; the request itself is what counts.
    if (interruption_signal() != 0) throw Interrupted();
    throw DeviceError("cannot write EXR file '" + path + "': " + e.what());
  }
}

HalfRangeLoss half_range_loss(const FrameImage& image) {
  const float kSmallestHalfStep = 5.9604645e-8f;  // 2^-24, the smallest positive (subnormal) half
  HalfRangeLoss loss;
  for (const ImageLayer& layer : image.layers) {
    loss.values += layer.rgb.size();
    for (float v : layer.rgb) {
      const float magnitude = std::fabs(v);
      loss.nonzero += magnitude != 0;
      loss.clamped += magnitude > kHalfMax;
      loss.flushed_to_zero += magnitude != 0 && magnitude < 0.5f * kSmallestHalfStep;
    }
  }
  return loss;
}

FrameImage read_exr(const std::string& path) {
  try {
    return read_exr_layers(path);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError("cannot read EXR file '" + path + "': " + e.what());
  }
}

ExrFileCheck check_exr_file(const std::string& path) {
  ExrFileCheck check;
  auto fail = [&](ExrFileState state, const std::string& problem) {
    check.state = state;
    check.problem = problem;
    return check;
  };
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) return fail(ExrFileState::missing, "no such file");
  if (ec) return fail(ExrFileState::unreadable, ec.message());
  if (status.type() != fs::file_type::regular) return fail(ExrFileState::unreadable, "not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return fail(ExrFileState::unreadable, ec.message());
  if (size == 0) return fail(ExrFileState::truncated, "empty file");

  // The magic number tells a file cut short (it starts as an EXR) from one that never was one.
  std::FILE* raw = std::fopen(path.c_str(), "rb");
  if (!raw) return fail(ExrFileState::unreadable, errno_text("cannot open"));
  unsigned char magic[4] = {};
  const size_t got = std::fread(magic, 1, sizeof(magic), raw);
  std::fclose(raw);
  const unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  if (std::memcmp(magic, kMagic, got) != 0) return fail(ExrFileState::unreadable, "not an OpenEXR file");
  if (got < sizeof(magic)) return fail(ExrFileState::truncated, "cut short inside the magic number");

  try {
    check_exr_header(path);
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    check.width = int(int64_t(window.max.x) - window.min.x + 1);
    check.height = int(int64_t(window.max.y) - window.min.y + 1);
    if (!file.isComplete()) return fail(ExrFileState::truncated, "scanline chunks are missing");
    // isComplete() only checks the line offset table, which sits near the start of the file,
    // so a copy cut short after the table passes it. Decoding one channel reads every chunk.
    const Imf::ChannelList& channels = header.channels();
    for (auto it = channels.begin(); it != channels.end(); ++it) {
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1) continue;
      std::vector<float> scratch(size_t(check.width) * size_t(check.height));
      Imf::FrameBuffer frame_buffer;
      frame_buffer.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, scratch.data(), window, sizeof(float),
                                                      sizeof(float) * size_t(check.width)));
      file.setFrameBuffer(frame_buffer);
      file.readPixels(window.min.y, window.max.y);
      break;
    }
    // (only subsampled channels: the offset table is all there is to go on)
    if (const auto* passes = header.findTypedAttribute<Imf::StringAttribute>(kCheckpointAttribute))
      return fail(ExrFileState::checkpoint, "a checkpoint after " + passes->value() + " passes (render --resume continues it)");
  } catch (const std::exception& e) {
    return fail(ExrFileState::truncated, e.what());
  }
  check.state = ExrFileState::complete;
  return check;
}

bool exr_is_complete(const std::string& path) { return check_exr_file(path).state == ExrFileState::complete; }

const char* exr_file_state_name(ExrFileState state) {
  switch (state) {
    case ExrFileState::complete: return "complete";
    case ExrFileState::missing: return "missing";
    case ExrFileState::truncated: return "truncated";
    case ExrFileState::unreadable: return "unreadable";
    case ExrFileState::checkpoint: return "unfinished";
  }
  return "unknown";
}

}  // namespace pm
