// Path-tracer settings: validation and description.
#include "render/path/path_settings.h"

#include <sstream>

#include "render/errors.h"
#include "render/path/path_tracing.h"

namespace pm {

void PathSettings::validate() const {
  if (samples < 1 || samples > 65536)
    throw SettingError("spp", "expected 1 to 65536 paths per pixel and pass, got " + std::to_string(samples));
  if (bounces < 0 || bounces > 16) throw SettingError("bounces", "expected 0 to 16, got " + std::to_string(bounces));
}

std::string PathSettings::describe() const {
  std::ostringstream s;
  s << "spp=" << samples << " bounces=" << bounces;
  if (!mis) s << " mis=off";
  return s.str();
}

std::unique_ptr<IndirectMethod> PathSettings::create(const MethodContext& context) const {
  return std::make_unique<PathTracing>(context, *this);
}

}  // namespace pm
