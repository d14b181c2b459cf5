#include "common/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>

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
