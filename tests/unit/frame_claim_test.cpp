// Tests of render/frame_claim and render/process_identity on real files and real processes: a
// claim is created and released; a live claim (this process) is refused; claims of a dead pid, a
// zombie or a reused pid are taken over; another host's claim, one of another boot and an
// unreadable claim are held until not refreshed for the stale age (forever with an age of 0); a
// release never removes a claim that is no longer its own; refreshing renews the modification
// time; remove_claim_if_stale removes a stale claim only.
#include "render/frame_claim.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

// A pid no process has: a child that has exited and been reaped.
long dead_pid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  return long(child);
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class FrameClaimTest : public test::FolderTest {
 protected:
  FrameClaimTest() : FolderTest("frame_claim_") {}

  std::string output() const { return (dir_ / "f_0007.exr").string(); }
  std::string claim() const { return output() + ".claim"; }
  // A claim file as another process would have written it: this process's identity changed by edit.
  void write_claim(void (*edit)(ClaimRecord&)) {
    ClaimRecord record;
    record.owner = this_process_identity();
    record.started_unix_seconds = 1795410166;
    edit(record);
    write("f_0007.exr.claim", claim_text(record));
  }
  void age_claim(int seconds) {
    fs::last_write_time(claim(), fs::file_time_type::clock::now() - std::chrono::seconds(seconds));
  }
};

TEST(ProcessIdentity, ThisProcessIsRunningAndHasAStartTime) {
  const ProcessIdentity self = this_process_identity();
  EXPECT_FALSE(self.host.empty());
  EXPECT_EQ(self.pid, long(getpid()));
  ASSERT_TRUE(process_start_ticks(self.pid).has_value());
  EXPECT_EQ(self.start_ticks, *process_start_ticks(self.pid));
  EXPECT_EQ(local_process_state(self), ProcessState::running);
  EXPECT_FALSE(process_start_ticks(dead_pid()).has_value());
}

TEST(ClaimText, RoundTrips) {
  ClaimRecord record;
  record.owner = {"node12", "6b1c-boot", 4242, 918273};
  record.started_unix_seconds = 1795410166;
  std::string problem;
  const std::optional<ClaimRecord> back = parse_claim_text(claim_text(record), &problem);
  ASSERT_TRUE(back.has_value()) << problem;
  EXPECT_EQ(back->owner.host, "node12");
  EXPECT_EQ(back->owner.boot_id, "6b1c-boot");
  EXPECT_EQ(back->owner.pid, 4242);
  EXPECT_EQ(back->owner.start_ticks, 918273u);
  EXPECT_EQ(back->started_unix_seconds, 1795410166);
  // Later versions may add lines; they are ignored.
  EXPECT_TRUE(parse_claim_text(claim_text(record) + "frames 0-23\n", &problem).has_value());
}

TEST(ClaimText, MalformedTextNamesItsProblem) {
  const std::string header = "pmrender frame claim\n";
  const std::string full = header + "host h\npid 5\nstart_ticks 9\nstarted 100\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", "empty"},
      {"hello\n", "not a pmrender claim"},
      {header, "no host line"},
      {header + "host h\npid x\nstart_ticks 9\nstarted 100\n", "bad pid 'x'"},
      {header + "host h\npid 0\nstart_ticks 9\nstarted 100\n", "bad pid '0'"},
      {header + "host h\npid 12abc\nstart_ticks 9\nstarted 100\n", "bad pid '12abc'"},
      {header + "host h\npid 5\nstarted 100\n", "no start_ticks line"},
      {header + "host \npid 5\nstart_ticks 9\nstarted 100\n", "empty host"},
      {full.substr(0, full.size() - 12), "no started line"},  // cut short
  };
  for (const auto& [text, expected] : cases) {
    std::string problem;
    EXPECT_FALSE(parse_claim_text(text, &problem).has_value()) << text;
    EXPECT_EQ(problem, expected) << text;
  }
}

TEST_F(FrameClaimTest, ClaimIsCreatedWithThisProcessAndRemovedOnRelease) {
  ClaimAttempt attempt = claim_frame(output(), ClaimRules{});
  ASSERT_TRUE(attempt.claim.held());
  EXPECT_FALSE(attempt.other.has_value());
  EXPECT_EQ(attempt.claim.path(), claim());
  std::string problem;
  const std::optional<ClaimRecord> record = parse_claim_text(file_text(claim()), &problem);
  ASSERT_TRUE(record.has_value()) << problem;
  EXPECT_EQ(record->owner.pid, long(getpid()));
  EXPECT_EQ(record->owner.start_ticks, this_process_identity().start_ticks);
  attempt.claim.release();
  EXPECT_FALSE(fs::exists(claim()));
  attempt.claim.release();  // twice: nothing more happens
  {
    ClaimAttempt scoped = claim_frame(output(), ClaimRules{});
    EXPECT_TRUE(fs::exists(claim()));
  }
  EXPECT_FALSE(fs::exists(claim())) << "destroying a held claim releases it";
}

TEST_F(FrameClaimTest, LiveClaimIsRefused) {
  ClaimAttempt first = claim_frame(output(), ClaimRules{});
  ASSERT_TRUE(first.claim.held());
  const ClaimAttempt second = claim_frame(output(), ClaimRules{});
  EXPECT_FALSE(second.claim.held());
  ASSERT_TRUE(second.other.has_value());
  EXPECT_FALSE(second.other->stale);
  EXPECT_EQ(claim_holder_text(*second.other).rfind("pid " + std::to_string(getpid()) + " on ", 0), 0u)
      << claim_holder_text(*second.other);
  EXPECT_TRUE(fs::exists(claim()));
}

TEST_F(FrameClaimTest, ClaimOfADeadProcessIsTakenOver) {
  static long pid;
  pid = dead_pid();
  write_claim([](ClaimRecord& r) { r.owner.pid = pid; });
  ClaimAttempt attempt = claim_frame(output(), ClaimRules{});
  ASSERT_TRUE(attempt.claim.held());
  ASSERT_TRUE(attempt.other.has_value());
  EXPECT_TRUE(attempt.other->stale);
  EXPECT_NE(attempt.other->why_stale.find("pid " + std::to_string(pid) + " on "), std::string::npos);
  EXPECT_NE(attempt.other->why_stale.find("is no longer running"), std::string::npos) << attempt.other->why_stale;
  EXPECT_NE(file_text(claim()).find("\npid " + std::to_string(getpid()) + "\n"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(dir_))  // the stale claim was moved aside, then removed
    EXPECT_EQ(entry.path(), fs::path(claim()));
}

TEST_F(FrameClaimTest, ClaimOfAnUnreapedZombieIsStale) {
  static long pid;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  pid = long(child);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // it exits; nobody reaps it yet
  ASSERT_EQ(kill(child, 0), 0) << "a zombie still answers kill(pid, 0)";
  write_claim([](ClaimRecord& r) {
    r.owner.pid = pid;
    r.owner.start_ticks = process_start_ticks(pid).value_or(0);
  });
  const std::optional<ClaimInspection> found = inspect_claim(claim(), ClaimRules{});
  waitpid(child, nullptr, 0);
  ASSERT_TRUE(found.has_value());
  EXPECT_TRUE(found->stale);
  EXPECT_NE(found->why_stale.find("is no longer running"), std::string::npos) << found->why_stale;
}

TEST_F(FrameClaimTest, ReusedPidIsStale) {
  write_claim([](ClaimRecord& r) { r.owner.start_ticks += 1; });  // this pid, started at another time
  const std::optional<ClaimInspection> found = inspect_claim(claim(), ClaimRules{});
  ASSERT_TRUE(found.has_value());
  EXPECT_TRUE(found->stale);
  EXPECT_NE(found->why_stale.find("now belongs to another process"), std::string::npos) << found->why_stale;
}

TEST_F(FrameClaimTest, ClaimOfAnotherBootIsJudgedByItsAgeLikeAnotherHosts) {
  // This host's name with another boot id: a restart, or another machine of the same name, where
  // a pid that is gone here may still run. Only its age can make it stale.
  ASSERT_FALSE(this_process_identity().boot_id.empty()) << "no /proc/sys/kernel/random/boot_id here";
  static long pid;
  pid = dead_pid();
  ClaimRules rules;
  rules.stale_after_seconds = 600;
  write_claim([](ClaimRecord& r) {
    r.owner.boot_id = "00000000-0000-0000-0000-000000000000";
    r.owner.pid = pid;  // gone here, yet maybe running there
  });
  EXPECT_FALSE(inspect_claim(claim(), rules)->stale);
  age_claim(700);
  const std::optional<ClaimInspection> found = inspect_claim(claim(), rules);
  EXPECT_TRUE(found->stale);
  EXPECT_NE(found->why_stale.find("has not refreshed it for 7"), std::string::npos) << found->why_stale;
}

TEST_F(FrameClaimTest, ClaimFromAnotherHostIsHeldUntilNotRefreshedForTheStaleAge) {
  write_claim([](ClaimRecord& r) {
    r.owner.host = "node-elsewhere";
    r.owner.pid = 1;
  });
  ClaimRules rules;
  rules.stale_after_seconds = 600;
  ClaimAttempt attempt = claim_frame(output(), rules);
  EXPECT_FALSE(attempt.claim.held()) << "a fresh claim of another host is live, whatever its pid";
  ASSERT_TRUE(attempt.other.has_value());
  EXPECT_EQ(claim_holder_text(*attempt.other).rfind("pid 1 on node-elsewhere since ", 0), 0u);

  age_claim(599);
  EXPECT_FALSE(inspect_claim(claim(), rules)->stale);
  age_claim(700);
  ClaimRules never;
  never.stale_after_seconds = 0;
  EXPECT_FALSE(inspect_claim(claim(), never)->stale) << "an age of 0 never takes over another host's claim";
  attempt = claim_frame(output(), rules);
  ASSERT_TRUE(attempt.claim.held());
  ASSERT_TRUE(attempt.other.has_value());
  EXPECT_NE(attempt.other->why_stale.find("pid 1 on node-elsewhere has not refreshed it for 7"), std::string::npos)
      << attempt.other->why_stale;
}

TEST_F(FrameClaimTest, UnreadableClaimIsHeldUntilNotRefreshedForTheStaleAge) {
  // What an owner killed between creating the file and writing it leaves: an empty file.
  write("f_0007.exr.claim", "");
  ClaimRules rules;
  rules.stale_after_seconds = 600;
  ClaimAttempt attempt = claim_frame(output(), rules);
  EXPECT_FALSE(attempt.claim.held()) << "a fresh unreadable claim may be one being written";
  ASSERT_TRUE(attempt.other.has_value());
  EXPECT_EQ(claim_holder_text(*attempt.other), "an unknown process (unreadable claim: empty)");
  age_claim(700);
  ClaimRules never;
  never.stale_after_seconds = 0;
  EXPECT_FALSE(inspect_claim(claim(), never)->stale);
  attempt = claim_frame(output(), rules);
  ASSERT_TRUE(attempt.claim.held());
  EXPECT_NE(attempt.other->why_stale.find("unreadable (empty) and not refreshed for 7"), std::string::npos)
      << attempt.other->why_stale;
}

TEST_F(FrameClaimTest, ReleaseLeavesAClaimThatIsNoLongerItsOwn) {
  ClaimAttempt attempt = claim_frame(output(), ClaimRules{});
  ASSERT_TRUE(attempt.claim.held());
  // Taken over meanwhile (this process was stopped long enough, say): another file at the path.
  fs::remove(claim());
  write("f_0007.exr.claim", "pmrender frame claim\nhost node-elsewhere\npid 3\nstart_ticks 1\nstarted 1\n");
  attempt.claim.release();
  EXPECT_TRUE(fs::exists(claim()));
}

TEST_F(FrameClaimTest, RefreshRenewsTheModificationTimeOfHeldClaims) {
  ClaimAttempt attempt = claim_frame(output(), ClaimRules{});
  ASSERT_TRUE(attempt.claim.held());
  age_claim(300);
  EXPECT_GT(inspect_claim(claim(), ClaimRules{})->seconds_since_refresh, 299);
  refresh_held_claims();
  EXPECT_LT(inspect_claim(claim(), ClaimRules{})->seconds_since_refresh, 5);
  attempt.claim.release();
  EXPECT_FALSE(fs::exists(claim()));
}

TEST_F(FrameClaimTest, OnlyAStaleClaimIsRemovedByRemoveClaimIfStale) {
  EXPECT_FALSE(remove_claim_if_stale(output(), ClaimRules{}).has_value());  // none there
  ClaimAttempt live = claim_frame(output(), ClaimRules{});
  EXPECT_FALSE(remove_claim_if_stale(output(), ClaimRules{}).has_value());
  EXPECT_TRUE(fs::exists(claim()));
  live.claim.release();
  static long pid;
  pid = dead_pid();
  write_claim([](ClaimRecord& r) { r.owner.pid = pid; });
  const std::optional<ClaimInspection> removed = remove_claim_if_stale(output(), ClaimRules{});
  ASSERT_TRUE(removed.has_value());
  EXPECT_NE(removed->why_stale.find("is no longer running"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(FrameClaimTest, MissingFoldersAreCreated) {
  const std::string nested = (dir_ / "shot" / "f_0001.exr").string();
  ClaimAttempt attempt = claim_frame(nested, ClaimRules{});
  EXPECT_TRUE(attempt.claim.held());
  EXPECT_TRUE(fs::exists(nested + ".claim"));
  EXPECT_FALSE(inspect_claim((dir_ / "none.exr.claim").string(), ClaimRules{}).has_value());
}

}  // namespace
}  // namespace pm
