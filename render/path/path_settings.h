// Settings of the reference path tracer (--method path): paths per shading point and pass, and
// the photon mapper's bounce count (the same semantics, kernels/common/path_trace.h). Each
// setting's name in messages is its command-line option's without the dashes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "render/indirect_method.h"

namespace pm {

class PathSettings final : public MethodSettings {
 public:
  uint32_t samples = 16;  // paths per shading point per pass (--spp)
  int bounces = 2;        // diffuse and glossy bounces of indirect light, as PhotonSettings::bounces
  // Area lights: multiple importance sampling of light samples and sampled directions (--path-mis
  // on), or light samples alone (off); both converge to the same image.
  bool mis = true;

  const char* method_name() const override { return "path"; }
  void validate() const override;
  std::unique_ptr<IndirectMethod> create(const MethodContext& context) const override;
  // One line: every setting.
  std::string describe() const;
};

}  // namespace pm
