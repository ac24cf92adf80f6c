// Claim files (frame_claim.h): their text, judging one found on disk, creating and taking over
// claims without ever removing a claim that was not the one judged, and the refresh thread.
#include "render/frame_claim.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

#include "render/atomic_file.h"
#include "render/interruption.h"

namespace pm {

namespace {

namespace fs = std::filesystem;

constexpr char kClaimHeader[] = "pmrender frame claim";
// A claim is a few lines; anything much longer is not one.
constexpr size_t kMaxClaimBytes = 4096;

// The descriptors of the claims this process holds, for refresh_held_claims().
std::mutex g_held_mutex;
std::set<int> g_held_descriptors;

bool parse_integer_field(const std::string& text, long long* value) {
  if (text.empty() || (text[0] != '-' && (text[0] < '0' || text[0] > '9'))) return false;
  try {
    size_t used = 0;
    *value = std::stoll(text, &used);
    return used == text.size();
  } catch (const std::exception&) {
    return false;
  }
}

double seconds_since(const struct stat& info) {
  const double modified = double(info.st_mtim.tv_sec) + 1e-9 * double(info.st_mtim.tv_nsec);
  const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  return now - modified;
}

std::string seconds_text(double seconds) { return std::to_string(static_cast<long long>(seconds)) + " s"; }

// Fills in stale and why_stale.
void judge(ClaimInspection& claim, const ClaimRules& rules) {
  const ProcessIdentity self = this_process_identity();
  const bool can_expire = rules.stale_after_seconds > 0 && claim.seconds_since_refresh > rules.stale_after_seconds;
  if (!claim.record) {
    claim.stale = can_expire;
    if (claim.stale)
      claim.why_stale = "unreadable (" + claim.problem + ") and not refreshed for " + seconds_text(claim.seconds_since_refresh);
    return;
  }
  const ProcessIdentity& owner = claim.record->owner;
  const std::string who = "pid " + std::to_string(owner.pid) + " on " + owner.host;
  // Another boot id under the same name is a restart, or another machine that shares the name
  // (containers, cloned images): its pid cannot be checked here either.
  const bool other_boot = !owner.boot_id.empty() && !self.boot_id.empty() && owner.boot_id != self.boot_id;
  if (owner.host != self.host || other_boot) {
    claim.stale = can_expire;
    if (claim.stale) claim.why_stale = who + " has not refreshed it for " + seconds_text(claim.seconds_since_refresh);
    return;
  }
  switch (local_process_state(owner)) {
    case ProcessState::running: claim.stale = false; break;
    case ProcessState::gone: claim.stale = true; claim.why_stale = who + " is no longer running"; break;
    case ProcessState::replaced: claim.stale = true; claim.why_stale = who + " now belongs to another process"; break;
  }
}

// "<folder>/.<name>-<pid>": where a stale claim is moved before it is removed (hidden, and within
// the name length output_checks.h reserves for temporaries).
std::string aside_path(const std::string& claim_path) {
  const fs::path path(claim_path);
  return (path.parent_path() / ("." + path.filename().string() + "-" + std::to_string(::getpid()))).string();
}

// Removes the claim judged stale, and only it: the claim is moved aside first, then checked to be
// the file judged. Another process may have taken it over first and written its own, live claim
// there: that one goes back where it was. False when the judged claim was no longer there.
bool remove_judged_claim(const ClaimInspection& judged) {
  const std::string aside = aside_path(judged.path);
  if (std::rename(judged.path.c_str(), aside.c_str()) != 0) {
    if (errno == ENOENT) return false;
    throw std::runtime_error(errno_text("cannot move the stale claim '" + judged.path + "' aside"));
  }
  struct stat moved {};
  if (::stat(aside.c_str(), &moved) == 0 && moved.st_dev == judged.device && moved.st_ino == judged.inode) {
    ::unlink(aside.c_str());
    return true;
  }
  std::rename(aside.c_str(), judged.path.c_str());
  return false;
}

}  // namespace

std::string claim_path_for(const std::string& output_path) { return output_path + ".claim"; }

std::string claim_text(const ClaimRecord& record) {
  std::ostringstream text;
  text << kClaimHeader << "\nhost " << record.owner.host << "\nboot_id " << record.owner.boot_id << "\npid "
       << record.owner.pid << "\nstart_ticks " << record.owner.start_ticks << "\nstarted "
       << record.started_unix_seconds << "\n";
  return text.str();
}

std::optional<ClaimRecord> parse_claim_text(const std::string& text, std::string* problem) {
  auto refuse = [problem](const std::string& why) {
    *problem = why;
    return std::nullopt;
  };
  std::istringstream lines(text);
  std::string line;
  if (text.empty()) return refuse("empty");
  if (!std::getline(lines, line) || line != kClaimHeader) return refuse("not a pmrender claim");
  ClaimRecord record;
  std::set<std::string> seen;
  while (std::getline(lines, line)) {
    const size_t blank = line.find(' ');
    const std::string key = line.substr(0, blank), value = blank == std::string::npos ? "" : line.substr(blank + 1);
    long long number = 0;
    const bool numeric = parse_integer_field(value, &number);
    if (key == "host") {
      record.owner.host = value;
    } else if (key == "boot_id") {
      record.owner.boot_id = value;
    } else if (key == "pid") {
      if (!numeric || number <= 0) return refuse("bad pid '" + value + "'");
      record.owner.pid = long(number);
    } else if (key == "start_ticks") {
      if (!numeric || number < 0) return refuse("bad start_ticks '" + value + "'");
      record.owner.start_ticks = static_cast<unsigned long long>(number);
    } else if (key == "started") {
      if (!numeric) return refuse("bad started '" + value + "'");
      record.started_unix_seconds = number;
    } else {
      continue;
    }
    seen.insert(key);
  }
  for (const char* key : {"host", "pid", "start_ticks", "started"})
    if (!seen.count(key)) return refuse(std::string("no ") + key + " line");
  if (record.owner.host.empty()) return refuse("empty host");
  return record;
}

std::optional<ClaimInspection> inspect_claim(const std::string& claim_path, const ClaimRules& rules) {
  const int fd = ::open(claim_path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw std::runtime_error(errno_text("cannot read '" + claim_path + "'"));
  }
  ClaimInspection claim;
  claim.path = claim_path;
  struct stat info {};
  std::string text(kMaxClaimBytes + 1, '\0');
  size_t size = 0;
  ssize_t got = 0;
  while (size < text.size() && (got = ::read(fd, &text[size], text.size() - size)) > 0) size += size_t(got);
  const bool read_failed = got < 0 || ::fstat(fd, &info) != 0;
  ::close(fd);
  if (read_failed) throw std::runtime_error(errno_text("cannot read '" + claim_path + "'"));
  text.resize(size);
  claim.device = info.st_dev;
  claim.inode = info.st_ino;
  claim.seconds_since_refresh = seconds_since(info);
  if (size > kMaxClaimBytes) claim.problem = "longer than " + std::to_string(kMaxClaimBytes) + " bytes";
  else claim.record = parse_claim_text(text, &claim.problem);
  judge(claim, rules);
  return claim;
}

std::string claim_holder_text(const ClaimInspection& claim) {
  if (!claim.record) return "an unknown process (unreadable claim: " + claim.problem + ")";
  const std::time_t started = std::time_t(claim.record->started_unix_seconds);
  char when[32] = "?";
  struct tm local {};
  if (::localtime_r(&started, &local)) std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S", &local);
  return "pid " + std::to_string(claim.record->owner.pid) + " on " + claim.record->owner.host + " since " + when;
}

FrameClaim::FrameClaim(FrameClaim&& other) noexcept { *this = std::move(other); }

FrameClaim& FrameClaim::operator=(FrameClaim&& other) noexcept {
  if (this == &other) return *this;
  release();
  path_ = std::move(other.path_);
  fd_ = other.fd_;
  temporary_slot_ = other.temporary_slot_;
  other.fd_ = -1;
  other.temporary_slot_ = -1;
  return *this;
}

void FrameClaim::release() noexcept {
  if (fd_ < 0) return;
  {
    std::lock_guard<std::mutex> lock(g_held_mutex);
    g_held_descriptors.erase(fd_);
  }
  struct stat mine {}, there {};
  if (::fstat(fd_, &mine) == 0 && ::stat(path_.c_str(), &there) == 0 && mine.st_dev == there.st_dev &&
      mine.st_ino == there.st_ino)
    ::unlink(path_.c_str());
  unregister_temporary(temporary_slot_);
  ::close(fd_);
  fd_ = -1;
  temporary_slot_ = -1;
}

ClaimAttempt claim_frame(const std::string& output_path, const ClaimRules& rules) {
  ClaimAttempt attempt;
  const std::string path = claim_path_for(output_path);
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty()) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) throw std::runtime_error("cannot create folder '" + folder.string() + "': " + error.message());
  }
  ClaimRecord record;
  record.owner = this_process_identity();
  record.started_unix_seconds = std::time(nullptr);
  const std::string text = claim_text(record);
  // Each round either creates the claim, finds a live one, or removes one stale claim; other
  // processes can only make a few rounds fail, so the bound is never reached in practice.
  for (int round = 0; round < 16; ++round) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      if (::write(fd, text.data(), text.size()) != ssize_t(text.size())) {
        const std::string reason = errno_text("cannot write '" + path + "'");
        ::unlink(path.c_str());
        ::close(fd);
        throw std::runtime_error(reason);
      }
      attempt.claim.path_ = path;
      attempt.claim.fd_ = fd;
      attempt.claim.temporary_slot_ = register_temporary(path);
      std::lock_guard<std::mutex> lock(g_held_mutex);
      g_held_descriptors.insert(fd);
      return attempt;
    }
    if (errno != EEXIST) throw std::runtime_error(errno_text("cannot create '" + path + "'"));
    std::optional<ClaimInspection> found = inspect_claim(path, rules);
    if (!found) continue;  // released since: try again
    if (!found->stale) {
      attempt.other = std::move(found);
      return attempt;
    }
    if (remove_judged_claim(*found)) attempt.other = std::move(found);
  }
  throw std::runtime_error("cannot claim '" + path + "': other processes keep changing it");
}

std::optional<ClaimInspection> remove_claim_if_stale(const std::string& output_path, const ClaimRules& rules) {
  std::optional<ClaimInspection> found = inspect_claim(claim_path_for(output_path), rules);
  if (!found || !found->stale || !remove_judged_claim(*found)) return std::nullopt;
  return found;
}

void refresh_held_claims() {
  std::lock_guard<std::mutex> lock(g_held_mutex);
  for (int fd : g_held_descriptors) ::futimens(fd, nullptr);  // best effort: a failure only ages it
}

ClaimRefresher::ClaimRefresher() {
  thread_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::seconds(kClaimRefreshSeconds), [this] { return stop_; }))
      refresh_held_claims();
  });
}

ClaimRefresher::~ClaimRefresher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

}  // namespace pm
