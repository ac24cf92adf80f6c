// The subcommands of the pmrender command line. Each registers its options on the CLI11 app and
// returns the callback that runs it; main() maps exceptions to exit codes.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace pm::cli {

using Run = std::function<int()>;

Run add_render_command(CLI::App& app);
Run add_devices_command(CLI::App& app);
Run add_compare_command(CLI::App& app);
Run add_bench_command(CLI::App& app);
Run add_frames_command(CLI::App& app);
Run add_farm_command(CLI::App& app);
Run add_export_scene_command(CLI::App& app);
Run add_tradeoff_command(CLI::App& app);

// "640x480" -> width, height; throws InputError naming the option on anything else.
void parse_resolution(const std::string& text, int* width, int* height);

// --frames SPEC within [first, last] (scene_io/frame_spec.h), its problems named as the option's.
std::vector<int> parse_frames_option(const std::string& spec, int first, int last);

}  // namespace pm::cli
