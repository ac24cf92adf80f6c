// pmrender's entry point: subcommand dispatch and the exit-code contract
// (0 success, 1 render or device failure, 2 bad usage or bad input).
#include <cstdio>
#include <iostream>
#include <new>

#include "cli/commands.h"
#include "cli/parse_errors.h"
#include "render/errors.h"
#include "render/program_cache.h"

int main(int argc, char** argv) {
  CLI::App app{"pmrender: global illumination by GPU photon mapping (Fabianowski & Dingliana 2009)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("pmrender ") + PMRENDER_VERSION);
  pm::cli::Run render = pm::cli::add_render_command(app);
  pm::cli::Run devices = pm::cli::add_devices_command(app);
  pm::cli::Run compare = pm::cli::add_compare_command(app);
  pm::cli::Run bench = pm::cli::add_bench_command(app);
  pm::cli::Run frames = pm::cli::add_frames_command(app);
  pm::cli::Run farm = pm::cli::add_farm_command(app);
  pm::cli::Run export_scene = pm::cli::add_export_scene_command(app);
  pm::cli::Run tradeoff = pm::cli::add_tradeoff_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return pm::cli::report_parse_error(app, e, argc, argv);
  }

  try {
    // The environment is input too: a bad switch is refused before a device or a scene is opened.
    pm::program_cache_settings_from_environment();
    if (app.got_subcommand("render")) return render();
    if (app.got_subcommand("devices")) return devices();
    if (app.got_subcommand("compare")) return compare();
    if (app.got_subcommand("bench")) return bench();
    if (app.got_subcommand("frames")) return frames();
    if (app.got_subcommand("farm")) return farm();
    if (app.got_subcommand("export-scene")) return export_scene();
    if (app.got_subcommand("tradeoff")) return tradeoff();
  } catch (const pm::SettingError& e) {
    // The library names the setting; on the command line it is the option of the same name.
    std::cerr << "pmrender: --" << e.what() << "\n";
    return 2;
  } catch (const pm::InputError& e) {
    std::cerr << "pmrender: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "pmrender: out of host memory; lower --resolution or --photons (pmrender render -v prints what a run used)\n";
    return 1;
  } catch (const pm::DeviceError& e) {
    std::cerr << "pmrender: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "pmrender: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
