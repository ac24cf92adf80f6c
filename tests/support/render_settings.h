// RenderSettings for the tests that render with photon mapping or radiosity: the method's
// settings become the renderer's method.
#pragma once

#include <memory>

#include "render/photon/photon_settings.h"
#include "render/radiosity/radiosity_settings.h"
#include "render/renderer.h"

namespace pm::test {

inline RenderSettings photon_render_settings(const PhotonSettings& photons, uint32_t passes = 1) {
  RenderSettings settings;
  settings.passes = passes;
  settings.method = std::make_shared<PhotonSettings>(photons);
  return settings;
}

// RenderSettings for the tests that render with vertex link radiosity.
inline RenderSettings radiosity_render_settings(const RadiositySettings& radiosity) {
  RenderSettings settings;
  settings.method = std::make_shared<RadiositySettings>(radiosity);
  return settings;
}

// The photon settings a RenderSettings carries (tests build them through photon_render_settings).
inline const PhotonSettings& photon_settings_of(const RenderSettings& settings) {
  return dynamic_cast<const PhotonSettings&>(*settings.method);
}

// A copy of the photon settings that settings carries, now owned by settings and editable:
// edit_photons(settings).smoothing = 4.
inline PhotonSettings& edit_photons(RenderSettings& settings) {
  auto copy = std::make_shared<PhotonSettings>(photon_settings_of(settings));
  PhotonSettings& editable = *copy;
  settings.method = copy;
  return editable;
}

}  // namespace pm::test
