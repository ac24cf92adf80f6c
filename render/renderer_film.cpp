// The renderer's film on the host: its sums as checkpoints and a sequence's passes store and
// restore them (the device's packed layout unpacked), and the read-back that resolves the film
// into a FrameImage with its layers (S7).
#include "render/renderer.h"

#include <algorithm>

#include "kernels/common/film.h"
#include "render/errors.h"

namespace pm {

namespace {

std::vector<float> rgb_from_float4(const std::vector<float4>& pixels) {
  std::vector<float> rgb(pixels.size() * 3);
  for (size_t i = 0; i < pixels.size(); ++i) {
    rgb[3 * i + 0] = pixels[i].x;
    rgb[3 * i + 1] = pixels[i].y;
    rgb[3 * i + 2] = pixels[i].z;
  }
  return rgb;
}

}  // namespace

// The device keeps the odd-pass sum's red and green in the w of the direct and indirect buffers,
// its blue in a plane, and a caustic sum only where the scene has mirrors (kernels/common/film.h);
// FilmSums holds every sum apart, with every w zero and the caustic sum zero where the film has
// none, as checkpoints store them.
FilmSums Renderer::film_sums() {
  const size_t pixels = size_t(width_) * height_;
  FilmSums sums;
  sums.passes = passes_done_;
  sums.odd_passes = odd_passes_;
  std::vector<float4> direct(pixels);
  std::vector<float> odd_blue(pixels);
  sums.indirect.resize(pixels);
  sums.caustic.assign(pixels, float4{0, 0, 0, 0});
  sums.odd.resize(pixels);
  device_.download(buffers_[BufferSlot::film_direct], direct.data(), pixels * sizeof(float4));
  device_.download(buffers_[BufferSlot::film_indirect_sum], sums.indirect.data(), pixels * sizeof(float4));
  device_.download(buffers_[BufferSlot::film_odd_blue], odd_blue.data(), pixels * sizeof(float));
  if (has_caustic_film())
    device_.download(buffers_[BufferSlot::film_caustic_sum], sums.caustic.data(), pixels * sizeof(float4));
  for (size_t i = 0; i < pixels; ++i) {
    sums.odd[i] = float4{direct[i].w, sums.indirect[i].w, odd_blue[i], 0.0f};
    sums.indirect[i].w = 0.0f;
  }
  return sums;
}

void Renderer::set_film_sums(const FilmSums& sums) {
  const size_t pixels = size_t(width_) * height_;
  if (sums.indirect.size() != pixels || sums.caustic.size() != pixels || sums.odd.size() != pixels)
    throw DeviceError("renderer: film sums of another size than the film");
  if (!has_caustic_film() && std::any_of(sums.caustic.begin(), sums.caustic.end(), [](const float4& v) {
        return v.x != 0 || v.y != 0 || v.z != 0;
      }))
    throw DeviceError("renderer: film sums with caustic light for a scene without mirrors, which makes none");
  std::vector<float4> indirect = sums.indirect, direct(pixels);
  std::vector<float> odd_blue(pixels);
  device_.download(buffers_[BufferSlot::film_direct], direct.data(), pixels * sizeof(float4));
  for (size_t i = 0; i < pixels; ++i) {
    direct[i].w = sums.odd[i].x;
    indirect[i].w = sums.odd[i].y;
    odd_blue[i] = sums.odd[i].z;
  }
  device_.upload(buffers_[BufferSlot::film_direct], direct.data(), pixels * sizeof(float4));
  device_.upload(buffers_[BufferSlot::film_indirect_sum], indirect.data(), pixels * sizeof(float4));
  device_.upload(buffers_[BufferSlot::film_odd_blue], odd_blue.data(), pixels * sizeof(float));
  if (has_caustic_film())
    device_.upload(buffers_[BufferSlot::film_caustic_sum], sums.caustic.data(), pixels * sizeof(float4));
  passes_done_ = sums.passes;
  odd_passes_ = sums.odd_passes;
  next_pass_ = sums.passes;
  if (!sums.control.sums.empty() && sums.control.bounces == control_bounces()) control_->adopt(sums.control);
}

void Renderer::add_film_sums(const FilmSums& other) {
  FilmSums sums = film_sums();
  if (other.indirect.size() != sums.indirect.size()) throw DeviceError("renderer: film sums of another size than the film");
  auto add = [](std::vector<float4>& a, const std::vector<float4>& b) {
    for (size_t i = 0; i < a.size(); ++i) a[i] = float4{a[i].x + b[i].x, a[i].y + b[i].y, a[i].z + b[i].z, 0.0f};
  };
  add(sums.indirect, other.indirect);
  add(sums.caustic, other.caustic);
  add(sums.odd, other.odd);
  const uint32_t next = next_pass_;
  sums.passes += other.passes;
  sums.odd_passes += other.odd_passes;
  set_film_sums(sums);
  next_pass_ = next;
}

FrameImage Renderer::read_image(FrameStats* stats) {
  const size_t pixels = size_t(width_) * height_;
  auto layer = [&](BufferSlot slot) {
    std::vector<float4> data(pixels);
    device_.download(buffers_[slot], data.data(), pixels * sizeof(float4));
    return data;
  };
  // The film resolved here (film.h, film_combine): the sums over the passes, and a pixel whose
  // combined value is not finite black in every layer and counted.
  std::vector<float4> direct = layer(BufferSlot::film_direct), indirect = layer(BufferSlot::film_indirect_sum),
                      caustic = has_caustic_film() ? layer(BufferSlot::film_caustic_sum)
                                                   : std::vector<float4>(pixels, float4{0, 0, 0, 0}),
                      combined(pixels);
  const uint32_t passes = passes_done_ > 0 ? passes_done_ : 1u;
  int repaired = 0;
  for (size_t i = 0; i < pixels; ++i) {
    Vec3 sum;
    if (film_combine(direct[i], indirect[i], caustic[i], passes, &sum)) {
      combined[i] = vec3_to_float4(sum, 0.0f);
      indirect[i] = vec3_to_float4(film_resolved(indirect[i], passes), 0.0f);
      caustic[i] = vec3_to_float4(film_resolved(caustic[i], passes), 0.0f);
    } else {
      combined[i] = direct[i] = indirect[i] = caustic[i] = float4{0, 0, 0, 0};
      ++repaired;
    }
  }

  FrameImage image;
  image.width = width_;
  image.height = height_;
  image.layers.push_back(ImageLayer{"", rgb_from_float4(combined)});
  image.layers.push_back(ImageLayer{"direct", rgb_from_float4(direct)});
  image.layers.push_back(ImageLayer{"indirect", rgb_from_float4(indirect)});
  image.layers.push_back(ImageLayer{"caustic", rgb_from_float4(caustic)});
  if (!settings_.layers.empty())
    add_film_layers(image, settings_.layers, layer(BufferSlot::film_albedo), layer(BufferSlot::film_normal),
                    layer(BufferSlot::film_position));
  if (stats) stats->repaired_pixels = repaired;
  return image;
}

}  // namespace pm
