// Claim files: "<output>.claim" beside a frame's output (out/f_0007.exr.claim) says that a process
// is rendering that frame now, so that two processes given the same frames never render one
// frame at the same time. A claim is created with O_CREAT | O_EXCL before the frame renders and
// removed once its file has been renamed into place (or the frame failed or was interrupted).
// It holds the owner's host, boot id, pid, pid start time and the wall-clock time it started;
// its owner refreshes its modification time every kClaimRefreshSeconds.
//
// A claim in the way is stale, and may be taken over, when
//   - it is from this host (same host name and boot id): its process is gone, or its pid now
//     belongs to a later process;
//   - it is from another host, from this host before a restart (another boot id: as well another
//     machine of the same name), or unreadable (not in the format below: cut short, edited): it
//     has not been refreshed for ClaimRules::stale_after_seconds (0: never stale).
// Any other claim is live: its frame is left to its owner. docs/farm.md has the farm's view.
#pragma once

#include <sys/types.h>

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "render/process_identity.h"

namespace pm {

// How often an owner refreshes its claims: far below any sensible stale age, so that a live
// claim from another host never looks stale.
constexpr int kClaimRefreshSeconds = 30;

struct ClaimRules {
  // Claims that cannot be checked by pid (another host, unreadable) are stale when not
  // refreshed for this long; 0: never.
  double stale_after_seconds = 600;
};

// What a claim file says.
struct ClaimRecord {
  ProcessIdentity owner;
  int64_t started_unix_seconds = 0;
};

// "out/f_0007.exr" -> "out/f_0007.exr.claim".
std::string claim_path_for(const std::string& output_path);

// The file's text:
//   pmrender frame claim
//   host node12
//   boot_id 6b1c...
//   pid 4242
//   start_ticks 918273
//   started 1795410166
std::string claim_text(const ClaimRecord& record);
// The record, or nothing with *problem saying what is wrong ("empty", "no pid line", ...).
// Lines of other keys are ignored, so that later versions may add some.
std::optional<ClaimRecord> parse_claim_text(const std::string& text, std::string* problem);

// A claim file found on disk and judged by the rules above.
struct ClaimInspection {
  std::string path;
  std::optional<ClaimRecord> record;  // nothing: unreadable
  std::string problem;                // why unreadable
  double seconds_since_refresh = 0;   // now minus the file's modification time
  bool stale = false;
  std::string why_stale;              // "pid 4242 on node12 is no longer running"
  dev_t device = 0;                   // the file judged, so that a takeover removes only it
  ino_t inode = 0;
};

// The claim at claim_path judged against this process and the rules; nothing when there is none.
std::optional<ClaimInspection> inspect_claim(const std::string& claim_path, const ClaimRules& rules);

// "pid 4242 on node12 since 2026-11-23 05:02:46" (local time), or, for an unreadable claim,
// "an unknown process (unreadable claim: empty)".
std::string claim_holder_text(const ClaimInspection& claim);

struct ClaimAttempt;
// Claims the frame whose output is output_path, creating missing folders, taking over a stale
// claim. Throws std::runtime_error when the claim file cannot be created (no space, no permission).
ClaimAttempt claim_frame(const std::string& output_path, const ClaimRules& rules);

// A claim this process holds. Moving it moves the ownership; destroying it releases it.
class FrameClaim {
 public:
  FrameClaim() = default;
  FrameClaim(FrameClaim&& other) noexcept;
  FrameClaim& operator=(FrameClaim&& other) noexcept;
  FrameClaim(const FrameClaim&) = delete;
  FrameClaim& operator=(const FrameClaim&) = delete;
  ~FrameClaim() { release(); }

  bool held() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }
  // Removes the claim file, unless another process has taken it over meanwhile (the file at the
  // path is then no longer this one). Safe to call twice.
  void release() noexcept;

 private:
  friend ClaimAttempt claim_frame(const std::string& output_path, const ClaimRules& rules);
  std::string path_;
  int fd_ = -1;
  int temporary_slot_ = -1;
};

struct ClaimAttempt {
  FrameClaim claim;  // held(): this process renders the frame
  // Not held: the live claim in the way. Held: the stale claim that was taken over, if any.
  std::optional<ClaimInspection> other;
};

// Removes the claim beside output_path when it is stale and returns it; nothing when there is no
// claim or a live one. For complete frames, whose owner was killed after its file was renamed
// into place but before it removed its claim.
std::optional<ClaimInspection> remove_claim_if_stale(const std::string& output_path, const ClaimRules& rules);

// Sets the modification time of every claim this process holds to now (what the rules call a
// refresh). ClaimRefresher calls it every kClaimRefreshSeconds.
void refresh_held_claims();

// A thread that refreshes this process's claims while it exists.
class ClaimRefresher {
 public:
  ClaimRefresher();
  ~ClaimRefresher();
  ClaimRefresher(const ClaimRefresher&) = delete;
  ClaimRefresher& operator=(const ClaimRefresher&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace pm
