// The session format's reading side on its own: no run engine, daemon or HTTP server linked.
// What a real capture records and ReadSession returns is tested in acquire/session_test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

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
