// Stale temporaries and claims, the --stale-claim-after option and the interruptible wait
// (concurrent_writers.h).
#include "cli/concurrent_writers.h"

#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include "cli/number_parsing.h"
#include "render/interruption.h"
#include "render/output_pattern.h"

namespace pm::cli {

namespace fs = std::filesystem;

void add_stale_claim_option(CLI::App* cmd, ClaimRules& rules) {
  const double shortest = 2.0 * kClaimRefreshSeconds;
  cmd->add_option("--stale-claim-after", rules.stale_after_seconds,
                  "A frame claim from another host, or an unreadable one, is stale (and is taken over) once not "
                  "refreshed for this many seconds; 0: never (docs/farm.md, \"Frame claims\")")
      ->default_val(rules.stale_after_seconds)
      ->transform(non_negative_float())
      ->check(CLI::Validator(
          [shortest](std::string& text) -> std::string {
            double seconds = -1;
            try {
              size_t used = 0;
              seconds = std::stod(text, &used);
              if (used != text.size()) seconds = -1;
            } catch (const std::exception&) {
            }
            if (seconds == 0 || seconds >= shortest) return "";
            return "expected 0 (never) or at least " + std::to_string(int(shortest)) +
                   " seconds (claims are refreshed every " + std::to_string(kClaimRefreshSeconds) + " s), got '" +
                   text + "'";
          },
          "SECONDS", "stale_claim_age"));
}

void remove_stale_temporaries(const std::vector<std::string>& targets, bool verbose) {
  std::map<fs::path, std::set<std::string>> names_by_folder;
  for (const std::string& target : targets) {
    const fs::path path(target);
    names_by_folder[path.parent_path().empty() ? fs::path(".") : path.parent_path()].insert(path.filename().string());
  }
  for (const auto& [folder, names] : names_by_folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      const size_t tmp = name.rfind(".tmp-");
      if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos || !names.count(name.substr(1, tmp - 1))) continue;
      const std::string rest = name.substr(tmp + 5);
      const size_t dash = rest.find('-');
      if (dash == std::string::npos || dash == 0) continue;
      long pid = 0;
      try {
        size_t used = 0;
        pid = std::stol(rest.substr(0, dash), &used);
        if (used != dash) continue;
      } catch (const std::exception&) {
        continue;
      }
      if (pid <= 0 || ::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue;  // its writer is alive
      std::error_code remove_error;
      if (fs::remove(entry.path(), remove_error) && verbose)
        std::printf("removed stale temporary %s\n", entry.path().c_str());
    }
  }
}

void remove_stale_claims_of_complete_frames(const std::string& pattern, const std::vector<int>& frames,
                                            const ClaimRules& rules, bool verbose) {
  for (int f : frames) {
    const std::optional<ClaimInspection> removed = remove_claim_if_stale(expand_output_pattern(pattern, f), rules);
    if (removed && verbose) std::printf("removed stale claim %s: %s\n", removed->path.c_str(), removed->why_stale.c_str());
  }
}

void sleep_unless_interrupted(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (interruption_signal() == 0 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

}  // namespace pm::cli
