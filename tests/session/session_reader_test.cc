// The session format's reading side on its own: no run engine, daemon or HTTP server linked.
// What a real capture records and ReadSession returns is tested in acquire/session_test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "common/error.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "session/sqlite_db.h"

namespace brdfrig::session {
namespace {

namespace fs = std::filesystem;

fs::path EmptyDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(SessionReaderTest, ADirectoryWithoutACatalogIsNotASession) {
  const fs::path dir = EmptyDir("brdfrig_not_a_session");
  EXPECT_THAT([&] { ReadSession(dir); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("is not a session")));
  EXPECT_THROW(VerifySession(dir), Error);
}

// A catalog from the fuzz seed (the `.dump` of a real two-position session) with `edit` (SQL)
// applied, in a fresh session directory.
fs::path CatalogFromSeed(const std::string& name, const std::string& edit) {
  const fs::path dir = EmptyDir(name);
  std::ifstream in(BRDFRIG_SOURCE_DIR "/fuzz/corpus/fuzz_session_catalog/two_positions.sql");
  const std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(seed.empty());
  SqliteDb db(dir / "session.sqlite", SqliteDb::Mode::kCreate);
  db.Exec(seed);
  db.Exec(edit);
  return dir;
}

// Found by fuzz_session_catalog: a JSON cell that is not JSON, or not the JSON this version
// writes, ended in an uncaught nlohmann::json exception (std::terminate in `session verify`).
TEST(SessionReaderTest, AMalformedJsonCellNamesTheCatalogAndTheCell) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"UPDATE frames SET axis_readings_json = '{\"camera_arm\": 0.3' WHERE id = 1",
       "frames.axis_readings_json"},
      {"UPDATE frames SET axis_readings_json = '[1, 2]' WHERE id = 1", "frames.axis_readings_json"},
      {"UPDATE session SET positions_json = '{}'", "session.positions_json"},
      {"UPDATE session SET positions_json = '[3]'", "session.positions_json"},
      {"UPDATE session SET exposures_json = '[\"a\"]'", "session.exposures_json"},
      {"UPDATE meta SET value = 'x' WHERE key = 'validation_positions'",
       "meta.validation_positions"}};
  for (const auto& [edit, cell] : cases) {
    const fs::path dir = CatalogFromSeed("brdfrig_catalog_json", edit);
    EXPECT_THAT([&] { ReadSession(dir); },
                ::testing::ThrowsMessage<FileError>(::testing::AllOf(
                    ::testing::HasSubstr((dir / "session.sqlite").string()),
                    ::testing::HasSubstr(cell), ::testing::HasSubstr("not what this version"))))
        << edit;
  }
}

// An auto-bracketed session whose catalog lists a negative position as complete indexed the
// planned brackets at -1 (out of bounds).
TEST(SessionReaderTest, ANegativePositionIndexIsNotABracketOfAnyPlannedPosition) {
  const fs::path dir = CatalogFromSeed("brdfrig_catalog_negative",
                                       "UPDATE session SET exposures_json = '\"auto\"';"
                                       "UPDATE frames SET position_index = -1 WHERE id = 1;"
                                       "INSERT INTO positions VALUES (-1, 'now', 1);");
  try {
    const SessionContents s = ReadSession(dir);
    for (const auto& bracket : s.planned_brackets) EXPECT_LE(bracket.size(), 2u);
  } catch (const Error& e) {
    // The rig snapshot is not in this directory: refused after the frames were read.
    EXPECT_THAT(e.what(), ::testing::HasSubstr("rig"));
  }
}

TEST(SqliteDbTest, WritesInATransactionAndReadsBack) {
  const fs::path file = EmptyDir("brdfrig_sqlite") / "t.sqlite";
  {
    SqliteDb db(file, SqliteDb::Mode::kCreate);
    db.Exec("CREATE TABLE t(k TEXT PRIMARY KEY, v REAL)");
    Transaction tx(db);
    Statement(db, "INSERT INTO t VALUES (?1, ?2)").Bind(1, "a").Bind(2, 0.5).Run();
    tx.Commit();
  }
  SqliteDb db(file, SqliteDb::Mode::kReadOnly);
  Statement q(db, "SELECT k, v FROM t");
  ASSERT_TRUE(q.Step());
  EXPECT_EQ(q.Text(0), "a");
  EXPECT_DOUBLE_EQ(q.Double(1), 0.5);
  EXPECT_FALSE(q.Step());
}

}  // namespace
}  // namespace brdfrig::session
