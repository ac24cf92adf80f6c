// Tests of render/slurm_script: shell quoting read back by a real shell, the #SBATCH header
// (array size, GPU request, pass-through options, log path with spaces and %), and the refusal of
// values that cannot go into a script.
#include "render/slurm_script.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "render/errors.h"

namespace pm {
namespace {

// What `sh` prints for `printf '%s' WORD` with the word written as shell_quote writes it.
std::string read_back_by_sh(const std::string& word) {
  const std::string command = "printf '%s' " + shell_quote(word);
  const std::string invocation = "sh -c " + shell_quote(command);
  std::FILE* pipe = ::popen(invocation.c_str(), "r");
  std::string out;
  char buffer[256];
  for (size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) out.append(buffer, n);
  ::pclose(pipe);
  return out;
}

SlurmArrayJob sample_job() {
  SlurmArrayJob job;
  job.job_name = "pmrender-room";
  job.pmrender = "/opt/pm/bin/pmrender";
  job.workdir = "/home/a/shot 1";
  job.render_args = {"/home/a/shot 1/room.json", "--photons", "200000", "--seed", "7"};
  job.output_pattern = "/home/a/shot 1/out/f_####.exr";
  job.chunks = {"0-9", "10-19", "20-24"};
  job.check_resolution = "640x480";
  job.log_folder = "/home/a/shot 1/out/logs";
  return job;
}

TEST(SlurmScript, QuotedWordsReadBackUnchanged) {
  for (const std::string word : {"plain", "/a/b-c_d.e", "with space", "it's", "''", "a\"b", "$HOME", "`id`", "a\\b",
                                 "#comment", "f_####.exr", "*", "semi;colon", "tab\there", "", "--opt=x y", "!x"})
    EXPECT_EQ(read_back_by_sh(word), word) << shell_quote(word);
  EXPECT_EQ(shell_quote("plain-word_1.exr"), "plain-word_1.exr");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quote(""), "''");
}

TEST(SlurmScript, HeaderHasTheArrayRequeueAndLogs) {
  const std::string script = slurm_batch_script(sample_job());
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --requeue\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --open-mode=append\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=\"/home/a/shot 1/out/logs/%x_%A_%a.log\"\n"), std::string::npos) << script;
  EXPECT_EQ(script.find("--gres"), std::string::npos);
  EXPECT_EQ(script.find("--partition"), std::string::npos);
  EXPECT_NE(script.find("set -euo pipefail\n"), std::string::npos);
  EXPECT_NE(script.find("frames=${chunks[$SLURM_ARRAY_TASK_ID]}"), std::string::npos);
  EXPECT_NE(script.find("\"$pmrender\" render '/home/a/shot 1/room.json' --photons 200000 --seed 7 --frames \"$frames\" "
                        "-o \"$pattern\" --resume --wait-for-claimed-frames 2>&1"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("\"$pmrender\" frames check -o \"$pattern\" --frames \"$frames\" --resolution 640x480"),
            std::string::npos);
  // The check comes after the render: the task's exit status is the check's when the render ran.
  EXPECT_LT(script.find("render '/home"), script.find("frames check"));
}

TEST(SlurmScript, GpuPartitionTimeAccountAndExtraOptions) {
  SlurmArrayJob job = sample_job();
  job.gpu = true;
  job.partition = "gpu";
  job.time_limit = "1:00:00";
  job.account = "vfx";
  job.sbatch_options = {"--mem=8G", "--qos=high"};
  job.max_running = 4;
  job.log_folder = "/farm/100%/logs";
  const std::string script = slurm_batch_script(job);
  for (const char* line : {"#SBATCH --gres=gpu:1\n", "#SBATCH --partition=gpu\n", "#SBATCH --time=1:00:00\n",
                           "#SBATCH --account=vfx\n", "#SBATCH --mem=8G\n", "#SBATCH --qos=high\n",
                           "#SBATCH --array=0-2%4\n", "#SBATCH --output=/farm/100%%/logs/%x_%A_%a.log\n"})
    EXPECT_NE(script.find(line), std::string::npos) << line << "\n" << script;
  // Every #SBATCH line comes before the first command: sbatch stops reading them there.
  EXPECT_LT(script.rfind("#SBATCH"), script.find("set -euo"));
}

TEST(SlurmScript, ValuesThatCannotGoIntoAScriptAreRefused) {
  SlurmArrayJob job = sample_job();
  job.render_args.push_back("line\nbreak");
  EXPECT_THROW(slurm_batch_script(job), InputError);
  job = sample_job();
  job.sbatch_options = {"--comment=a\nrm -rf /"};
  EXPECT_THROW(slurm_batch_script(job), InputError);
  job = sample_job();
  job.log_folder = "/farm/\"quoted\"";
  EXPECT_THROW(slurm_batch_script(job), InputError);
  job = sample_job();
  job.chunks.clear();
  EXPECT_THROW(slurm_batch_script(job), InputError);
}

TEST(SlurmScript, IsValidBash) {
  SlurmArrayJob job = sample_job();
  job.render_args.push_back("it's \"odd\" $x `y`");
  const std::string script = slurm_batch_script(job);
  std::FILE* bash = ::popen("bash -n", "w");
  ASSERT_NE(bash, nullptr);
  std::fwrite(script.data(), 1, script.size(), bash);
  EXPECT_EQ(::pclose(bash), 0) << script;
}

}  // namespace
}  // namespace pm
