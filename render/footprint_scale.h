// Automatic smoothing (`--smoothing auto`, the default): the smoothing factor s of the diffuse
// photon footprints (paper section 4.3) chosen per batch so that, at any scene size and photon
// count, the batch's footprints cover the scene's surface kAutoSmoothingOverlap times on average.
//
// The paper's rule |a_x| = s Delta |dp_x|^(1/4) (kernels/common/footprint.h) is not scale
// invariant: scaling a scene by k scales its footprints by k^(1/4), so one fixed s gives
// footprints too small to reach anything in a large scene and blurry ones in a small one. With
// A1 the batch's total diffuse footprint area at s = 1 (unclamped; kernels/common/
// footprint_scale.h) and A the scene's surface area,
//     s = sqrt(overlap * A / A1),
// so the total area at s is overlap * A: s grows as k^(3/4) with the scene, radii as k; and since
// A1 does not depend on the photon count (n hits of area ~ Delta^2 = 4 pi / n each), radii still
// shrink as Delta ~ 1/sqrt(n), as in the paper. The relative sizes of the footprints (the
// L^(1/4) compression) are the paper's. The choice depends on the batch's photons only (a fixed
// reduction order), so a frame's result does not depend on how frames are chunked.
#pragma once

#include <cstdint>

#include "render/device.h"

namespace pm {

// The overlap of the automatic smoothing, chosen by measured error across the benchmark scenes
// (docs/accuracy.md, "The one-pass footprint size by its bias"): at the default 262144 photons, one
// pass, 100 keeps the expected indirect bias within 1.1 % on Sponza, Sibenik, Conference and both
// Cornell boxes, at 96 x 54 untextured and at 960 x 540 textured (200: +1.74 % on textured
// Sibenik), at an indirect relMAE within 5 % of 200's geometric mean over the five (better in the
// three benchmark scenes, worse in the boxes). 800, the value calibrated on the built-in Cornell box
// alone, blurs the real scenes (relMAE 23-28 % against 15-20 % in them at 96 x 54).
constexpr double kAutoSmoothingOverlap = 100.0;

// s = sqrt(overlap * scene_area / area_at_s1); 1 when the batch has no diffuse footprint area
// (no diffuse hits: s then sizes nothing).
float auto_smoothing(double area_at_s1, double scene_area, double overlap = kAutoSmoothingOverlap);

// The batch's area at s = 1 from the photon_footprint_scale tiles' sums, added in tile order.
double footprint_scale_tile_sum(const float* tile_sums, uint32_t tiles);

// Runs the photon_footprint_scale reduction over the batch's hit records (params as for the
// footprint stage, partials bound to map_partials, which holds a float per tile) and returns the
// batch's automatic s. *area_at_s1 (if not null) gets A1.
float batch_auto_smoothing(Device& device, const DeviceBuffer& partials, const LaunchParams& params,
                           double scene_area, double overlap = kAutoSmoothingOverlap, double* area_at_s1 = nullptr);

}  // namespace pm
