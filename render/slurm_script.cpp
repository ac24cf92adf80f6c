// Slurm job-array batch scripts for frame sequences: #SBATCH header, one frame chunk per array
// task, per-line timestamps for per-frame timings, render with --resume and
// --wait-for-claimed-frames, then frames check.
#include "render/slurm_script.h"

#include <sstream>

#include "render/errors.h"

namespace pm {

namespace {

void refuse_control_characters(const std::string& what, const std::string& value) {
  for (char c : value)
    if (c == '\n' || c == '\r' || c == '\0')
      throw InputError(what + ": a line break or NUL cannot go into a batch script: '" + value + "'");
}

// An #SBATCH value is read by sbatch's own word splitter, which knows double quotes and
// backslashes; the log pattern's folder is the only value of ours that may contain spaces.
std::string sbatch_quote(const std::string& value) {
  if (value.find_first_of(" \t\"\\") == std::string::npos) return value;
  return "\"" + value + "\"";
}

// sbatch expands %A, %a, %x, ... in file names; a literal % in the folder is %%.
std::string escape_percent(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

}  // namespace

std::string shell_quote(const std::string& word) {
  bool plain = !word.empty();
  for (char c : word) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string("-_./=:,+@%").find(c) != std::string::npos;
    plain = plain && safe;
  }
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string slurm_batch_script(const SlurmArrayJob& job) {
  refuse_control_characters("job name", job.job_name);
  refuse_control_characters("pmrender binary", job.pmrender);
  refuse_control_characters("working folder", job.workdir);
  refuse_control_characters("-o", job.output_pattern);
  refuse_control_characters("--logs", job.log_folder);
  refuse_control_characters("--partition", job.partition);
  refuse_control_characters("--time-limit", job.time_limit);
  refuse_control_characters("--account", job.account);
  refuse_control_characters("description", job.description);
  for (const std::string& a : job.render_args) refuse_control_characters("render option", a);
  for (const std::string& o : job.sbatch_options) refuse_control_characters("--sbatch", o);
  for (const std::string& c : job.chunks) refuse_control_characters("--frames", c);
  if (job.log_folder.find_first_of("\\\"") != std::string::npos)
    throw InputError("--logs: '" + job.log_folder + "': a folder with '\\' or '\"' cannot be named in #SBATCH --output");
  if (job.chunks.empty()) throw InputError("--frames: no frames to render");

  std::ostringstream s;
  s << "#!/bin/bash\n";
  if (!job.description.empty()) s << "# " << job.description << "\n";
  s << "#SBATCH --job-name=" << sbatch_quote(job.job_name) << "\n";
  s << "#SBATCH --array=0-" << job.chunks.size() - 1;
  if (job.max_running > 0) s << "%" << job.max_running;
  s << "\n";
  // Preempted or failed nodes put the task back in the queue; the requeued task appends to its log.
  s << "#SBATCH --requeue\n";
  s << "#SBATCH --open-mode=append\n";
  s << "#SBATCH --output=" << sbatch_quote(escape_percent(job.log_folder) + "/%x_%A_%a.log") << "\n";
  s << "#SBATCH --ntasks=1\n";
  if (job.gpu) s << "#SBATCH --gres=gpu:1\n";
  if (!job.partition.empty()) s << "#SBATCH --partition=" << sbatch_quote(job.partition) << "\n";
  if (!job.time_limit.empty()) s << "#SBATCH --time=" << sbatch_quote(job.time_limit) << "\n";
  if (!job.account.empty()) s << "#SBATCH --account=" << sbatch_quote(job.account) << "\n";
  for (const std::string& option : job.sbatch_options) s << "#SBATCH " << option << "\n";
  s << "set -euo pipefail\n\n";

  s << "pmrender=" << shell_quote(job.pmrender) << "\n";
  s << "pattern=" << shell_quote(job.output_pattern) << "\n";
  s << "# The frames of each array task.\n";
  s << "chunks=(\n";
  for (const std::string& chunk : job.chunks) s << "  " << shell_quote(chunk) << "\n";
  s << ")\n";
  s << "frames=${chunks[$SLURM_ARRAY_TASK_ID]}\n\n";

  s << "# Each line of output with the wall-clock time: start-up, then one 'wrote' line per frame.\n";
  s << "stamp() { while IFS= read -r line; do printf '%s %s\\n' \"$(date '+%F %T.%3N')\" \"$line\"; done; }\n\n";
  s << "cd " << shell_quote(job.workdir) << "\n";
  s << "echo \"task ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}, attempt $((${SLURM_RESTART_COUNT:-0} + 1)), "
       "on $(hostname): frames $frames\" | stamp\n";
  s << "status=0\n";
  s << "\"$pmrender\" render";
  for (const std::string& a : job.render_args) s << " " << shell_quote(a);
  // Waiting: an earlier attempt of this task that still runs (or a second submission) keeps the
  // frames it has claimed, and this attempt ends once they are complete.
  s << " --frames \"$frames\" -o \"$pattern\" --resume --wait-for-claimed-frames 2>&1 | stamp || status=$?\n";
  s << "# The task succeeds only when every one of its frames is complete.\n";
  s << "\"$pmrender\" frames check -o \"$pattern\" --frames \"$frames\"";
  if (!job.check_resolution.empty()) s << " --resolution " << shell_quote(job.check_resolution);
  s << " 2>&1 | stamp || status=$?\n";
  s << "echo \"task ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID} ended with status $status after $SECONDS s\" | stamp\n";
  s << "exit \"$status\"\n";
  return s.str();
}

}  // namespace pm
