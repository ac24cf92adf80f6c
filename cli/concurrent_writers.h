// Other processes that write the same output files as this one: the temporaries that killed
// writers left behind, and the frame claims (render/frame_claim.h) that keep two live processes
// off the same frame, as `render` and `frames check` present them on the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "render/frame_claim.h"

namespace pm::cli {

// Registers --stale-claim-after SECONDS, the rules' age for claims that cannot be checked by pid:
// 0 (never stale) or at least twice the refresh interval, so that a live claim never looks stale.
void add_stale_claim_option(CLI::App* cmd, ClaimRules& rules);

// Temporaries that write_exr leaves behind when its process is killed mid-write:
// ".<name>.tmp-<pid>-<n>" beside the target. Removes those of the given targets whose process no
// longer exists on this host (each folder is listed once); verbose lists them.
void remove_stale_temporaries(const std::vector<std::string>& targets, bool verbose);

// Claims beside frames skipped as complete (--resume) whose owner was killed between renaming the
// frame into place and removing its claim: stale ones are removed (verbose lists them).
void remove_stale_claims_of_complete_frames(const std::string& pattern, const std::vector<int>& frames,
                                            const ClaimRules& rules, bool verbose);

// Waits up to seconds, in short steps, and returns early once a stop is requested (SIGINT, SIGTERM).
void sleep_unless_interrupted(double seconds);

}  // namespace pm::cli
