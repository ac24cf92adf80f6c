// The text of a Slurm job-array batch script that renders a sequence in chunks of frames: one
// array task per chunk, each running `pmrender render ... --frames CHUNK --resume
// --wait-for-claimed-frames` and then
// `pmrender frames check` over the same frames (docs/farm.md). Pure string work: the command line
// (cli/farm_command.cpp) validates the job and submits the script.
#pragma once

#include <string>
#include <vector>

namespace pm {

struct SlurmArrayJob {
  std::string job_name;
  std::string pmrender;                  // absolute path of the pmrender binary on the nodes
  std::string workdir;                   // absolute; relative paths among render_args resolve here
  std::vector<std::string> render_args;  // after `render`: the scene and the options, except
                                         // --frames, -o, --resume and --wait-for-claimed-frames,
                                         // which the script adds
  std::string output_pattern;            // absolute, with # for the frame number
  std::vector<std::string> chunks;       // each array task's frames, as a --frames specification
  std::string check_resolution;          // WIDTHxHEIGHT every frame must have; empty: any
  std::string log_folder;                // absolute; one log per task, appended to on requeue
  bool gpu = false;                      // --gres=gpu:1 (the CUDA backend)
  std::string partition, time_limit, account;  // empty: the cluster's defaults
  std::vector<std::string> sbatch_options;     // further #SBATCH lines, verbatim
  int max_running = 0;                   // at most this many tasks at once; 0: no limit
  std::string description;               // a comment line at the top
};

// The word as POSIX sh reads it back unchanged: kept as it is when it has only characters no shell
// treats specially, otherwise in single quotes (a ' inside as '\''). Newlines survive, but
// slurm_batch_script refuses them: keep them out of scripts altogether.
std::string shell_quote(const std::string& word);

// The whole script, ending in a newline. Throws InputError when a value cannot be written into a
// script safely (a newline or NUL anywhere, a log folder with '\' or '"'), naming the value.
std::string slurm_batch_script(const SlurmArrayJob& job);

}  // namespace pm
