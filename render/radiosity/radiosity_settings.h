// Settings of the vertex link radiosity method (the 2008 explicit-visibility link radiosity
// paper; docs/radiosity.md), their name tables, validation and scene-dependent defaults. Each
// setting's name in messages is its command-line option's without the dashes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "render/indirect_method.h"
#include "render/kernel_abi.h"
#include "render/named_values.h"

namespace pm {

extern const NameTable kRadiositySidesNames;         // one, two
extern const NameTable kRadiosityLightSamplesNames;  // vertex, one-ring (PM_RADIOSITY_LIGHT_*)
extern const NameTable kRadiosityLinkOriginsNames;   // vertex, one-ring (PM_RADIOSITY_ORIGINS_*)

class RadiositySettings final : public MethodSettings {
 public:
  // nC: cosine-weighted hemisphere directions per element (section 3.2); 0: automatic,
  // kDirections, or kFinalGatherDirections under final gathering, whose rays read the solution
  // only beyond their hits (its bias there was the same at 64 as at 256 on the benchmark scenes,
  // its solve 1.3-1.5 times faster; docs/final-gathering.md).
  uint32_t directions = 0;
  static constexpr uint32_t kDirections = 256;
  static constexpr uint32_t kFinalGatherDirections = 64;
  int bounces = 2;            // nB: gathering iterations, one bounce each (eq. 3, 4), as --bounces
  float max_edge = 0.0f;      // refinement: longest triangle edge, metres; 0: the scene diagonal / 50
  float feature_angle = 40.0f;  // alpha_f, degrees: normals split and smoothing stops beyond it (eq. 6)
  int smooth_passes = 1;      // one-ring smoothing passes (eq. 5); 0: none
  int sides = 2;              // 2: an element on each side of every surface; 1: the winding's side only
  int light_samples = PM_RADIOSITY_LIGHT_ONE_RING;  // light links at the vertex, or oversampled (1:4)
  int link_origins = PM_RADIOSITY_ORIGINS_ONE_RING;  // link rays from the vertex, or over its one-ring
  uint32_t link_batch = 0;    // elements per link batch; 0: as many as 256 MiB of scratch holds
  // A link ray that meets a back face nearer than this many max_edge started inside geometry and
  // is left out of its vertex's value (radiosity_links.h); 0: every origin counts. One max edge:
  // measured across the benchmark scenes (docs/accuracy.md, "Hidden origins").
  float hidden_origins = 1.0f;
  // Final gathering (kernels/common/final_gather.h): gather rays per shading point and pass, the
  // solution (solved with one bounce fewer) read at their hits; 0: the solution read at the
  // shading point, one pass. Passes add rays: the image converges to the solution's light after
  // the first bounce, the first bounce itself exact.
  uint32_t final_gather = 0;

  const char* method_name() const override { return "radiosity"; }
  void validate() const override;
  std::unique_ptr<IndirectMethod> create(const MethodContext& context) const override;
  // The refined mesh, its elements and texture tints (vertex_link_radiosity.cpp), begun on a
  // thread of its own; none where the solution has no bounces or the mesh would be refused.
  std::shared_ptr<const HostWorkAhead> begin_host_work(const Scene& scene, const SceneMeasures& measures) const override;

  // The defaults that depend on the scene (max_edge) or on other settings (directions) filled in.
  RadiositySettings resolved(const SceneMeasures& measures) const;
  // Elements per link batch for `elements` elements: link_batch, or what the scratch budget holds.
  uint32_t batch_elements(uint64_t elements) const;
  uint32_t resolved_directions() const {
    return directions > 0 ? directions : final_gather > 0 ? kFinalGatherDirections : kDirections;
  }
  // Gathering bounces of the solution: bounces, or one fewer when final gathering reads it a
  // bounce away from the shading point.
  int solution_bounces() const { return final_gather > 0 ? bounces - 1 : bounces; }
  // Whether the two (as resolved) refine the scene into the same elements: the refinement
  // (max_edge) and the elements' settings (feature_angle, sides) agree.
  bool same_mesh_as(const RadiositySettings& other) const;
  // Whether the two (as resolved) refine the scene into the same elements and trace the same
  // links: the settings of the mesh and of the link rays agree.
  bool same_links_as(const RadiositySettings& other) const;
  // One line: every setting, as resolved.
  std::string describe() const;
};

// Scratch bytes of the link build per element of a batch: 3 nC (target, weight) entries.
constexpr uint64_t radiosity_scratch_bytes_per_element(uint32_t directions) { return uint64_t(directions) * 3 * 8; }

}  // namespace pm
