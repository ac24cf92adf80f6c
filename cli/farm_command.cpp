// `pmrender farm slurm [SCENE] --chunk N [--frames SPEC] -o PATTERN [render options] [--submit]`:
// writes a Slurm job-array batch script (render/slurm_script.h) that renders the frames in chunks
// of N, one array task per chunk, and with --submit hands it to sbatch. The render options are not
// listed here: they pass through verbatim and are checked by parsing them with the real `render`
// subcommand, so a bad one is exit 2 before anything is written or submitted (docs/farm.md).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "scene_io/frame_spec.h"
#include "render/scene_frame.h"
#include "cli/commands.h"
#include "render/errors.h"
#include "render/output_pattern.h"
#include "render/slurm_script.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"

extern char** environ;

namespace pm::cli {

namespace {

namespace fs = std::filesystem;

// Render options the farm itself owns: it gives every task its own --frames, an absolute -o,
// --resume and --wait-for-claimed-frames. Any other name the two commands share would be ambiguous.
const std::vector<std::string> kOwnedRenderOptions = {"--frames", "--output", "--resume", "--frame",
                                                      "--wait-for-claimed-frames"};

struct FarmSlurmOptions {
  std::string output, frames;
  int chunk = 0;
  std::string partition, time_limit, account, job_name, logs, script;
  std::vector<std::string> sbatch;
  int max_running = 0;
  bool submit = false;
};

// The render subcommand, freshly registered on its own app and parsed with these arguments (what
// `pmrender render ARGS` would see). CLI11 errors become InputError naming the render options.
// The command's run function is kept: it owns the options CLI11 writes the parsed values into.
class RenderArguments {
 public:
  explicit RenderArguments(const std::vector<std::string>& args) : run_(add_render_command(holder_)) {
    std::vector<std::string> reversed = {"render"};
    reversed.insert(reversed.end(), args.begin(), args.end());
    std::reverse(reversed.begin(), reversed.end());  // CLI11 takes the arguments last first
    try {
      holder_.parse(reversed);
    } catch (const CLI::ParseError& e) {
      throw InputError(std::string("render options: ") + e.what());
    }
  }
  CLI::App* render() { return holder_.get_subcommand("render"); }

 private:
  CLI::App holder_;
  Run run_;
};

std::string option_text(CLI::App* render, const std::string& name) {
  CLI::Option* option = render->get_option_no_throw(name);
  return option && option->count() > 0 ? option->as<std::string>() : std::string();
}

// Which of the pass-through arguments the render parser takes as the scene: the one whose
// replacement by a marker makes the marker the scene (an option's value of the same spelling
// stays an option value). -1 when no scene is given.
int scene_argument_index(const std::vector<std::string>& args, const std::string& scene) {
  const std::string marker = "\x01pmrender-scene-marker";
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] != scene) continue;
    std::vector<std::string> trial = args;
    trial[i] = marker;
    try {
      RenderArguments parsed(trial);
      if (option_text(parsed.render(), "scene") == marker) return int(i);
    } catch (const InputError&) {
      // the marker was an option's value (--seed, say) that does not parse: not the scene
    }
  }
  return -1;
}

// Two commands that both declared a name would silently swallow a render option.
void require_no_shared_option_names(CLI::App* farm, CLI::App* render) {
  for (const CLI::Option* option : farm->get_options()) {
    if (option == farm->get_help_ptr()) continue;
    for (const std::string& name : option->get_lnames()) {
      const std::string spelled = "--" + name;
      if (std::find(kOwnedRenderOptions.begin(), kOwnedRenderOptions.end(), spelled) != kOwnedRenderOptions.end())
        continue;
      if (render->get_option_no_throw(spelled))
        throw std::logic_error("option " + spelled + " is declared by both `farm slurm` and `render`");
    }
  }
}

std::string job_name_for(const std::string& scene_name) {
  std::string name = "pmrender-" + scene_name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return name;
}

void require_word(const std::string& option, const std::string& value) {
  if (value.find_first_of(" \t\"'\\") != std::string::npos)
    throw InputError(option + ": '" + value + "' must be one word without quotes");
}

// Slurm's time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S, or UNLIMITED/INFINITE.
void require_time_limit(const std::string& value) {
  static const std::regex format(R"(\d+(:\d+){0,2}|\d+-\d+(:\d+){0,2}|UNLIMITED|INFINITE)");
  if (!value.empty() && !std::regex_match(value, format))
    throw InputError("--time-limit: '" + value + "' is not a Slurm time (minutes, H:M:S or D-H:M:S)");
}

// Runs `sbatch --parsable [FILE]` (the script on standard input when FILE is empty) and returns
// the job id it prints. sbatch's own errors go straight to our standard error.
std::string submit_to_sbatch(const std::string& script, const std::string& file) {
  int to_child[2], from_child[2];
  if (::pipe(to_child) != 0 || ::pipe(from_child) != 0) throw DeviceError("sbatch: cannot create a pipe");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, to_child[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, from_child[1], STDOUT_FILENO);
  for (int fd : {to_child[0], to_child[1], from_child[0], from_child[1]}) posix_spawn_file_actions_addclose(&actions, fd);
  std::vector<std::string> words = {"sbatch", "--parsable"};
  if (!file.empty()) words.push_back(file);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, "sbatch", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(to_child[0]);
  ::close(from_child[1]);
  if (spawn_error != 0) {
    ::close(to_child[1]);
    ::close(from_child[0]);
    throw DeviceError("sbatch: cannot run it (" + std::string(std::strerror(spawn_error)) + "); is Slurm's client on PATH?");
  }
  // sbatch reads the whole script before it prints anything, so writing first cannot deadlock;
  // if it exits early the write fails with EPIPE instead of killing us.
  auto previous = std::signal(SIGPIPE, SIG_IGN);
  const std::string input = file.empty() ? script : std::string();
  for (size_t done = 0; done < input.size();) {
    const ssize_t n = ::write(to_child[1], input.data() + done, input.size() - done);
    if (n <= 0) break;
    done += size_t(n);
  }
  ::close(to_child[1]);
  std::signal(SIGPIPE, previous);
  std::string output;
  char buffer[256];
  for (ssize_t n; (n = ::read(from_child[0], buffer, sizeof(buffer))) > 0;) output.append(buffer, size_t(n));
  ::close(from_child[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw DeviceError("sbatch failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                      "); nothing was submitted");
  const std::string id = output.substr(0, output.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw DeviceError("sbatch printed no job id: '" + output + "'");
  return id;
}

// Everything the script needs, every input checked (InputError otherwise); writes nothing.
SlurmArrayJob plan_slurm_job(const FarmSlurmOptions& o, CLI::App* farm) {
  // 1. The pass-through options, parsed as `render` would parse them.
  const std::vector<std::string> passed = farm->remaining();
  RenderArguments parsed(passed);
  CLI::App* render = parsed.render();
  require_no_shared_option_names(farm, render);
  for (const std::string& owned : kOwnedRenderOptions)
    if (render->get_option(owned)->count() > 0)
      throw InputError(owned + (owned == "--resume"                     ? ": farm tasks always resume; leave it out"
                                : owned == "--wait-for-claimed-frames" ? ": farm tasks always wait; leave it out"
                                                                       : ": give the frames with --frames and the output with -o"));

  // 2. The scene (absolute in the script), its frames, and the frame size every file must have.
  std::vector<std::string> render_args = passed;
  const std::string scene_path = option_text(render, "scene");
  if (!scene_path.empty()) {
    const int index = scene_argument_index(passed, scene_path);
    if (index < 0) throw std::logic_error("the scene '" + scene_path + "' is not among the render options");
    render_args[size_t(index)] = fs::absolute(scene_path).string();
  }
  const Scene scene = scene_path.empty() ? builtin_cornell_box() : load_scene_file(scene_path);
  const SceneAnimation& a = scene.animation;
  std::vector<int> frames;
  if (!o.frames.empty()) {
    frames = parse_frames_option(o.frames, a.enabled ? a.first_frame : 0, a.enabled ? a.last_frame : 999999999);
  } else {
    for (int f = a.first_frame; f <= (a.enabled ? a.last_frame : 0); ++f) frames.push_back(f);
  }
  if (frames.size() > 1 && !pattern_has_frame_field(o.output))
    throw InputError("-o: '" + o.output + "' has no # for the frame number, but " + std::to_string(frames.size()) +
                     " frames are selected");
  for (int f : frames) {
    const std::string problem = camera_problem(camera_at_frame(scene, f));
    if (!problem.empty()) throw InputError(scene.source + ": camera at frame " + std::to_string(f) + ": " + problem);
  }
  int width = scene.camera.width, height = scene.camera.height;
  const std::string resolution = option_text(render, "--resolution");
  if (!resolution.empty()) parse_resolution(resolution, &width, &height);

  // 3. The farm's own options.
  require_word("--partition", o.partition);
  require_word("--account", o.account);
  require_word("--job-name", o.job_name);
  require_time_limit(o.time_limit);
  for (const std::string& option : o.sbatch)
    if (option.size() < 2 || option[0] != '-') throw InputError("--sbatch: '" + option + "' is not an sbatch option");

  SlurmArrayJob job;
  job.job_name = o.job_name.empty() ? job_name_for(scene.name) : o.job_name;
  std::error_code ec;
  const fs::path binary = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw DeviceError("cannot find the pmrender binary's path: " + ec.message());
  job.pmrender = binary.string();
  job.workdir = fs::current_path().string();
  job.render_args = render_args;
  job.output_pattern = fs::absolute(o.output).lexically_normal().string();
  for (size_t first = 0; first < frames.size(); first += size_t(o.chunk)) {
    const size_t end = std::min(frames.size(), first + size_t(o.chunk));
    job.chunks.push_back(format_frame_spec(std::vector<int>(frames.begin() + long(first), frames.begin() + long(end))));
  }
  job.check_resolution = std::to_string(width) + "x" + std::to_string(height);
  const fs::path logs = o.logs.empty() ? fs::path(job.output_pattern).parent_path() / "logs" : fs::absolute(o.logs);
  job.log_folder = logs.lexically_normal().string();
  while (job.log_folder.size() > 1 && job.log_folder.back() == '/') job.log_folder.pop_back();
  job.gpu = option_text(render, "--backend") == "cuda";
  job.partition = o.partition;
  job.time_limit = o.time_limit;
  job.account = o.account;
  job.sbatch_options = o.sbatch;
  job.max_running = o.max_running;
  job.description = "pmrender " PMRENDER_VERSION " farm slurm: " + std::to_string(frames.size()) + " frame" +
                    (frames.size() == 1 ? "" : "s") + " of " +
                    (scene_path.empty() ? scene.source : fs::absolute(scene_path).string()) + " in " + std::to_string(job.chunks.size()) +
                    " task" + (job.chunks.size() == 1 ? "" : "s") + " of up to " + std::to_string(o.chunk) + " frame" +
                    (o.chunk == 1 ? "" : "s");
  return job;
}

int run_farm_slurm(const FarmSlurmOptions& o, CLI::App* farm) {
  const SlurmArrayJob job = plan_slurm_job(o, farm);
  const std::string script = slurm_batch_script(job);

  // Input is valid: write, then submit. sbatch does not create the log folder; a task whose log
  // cannot be opened fails without a word.
  std::error_code ec;
  fs::create_directories(job.log_folder, ec);
  if (ec) throw DeviceError("--logs: cannot create '" + job.log_folder + "': " + ec.message());
  if (!o.script.empty()) {
    std::ofstream out(o.script, std::ios::binary | std::ios::trunc);
    out << script;
    out.close();
    if (!out) throw DeviceError("--script: cannot write '" + o.script + "'");
    std::printf("wrote %s (%zu array tasks)\n", o.script.c_str(), job.chunks.size());
  } else {
    std::fwrite(script.data(), 1, script.size(), stdout);
  }
  std::fflush(stdout);
  if (o.submit) {
    const std::string id = submit_to_sbatch(script, o.script);
    std::printf("submitted job %s (%zu array tasks, logs in %s)\n", id.c_str(), job.chunks.size(), job.log_folder.c_str());
  }
  return 0;
}

}  // namespace

Run add_farm_command(CLI::App& app) {
  auto options = std::make_shared<FarmSlurmOptions>();
  CLI::App* farm = app.add_subcommand("farm", "Render a sequence on a cluster's scheduler");
  farm->require_subcommand(1);
  CLI::App* slurm = farm->add_subcommand(
      "slurm", "Write (and with --submit submit) a Slurm job-array script: one task per chunk of frames, "
               "resumable. Other options are render options, passed through (see `pmrender render --help`)");
  slurm->allow_extras();
  slurm->add_option("--chunk", options->chunk, "Frames per array task")->required()->check(CLI::PositiveNumber);
  slurm->add_option("--frames", options->frames, "Frames to render, e.g. 0-999 (default: the scene's whole sequence)");
  slurm->add_option("-o,--output", options->output, "Output pattern; runs of # are the zero-padded frame number")
      ->required();
  slurm->add_option("--partition", options->partition, "Slurm partition (default: the cluster's)");
  slurm->add_option("--time-limit", options->time_limit, "Time limit per task, as sbatch --time (e.g. 2:00:00)");
  slurm->add_option("--account", options->account, "Slurm account to charge");
  slurm->add_option("--job-name", options->job_name, "Job name (default: pmrender-<scene name>)");
  slurm->add_option("--sbatch", options->sbatch, "A further sbatch option for the script, e.g. --sbatch=--mem=8G "
                                                 "(repeatable)");
  slurm->add_option("--max-running", options->max_running, "At most this many tasks at once (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  slurm->add_option("--logs", options->logs, "Folder of the task logs (default: logs/ beside the output)");
  slurm->add_option("--script", options->script, "Write the script to this file instead of standard output");
  slurm->add_flag("--submit", options->submit, "Submit the script with sbatch and print the job id");
  return [options, slurm] { return run_farm_slurm(*options, slurm); };
}

}  // namespace pm::cli
