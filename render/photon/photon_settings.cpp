// Photon-mapping settings: name tables, validation, scene-dependent defaults and description.
#include "render/photon/photon_settings.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "render/errors.h"
#include "render/photon/photon_mapping.h"

namespace pm {

const NameTable kEstimatorNames = {{"pd", PM_ESTIMATOR_PD}, {"radius", PM_ESTIMATOR_RADIUS}, {"knn", PM_ESTIMATOR_KNN}};
const NameTable kKernelShapeNames = {{"constant", PM_KERNEL_CONSTANT}, {"epanechnikov", PM_KERNEL_EPANECHNIKOV}};
const NameTable kPhotonMapBuilderNames = {{"lbvh", kPhotonMapLbvh}, {"vvh", kPhotonMapVvh}};
const NameTable kPhotonSequenceNames = {{"random", PM_PHOTON_SEQUENCE_RANDOM}, {"halton", PM_PHOTON_SEQUENCE_HALTON}};
const NameTable kProgressiveNames = {{"average", kProgressiveAverage}, {"shrink", kProgressiveShrink}};
const NameTable kFootprintClipNames = {{"on", 1}, {"off", 0}};

namespace {

void require_named(const NameTable& table, int value, const char* setting) {
  if (std::string(name_of(table, value)) == "?")
    throw SettingError(setting, "expected " + names_list(table) + ", got value " + std::to_string(value));
}

// Hit records of one pass are indexed with 32-bit integers in the photon map (photon_map.h).
constexpr uint64_t kMaxHitSlots = uint64_t(1) << 29;

}  // namespace

void PhotonSettings::validate() const {
  if (bounces < 0 || bounces > 16) throw SettingError("bounces", "expected 0 to 16, got " + std::to_string(bounces));
  if (!(smoothing >= 0) || !std::isfinite(smoothing))
    throw SettingError("smoothing", "expected auto or a positive number, got " + std::to_string(smoothing));
  if (!(footprint_thickness > 0 && footprint_thickness <= 4))
    throw SettingError("footprint-thickness", "expected a number above 0 and at most 4, got " +
                                                  std::to_string(footprint_thickness));
  if (!(overlap >= 0) || !std::isfinite(overlap))
    throw SettingError("overlap", "expected auto or a positive number, got " + std::to_string(overlap));
  if (!(rmax >= 0) || !std::isfinite(rmax)) throw SettingError("rmax", "must be a positive length in metres");
  if (!(radius >= 0) || !std::isfinite(radius)) throw SettingError("radius", "must be a positive length in metres");
  if (knn_k < 1 || knn_k > 256) throw SettingError("k", "expected 1 to 256, got " + std::to_string(knn_k));
  if (leaf_threshold < 0) throw SettingError("leaf", "expected auto or a positive integer");
  if (!(leaf_c > 0) || !std::isfinite(leaf_c)) throw SettingError("leaf-c", "must be positive");
  require_named(kEstimatorNames, estimator, "estimator");
  require_named(kKernelShapeNames, kernel_shape, "kernel");
  require_named(kPhotonMapBuilderNames, builder, "photon-bvh");
  require_named(kPhotonSequenceNames, sequence, "photon-sequence");
  require_named(kProgressiveNames, progressive, "progressive");
  if (final_gather > 65536) throw SettingError("final-gather", "expected 0 to 65536 rays, got " + std::to_string(final_gather));
  if (final_gather > 0 && estimator == PM_ESTIMATOR_KNN)
    throw SettingError("final-gather", "reads the footprints of --estimator pd or radius, not knn");
  if (final_gather > 0 && bounces < 1) throw SettingError("final-gather", "needs --bounces 1 or more");
  if (!(tile_gather == kTileGatherAuto || (tile_gather >= 0 && std::isfinite(tile_gather))))
    throw SettingError("tile-gather", "expected auto, off or a positive number, got " + std::to_string(tile_gather));
  if (!(alpha >= 0 && alpha < 1))
    throw SettingError("alpha", "expected auto or a number between 0 and 1 (exclusive), got " + std::to_string(alpha));
  if (photons * hit_slots_per_photon() > kMaxHitSlots)
    throw SettingError("photons", std::to_string(photons) + " photons per pass need more than 2^29 hit records; "
                                  "use fewer photons per pass and more passes");
  if (photons_max > 0 && photons_max < photons)
    throw SettingError("photons-max", "expected at least --photons (" + std::to_string(photons) + "), got " +
                                          std::to_string(photons_max));
  if (photons_max > photons && sequence == PM_PHOTON_SEQUENCE_HALTON)
    throw SettingError("photons-max", "needs --photon-sequence random (Halton photons are the same count every pass)");
  if (photons_max * hit_slots_per_photon() > kMaxHitSlots)
    throw SettingError("photons-max", std::to_string(photons_max) + " photons per pass need more than 2^29 hit "
                                      "records; use fewer");
}

uint64_t PhotonSettings::photons_max_or_default() const {
  if (photons_max > 0) return photons_max;
  if (final_gather == 0 || sequence == PM_PHOTON_SEQUENCE_HALTON) return photons;
  return std::max(photons, std::min(kPhotonGrowthFactor * photons, kPhotonGrowthMost));
}

// Pass k's doublings: none before kPhotonGrowthStart, then one more each time k quadruples.
static uint32_t photon_doublings(uint32_t pass) {
  uint32_t doublings = 0;
  for (uint64_t step = kPhotonGrowthStart; pass >= step; step *= 4) ++doublings;
  return doublings;
}

uint64_t PhotonSettings::photons_in_pass(uint32_t pass) const {
  // At most 13 doublings in 2^32 passes, on at most 2^29 photons: no overflow.
  return std::min(photons_max_or_default(), photons << photon_doublings(pass));
}

uint64_t PhotonSettings::photons_before_pass(uint32_t pass) const {
  // Summed by runs of passes of one count: [0, start), [start, 4 start), [4 start, 16 start), ...
  uint64_t sum = 0;
  uint64_t run_begin = 0, run_end = kPhotonGrowthStart;
  while (run_begin < pass) {
    const uint64_t end = std::min<uint64_t>(run_end, pass);
    sum += (end - run_begin) * photons_in_pass(uint32_t(run_begin));
    run_begin = run_end;
    run_end *= 4;
  }
  return sum;
}

PhotonSettings PhotonSettings::resolved(const SceneMeasures& measures) const {
  PhotonSettings s = *this;
  if (s.rmax == 0) s.rmax = float(0.1 * measures.diagonal);
  if (s.radius == 0) s.radius = float(0.05 * measures.diagonal);
  // Chosen by the measured bias of each estimator on the benchmark scenes (docs/accuracy.md): the
  // fixed radius's spheres reach far across the bends of curved surfaces, pd's thin footprints
  // hardly (but pd's shrinking passes reach the medium sizes where its bias without the weighting
  // peaks: "Shrink that converges"), and knn has its own region (knn_gather.h).
  if (s.facet_weighting == kFacetWeightingAuto)
    s.facet_weighting = s.estimator == PM_ESTIMATOR_RADIUS || s.shrinking_pd() ? 1 : 0;
  s.overlap = overlap_or_default();
  s.alpha = alpha_or_default();
  return s;
}

std::string PhotonSettings::describe() const {
  std::ostringstream s;
  s << "photons=" << photons;
  if (photons_max_or_default() > photons) s << " photons_max=" << photons_max_or_default();
  s << " bounces=" << bounces << " estimator=" << name_of(kEstimatorNames, estimator)
    << " kernel=" << name_of(kKernelShapeNames, kernel_shape) << " smoothing=";
  if (smoothing > 0) s << smoothing;
  else s << "auto overlap=" << overlap_or_default();
  s << " rmax=" << rmax;
  if (estimator == PM_ESTIMATOR_RADIUS) s << " radius=" << radius;
  if (estimator == PM_ESTIMATOR_KNN) s << " k=" << knn_k;
  if (final_gather > 0) s << " final_gather=" << final_gather;
  s << " photon_bvh=" << name_of(kPhotonMapBuilderNames, builder)
    << " leaf=" << (leaf_threshold > 0 ? std::to_string(leaf_threshold) : "auto")
    << " photon_sequence=" << name_of(kPhotonSequenceNames, sequence)
    << " footprint_clip=" << name_of(kFootprintClipNames, footprint_clip ? 1 : 0)
    << " footprint_coverage=" << name_of(kFootprintClipNames, footprint_coverage ? 1 : 0)
    << " footprint_thickness=" << footprint_thickness << " facet_weighting="
    << (facet_weighting == kFacetWeightingAuto ? "auto" : name_of(kFootprintClipNames, facet_weighting ? 1 : 0))
    << " progressive=" << name_of(kProgressiveNames, progressive) << " tile_gather=";
  if (tile_gather > 0) s << tile_gather;
  else s << (tile_gather == kTileGatherAuto ? "auto" : "off");
  if (progressive == kProgressiveShrink) s << " alpha=" << alpha_or_default();
  return s.str();
}

double PhotonSettings::footprint_scale(uint32_t pass) const {
  if (progressive != kProgressiveShrink) return 1.0;
  const double a = alpha_or_default();
  // In logarithms: a product of a million factors stays exact enough and never underflows early.
  double log_area = 0;
  for (uint32_t j = 1; j <= pass; ++j) log_area += std::log((j + a) / (j + 1.0));
  return std::exp(0.5 * log_area);
}

std::unique_ptr<IndirectMethod> PhotonSettings::create(const MethodContext& context) const {
  return std::make_unique<PhotonMapping>(context, *this);
}

}  // namespace pm
