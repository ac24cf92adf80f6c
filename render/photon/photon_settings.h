// Settings of the photon-mapping method (Fabianowski & Dingliana 2009), their name tables and
// their validation. Each setting's name in messages is its command-line option's without the
// dashes (docs/algorithm.md explains each one).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "render/indirect_method.h"
#include "render/kernel_abi.h"
#include "kernels/common/footprint.h"
#include "render/footprint_scale.h"
#include "render/named_values.h"

namespace pm {

extern const NameTable kEstimatorNames;         // pd, radius, knn (PM_ESTIMATOR_*)
extern const NameTable kKernelShapeNames;       // constant, epanechnikov (PM_KERNEL_*)
extern const NameTable kPhotonMapBuilderNames;  // lbvh, vvh
extern const NameTable kPhotonSequenceNames;    // random, halton (PM_PHOTON_SEQUENCE_*)
extern const NameTable kProgressiveNames;       // average, shrink
extern const NameTable kFootprintClipNames;     // on, off

enum PhotonMapBuilder { kPhotonMapLbvh = 0, kPhotonMapVvh = 1 };
// How passes combine (docs/progressive.md): every pass at the same footprint sizes, or footprints
// shrinking from pass to pass (progressive photon mapping, consistent).
enum ProgressiveMode { kProgressiveAverage = 0, kProgressiveShrink = 1 };

// pd's shrinking passes (--progressive shrink, the default under a budget) start from footprints
// half of one pass's area (overlap 50 instead of 100), shrink with alpha 0.2 and weigh photons
// on tilted facets (facet weighting): chosen by measured error on the benchmark scenes, where the
// one-pass defaults shrunk with alpha 2/3 made the bias grow with the passes (docs/accuracy.md,
// "Shrink that converges"); alpha 0.2 rather than 0.3 for the lower error of Sponza, Sibenik and
// Conference together at 16 to 256 passes and in 1 s ("Shrink's alpha by error and by its fall",
// where the closed boxes, which prefer larger footprints, pay for it). Other estimators, and final
// gathering, keep alpha 2/3 (not measured).
constexpr double kShrinkStartOverlap = 50.0;
constexpr float kShrinkAlphaPd = 0.2f;
constexpr float kShrinkAlpha = 2.0f / 3.0f;
// Final gathering reads the map at its gather rays' hits, where each ray's lookup averages the
// map's noise with the other rays' and passes': a small overlap makes a lookup read a few
// photons instead of a few hundred, so the same time holds several times the rays. At 960 x 540
// on the benchmark scenes 3 s of 16-ray passes read 2.20 % relMAE on Sponza at overlap 3 against
// 7.89 % at overlap 200 (the reference's noise taken out), level with overlap 1 and better than 12
// on all three (docs/final-gathering.md, "The map's overlap").
constexpr double kFinalGatherOverlap = 3.0;
// The largest spread of a pixel tile's first shading points, in mean footprint radii, at which
// its lanes walk the photon map together (docs/benchmarks.md, "Pixel tiles walk the photon map
// together").
constexpr float kTileGatherReach = 4.5f;
// Final gathering's photons a pass grow with the frame (PhotonSettings::photons_in_pass): a pass's
// map is traced anew, so the map's noise at the rays' hits falls as 1 / sqrt(passes) where the
// rays', points of scrambled nets, falls faster, and the longer a frame the larger the map's share
// of its error. The count doubles at pass kPhotonGrowthStart and again each time the passes
// quadruple, up to photons_max; by default up to kPhotonGrowthFactor times --photons, at most
// kPhotonGrowthMost (docs/final-gathering.md, "Photons a pass that grow with the frame").
constexpr uint32_t kPhotonGrowthStart = 128;
constexpr uint64_t kPhotonGrowthFactor = 4;
constexpr uint64_t kPhotonGrowthMost = 1048576;

class PhotonSettings final : public MethodSettings {
 public:
  uint64_t photons = 262144;  // emitted per pass, all lights together; 0: no indirect light
  // The most photons a pass grows to (photons_in_pass), in any mode when given; 0: by the mode
  // (photons_max_or_default: growth for final gathering only). Equal to photons: every pass the same.
  uint64_t photons_max = 0;
  int bounces = 2;            // diffuse bounces of indirect light
  float smoothing = 0.0f;     // s of section 4.3, diffusely reflected photons; 0: automatic per pass
  // The automatic s: footprints per surface point (render/footprint_scale.h); 0: by the mode
  // (kAutoSmoothingOverlap; kShrinkStartOverlap for pd's shrinking passes, kFinalGatherOverlap for
  // final gathering's map).
  double overlap = 0;
  float rmax = 0.0f;          // footprint semiaxis clamp (knn: search radius), metres; 0: 10 % of the scene diagonal
  int estimator = PM_ESTIMATOR_PD;
  int kernel_shape = PM_KERNEL_CONSTANT;
  float radius = 0.0f;        // radius estimator, metres; 0: 5 % of the scene diagonal
  int knn_k = 64;             // knn estimator
  int leaf_threshold = 0;     // T; 0: T_auto
  float leaf_c = 0.5f;        // c of T_auto = c * footprint area / scene area, calibrated on the H200 (docs/algorithm.md)
  int sequence = PM_PHOTON_SEQUENCE_RANDOM;  // emission: random, or Halton (the same every frame)
  int builder = kPhotonMapLbvh;  // the device LBVH, or the voxel volume heuristic on the host
                                 // (section 5.1, for the paper's Table 1 comparison)
  // Footprints cut at the walls around their hit (kernels/common/footprint_clip.h): no light leaks
  // through thin walls, at one scene-BVH box query per hit; off: the paper's whole ellipses.
  bool footprint_clip = true;
  // A footprint's area is the part of it that lies on a surface the gather accepts
  // (kernels/common/footprint_coverage.h): no light lost over edges, at a few short rays per hit.
  bool footprint_coverage = true;
  // A photon counted on a facet tilted from its own surface weighs what its beam delivers there,
  // and its footprint's area is the lit surface area under it (kernels/common/gather_reach.h,
  // docs/accuracy.md "Bias at bends"): 1 on, 0 off, kFacetWeightingAuto by the estimator.
  int facet_weighting = kFacetWeightingAuto;
  static constexpr int kFacetWeightingAuto = -1;
  // The pd footprints' normal half-axis over their shorter in-plane semiaxis (docs/algorithm.md).
  float footprint_thickness = PM_FOOTPRINT_NORMAL_RATIO;
  int progressive = kProgressiveAverage;
  // shrink: r_i^2 = r_{i-1}^2 (i + alpha) / (i + 1) (Knaus & Zwicker 2011); 0: by the estimator
  // (kShrinkAlphaPd for pd's shrinking passes, kShrinkAlpha otherwise).
  float alpha = 0.0f;
  // Final gathering (kernels/common/final_gather.h): gather rays per shading point and pass, the
  // map read at their hits and traced with one bounce fewer; 0: the map read at the shading point.
  uint32_t final_gather = 0;
  // The gather's pixel tiles walk the photon map together (kernels/common/gather_tiles.h) when
  // their first shading points lie within this many of the pass's mean footprint radii (the box
  // diagonal); 0: every point walks alone; kTileGatherAuto: kTileGatherReach on devices whose
  // lanes run in lockstep (GPUs), 0 elsewhere. The same image either way.
  float tile_gather = kTileGatherAuto;
  static constexpr float kTileGatherAuto = -1.0f;

  const char* method_name() const override { return "photon"; }
  void validate() const override;
  std::unique_ptr<IndirectMethod> create(const MethodContext& context) const override;

  // Hit records reserved per photon. A photon records a hit after each of its bounces
  // (kernels/common/photon_trace.h). In a scene without mirror reflectance every bounce is
  // diffuse or glossy, so `bounces` records hold them all; mirrors add specular bounces on caustic
  // paths: two more records (a path's hits beyond them are not recorded).
  uint32_t hit_slots_per_photon(bool scene_has_mirrors = true) const {
    return uint32_t(bounces + (scene_has_mirrors ? 2 : 0));
  }
  // Whether these are pd's shrinking passes read at the shading point, whose defaults differ
  // (overlap, alpha, facet weighting; docs/accuracy.md "Shrink that converges").
  bool shrinking_pd() const {
    return progressive == kProgressiveShrink && estimator == PM_ESTIMATOR_PD && final_gather == 0;
  }
  // alpha and overlap as given, or their defaults for this mode when 0 (auto).
  float alpha_or_default() const { return alpha > 0 ? alpha : shrinking_pd() ? kShrinkAlphaPd : kShrinkAlpha; }
  double overlap_or_default() const {
    if (overlap > 0) return overlap;
    if (shrinking_pd()) return kShrinkStartOverlap;
    return final_gather > 0 ? kFinalGatherOverlap : kAutoSmoothingOverlap;
  }
  // photons_max as given, or its default: for final gathering with random photons
  // kPhotonGrowthFactor times photons up to kPhotonGrowthMost (never below photons); photons
  // otherwise (Halton photons number a light's photons by pass, the same count every pass).
  uint64_t photons_max_or_default() const;
  // Photons emitted in pass `pass` (0, 1, ...): photons, doubled at pass kPhotonGrowthStart and
  // at each fourfold pass count after it, at most photons_max_or_default().
  uint64_t photons_in_pass(uint32_t pass) const;
  // Photons emitted in the passes before `pass`: the first photon's index of that pass.
  uint64_t photons_before_pass(uint32_t pass) const;
  // The defaults that depend on the scene (rmax, radius) or on the mode (overlap, alpha, facet
  // weighting) filled in.
  PhotonSettings resolved(const SceneMeasures& measures) const;
  // One line: every setting, as resolved.
  std::string describe() const;
  // Footprint semiaxis (and gather radius) factor of pass `pass`: 1 when averaging; when
  // shrinking sqrt(prod_{j=1..pass} (j + alpha) / (j + 1)), so areas shrink like r^2.
  double footprint_scale(uint32_t pass) const;
};

}  // namespace pm
