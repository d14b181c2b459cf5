#include "common/atomic_file.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <span>

#include "common/error.h"
#include "common/parallel.h"

namespace brdfrig {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("brdfrig_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(AtomicFileTest, WritesContentAndLeavesNoTemporaryFile) {
  const fs::path dir = FreshDir("atomic");
  WriteFileAtomically(dir / "a.txt", std::string_view("hello"));
  EXPECT_EQ(ReadFileToString(dir / "a.txt"), "hello");
  WriteFileAtomically(dir / "a.txt", std::string_view("replaced"));
  EXPECT_EQ(ReadFileToString(dir / "a.txt"), "replaced");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(AtomicFileTest, UnwritableDirectoryGivesErrorNamingThePath) {
  try {
    WriteFileAtomically("/nonexistent_dir/x.txt", std::string_view("x"));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/x.txt"), std::string::npos);
  }
}

// Issue 25, finding 3: the temporary was "<out>.tmp-<pid>", opened with O_CREAT|O_TRUNC, so a
// symlink planted at that name made the write overwrite its target and left the output a link.
TEST(AtomicFileTest, PlantedSymlinkAtTheTemporaryNameIsNeitherFollowedNorOverwritten) {
  const fs::path dir = FreshDir("atomic_symlink");
  const fs::path victim = dir / "victim";
  WriteFileAtomically(victim, std::string_view("precious"));
  const fs::path out = dir / "out.binary";
  const fs::path planted = dir / ("out.binary.tmp-" + std::to_string(::getpid()));
  fs::create_symlink(victim, planted);
  WriteFileAtomically(out, std::string_view("new output"));
  EXPECT_EQ(ReadFileToString(victim), "precious");
  EXPECT_FALSE(fs::is_symlink(out));
  EXPECT_EQ(ReadFileToString(out), "new output");
  EXPECT_TRUE(fs::is_symlink(planted)) << "someone else's file is left alone";
  fs::remove_all(dir);
}

TEST(AtomicFileTest, TemporariesAreFreshFilesBesideTheTarget) {
  const fs::path dir = FreshDir("atomic_fresh");
  const std::string_view bytes("x");
  const fs::path a = WriteTemporaryAndSync(dir / "t.json", std::as_bytes(std::span(bytes)));
  const fs::path b = WriteTemporaryAndSync(dir / "t.json", std::as_bytes(std::span(bytes)));
  EXPECT_NE(a, b);
  EXPECT_EQ(a.parent_path(), dir);
  EXPECT_NE(a.filename().string().find("t.json.tmp-"), std::string::npos) << a;
  RenameAndSync(a, dir / "t.json");
  EXPECT_EQ(ReadFileToString(dir / "t.json"), "x");
  EXPECT_EQ(ReadFileToString(b), "x");
  fs::remove_all(dir);
}

// Issue 25, finding 11: a writer killed between writing and renaming left its temporary
// beside the output forever.
TEST(AtomicFileTest, StaleTemporariesOfEndedWritersAreRemovedAndNothingElse) {
  const fs::path dir = FreshDir("atomic_stale");
  const pid_t ended = ::fork();
  if (ended == 0) ::_exit(0);
  ::waitpid(ended, nullptr, 0);
  const std::string dead = std::to_string(ended), alive = std::to_string(::getpid());
  const auto old = fs::file_time_type::clock::now() - std::chrono::hours(1);
  auto make = [&](const std::string& name, bool is_old) {
    std::ofstream(dir / name) << "torn";
    if (is_old) fs::last_write_time(dir / name, old);
    return dir / name;
  };
  const std::vector<fs::path> removed = {make("m.json.tmp-" + dead, true),
                                         make("m.json.tmp-" + dead + "-0123abcd", true)};
  const std::vector<fs::path> kept = {
      make("m.json.tmp-" + alive + "-0123abcd", true),  // its writer runs
      make("m.json.tmp-" + dead + "-4567abcd", false),  // written lately: maybe another host's
      make("n.json.tmp-" + dead, true),                 // another output's
      make("xm.json.tmp-" + dead, true),
      make("m.json.tmp-" + dead + "-0123ABCD", true),  // not this code's pattern
      make("m.json.tmp-" + dead + "-0123abc", true),
      make("m.json.tmp-" + dead + "x", true),
      make("m.json.tmp-", true),
      make("m.json.tmp-0", true),
      make("m.json", true)};
  const fs::path victim = make("victim", true);
  const fs::path link = dir / ("m.json.tmp-" + dead + "-89abcdef");
  fs::create_symlink(victim, link);
  const fs::path directory = dir / ("m.json.tmp-" + dead + "-fedcba98");
  fs::create_directory(directory);
  fs::last_write_time(directory, old);

  EXPECT_EQ(RemoveStaleTemporaries(dir / "m.json"), 2);
  for (const fs::path& p : removed) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(fs::is_directory(directory));
  EXPECT_EQ(ReadFileToString(victim), "torn");

  // Every atomic write does it before creating its own temporary.
  const fs::path again = make("m.json.tmp-" + dead + "-00000000", true);
  WriteFileAtomically(dir / "m.json", std::string_view("new"));
  EXPECT_FALSE(fs::exists(again));
  EXPECT_EQ(ReadFileToString(dir / "m.json"), "new");
  fs::remove_all(dir);
}

TEST(ParallelForTest, CoversEveryIndexExactlyOnce) {
  std::vector<int> hits(1000, 0);
  ParallelFor(
      hits.size(),
      [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) hits[i]++;
      },
      4);
  for (int h : hits) EXPECT_EQ(h, 1);
}

TEST(ParallelForTest, RethrowsTheWorkersException) {
  EXPECT_THROW(ParallelFor(
                   10, [](std::size_t, std::size_t) { throw Error("boom"); }, 2),
               Error);
}

}  // namespace
}  // namespace brdfrig
