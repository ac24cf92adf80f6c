// The photon-mapping extras of `pmrender bench`, for the paper's tables: --leaf-sweep (Table 1,
// frame rate per photon-map leaf threshold T and T_auto) and --radius-histogram (Table 3,
// footprint radii). Both need --method photon; everything else in bench is method-independent.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/bench_measure.h"
#include "render/renderer.h"

namespace pm::cli {

// "1,2,4" -> {1, 2, 4}; InputError naming --leaf-sweep otherwise.
std::vector<int> parse_leaf_sweep(const std::string& text);

// Throws InputError when the extras cannot run with these settings.
void check_photon_extras(const RenderSettings& settings, bool leaf_sweep, bool radius_histogram);

// Prints the footprint radius histogram of the photon map on the device (the last pass of the
// last frame) and returns it as JSON.
nlohmann::ordered_json print_radius_histogram(Device& device, const Renderer& renderer, int frame);

// Measures a fresh Renderer per fixed T in thresholds and one with T_auto, prints the table and
// returns it as JSON.
nlohmann::ordered_json run_leaf_sweep(Device& device, const Scene& scene, const RenderSettings& settings,
                                      const FramePlan& plan, std::vector<int> thresholds);

}  // namespace pm::cli
