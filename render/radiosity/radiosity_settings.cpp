// Vertex link radiosity settings: name tables, validation, scene-dependent defaults and description.
#include "render/radiosity/radiosity_settings.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "render/errors.h"
#include "render/radiosity/vertex_link_radiosity.h"

namespace pm {

const NameTable kRadiositySidesNames = {{"one", 1}, {"two", 2}};
const NameTable kRadiosityLightSamplesNames = {{"vertex", PM_RADIOSITY_LIGHT_VERTEX},
                                               {"one-ring", PM_RADIOSITY_LIGHT_ONE_RING}};
const NameTable kRadiosityLinkOriginsNames = {{"vertex", PM_RADIOSITY_ORIGINS_VERTEX},
                                              {"one-ring", PM_RADIOSITY_ORIGINS_ONE_RING}};

namespace {

// The link build's scratch when link_batch is 0 (auto).
constexpr uint64_t kLinkScratchBudget = uint64_t(256) << 20;

}  // namespace

void RadiositySettings::validate() const {
  if (directions > 16384)
    throw SettingError("directions", "expected 1 to 16384 directions per element, got " + std::to_string(directions));
  if (bounces < 0 || bounces > 16) throw SettingError("bounces", "expected 0 to 16, got " + std::to_string(bounces));
  if (!(max_edge >= 0) || !std::isfinite(max_edge))
    throw SettingError("max-edge", "must be a positive length in metres (or 0: automatic)");
  if (!(feature_angle > 0) || !(feature_angle <= 180))
    throw SettingError("feature-angle", "expected more than 0 and at most 180 degrees, got " + std::to_string(feature_angle));
  if (smooth_passes < 0 || smooth_passes > 64)
    throw SettingError("smooth-passes", "expected 0 to 64, got " + std::to_string(smooth_passes));
  if (std::string(name_of(kRadiositySidesNames, sides)) == "?")
    throw SettingError("sides", "expected " + names_list(kRadiositySidesNames));
  if (std::string(name_of(kRadiosityLightSamplesNames, light_samples)) == "?")
    throw SettingError("light-samples", "expected " + names_list(kRadiosityLightSamplesNames));
  if (std::string(name_of(kRadiosityLinkOriginsNames, link_origins)) == "?")
    throw SettingError("link-origins", "expected " + names_list(kRadiosityLinkOriginsNames));
  if (!(hidden_origins >= 0) || !std::isfinite(hidden_origins))
    throw SettingError("hidden-origins", "expected 0 (off) or a positive multiple of the max edge");
  if (final_gather > 65536) throw SettingError("final-gather", "expected 0 to 65536 rays, got " + std::to_string(final_gather));
  if (final_gather > 0 && bounces < 1) throw SettingError("final-gather", "needs --bounces 1 or more");
  // One launch traces batch * nC rays, indexed with 32 bits.
  const uint32_t nc = resolved_directions();
  if (uint64_t(link_batch) * nc > 0x7fffffffull)
    throw SettingError("link-batch", std::to_string(link_batch) + " elements of " + std::to_string(nc) +
                                         " directions exceed 2^31 rays per launch");
}

RadiositySettings RadiositySettings::resolved(const SceneMeasures& measures) const {
  RadiositySettings s = *this;
  // Diagonal / 50, chosen by measured indirect bias at its link cost across the benchmark scenes
  // and both Cornell boxes (docs/accuracy.md, radiosity section): from / 25 it took every scene
  // closer to the path-traced references for 1.2 to 3.8 times the link rays.
  if (s.max_edge == 0) s.max_edge = float(measures.diagonal / 50.0);
  if (!(s.max_edge > 0)) s.max_edge = 1.0f;  // an empty or point-sized scene: nothing to refine
  s.directions = resolved_directions();
  return s;
}

uint32_t RadiositySettings::batch_elements(uint64_t elements) const {
  uint64_t batch = link_batch > 0 ? link_batch : kLinkScratchBudget / radiosity_scratch_bytes_per_element(directions);
  batch = std::min<uint64_t>(batch, 0x7fffffffull / directions);
  return uint32_t(std::max<uint64_t>(1, std::min(batch, std::max<uint64_t>(elements, 1))));
}

bool RadiositySettings::same_mesh_as(const RadiositySettings& o) const {
  return max_edge == o.max_edge && feature_angle == o.feature_angle && sides == o.sides;
}

bool RadiositySettings::same_links_as(const RadiositySettings& o) const {
  // The mesh and the link rays (their directions, origins and the hidden origins' distance); the
  // link rays' random numbers do not depend on the seed (radiosity_links.h), the batches do not
  // change a link.
  return same_mesh_as(o) && resolved_directions() == o.resolved_directions() && link_origins == o.link_origins &&
         hidden_origins == o.hidden_origins;
}

std::string RadiositySettings::describe() const {
  std::ostringstream s;
  s << "directions=" << resolved_directions() << " bounces=" << bounces << " max_edge=" << max_edge
    << " feature_angle=" << feature_angle << " smooth_passes=" << smooth_passes
    << " sides=" << name_of(kRadiositySidesNames, sides)
    << " light_samples=" << name_of(kRadiosityLightSamplesNames, light_samples)
    << " link_origins=" << name_of(kRadiosityLinkOriginsNames, link_origins)
    << " hidden_origins=" << hidden_origins << " link_batch=" << (link_batch > 0 ? std::to_string(link_batch) : "auto");
  if (final_gather > 0) s << " final_gather=" << final_gather;
  return s.str();
}

std::unique_ptr<IndirectMethod> RadiositySettings::create(const MethodContext& context) const {
  return std::make_unique<VertexLinkRadiosity>(context, *this);
}

std::shared_ptr<const HostWorkAhead> RadiositySettings::begin_host_work(const Scene& scene,
                                                                        const SceneMeasures& measures) const {
  return begin_radiosity_host_mesh(scene, resolved(measures));
}

}  // namespace pm
