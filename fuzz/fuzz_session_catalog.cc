// session.sqlite, the catalog `session verify`, `reconstruct` and `capture --resume` trust
// (session::ReadSession, session::VerifySession). SQLite's own file format is fuzzed upstream;
// what is ours is what we do with the catalog's contents: paths, JSON cells, counts, versions.
// So the input is SQL, run against an empty catalog in a session directory that holds a few
// frames and the rig snapshot, and the seeds are `sqlite3 session.sqlite .dump` of real
// sessions: mutations change the cells. An authorizer keeps the SQL inside that one database
// file (no ATTACH, no VACUUM INTO, no PRAGMA but foreign_keys).
#include <sqlite3.h>

#include <filesystem>

#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "session/session_reader.h"
#include "session/session_verify.h"

namespace {

namespace fs = std::filesystem;

int Authorize(void*, int action, const char* arg1, const char*, const char*, const char*) {
  switch (action) {
    case SQLITE_CREATE_TABLE:
    case SQLITE_CREATE_INDEX:
    case SQLITE_INSERT:
    case SQLITE_UPDATE:
    case SQLITE_DELETE:
    case SQLITE_READ:
    case SQLITE_SELECT:
    case SQLITE_FUNCTION:
    case SQLITE_TRANSACTION:
    case SQLITE_SAVEPOINT:
      return SQLITE_OK;
    case SQLITE_PRAGMA:
      return arg1 && std::string(arg1) == "foreign_keys" ? SQLITE_OK : SQLITE_DENY;
    default:  // ATTACH, DETACH, VACUUM (INTO a file), ALTER, DROP, triggers, views, ...
      return SQLITE_DENY;
  }
}

// The input's SQL run on a fresh catalog; statements after the first failing one are skipped
// (what ran stays: a half-written catalog is an input too).
void WriteCatalog(const fs::path& file, const std::string& sql) {
  for (const char* suffix : {"", "-journal", "-wal", "-shm"}) fs::remove(file.string() + suffix);
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) ==
      SQLITE_OK) {
    sqlite3_limit(db, SQLITE_LIMIT_LENGTH, 1 << 20);
    sqlite3_set_authorizer(db, Authorize, nullptr);
    sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
  }
  sqlite3_close(db);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using brdfrig::fuzz::ScratchDir;
  using brdfrig::fuzz::WriteScratchFile;
  static const bool setup = [] {
    fs::create_directories(ScratchDir() / "frames");
    fs::create_directories(ScratchDir() / "rig");
    WriteScratchFile("rig/scene.yaml", brdfrig::fuzz::kSmallScene);
    WriteScratchFile("rig/rig.yaml", "geometry: scene.yaml\n");
    WriteScratchFile("plan.yaml", "sample: s\n");
    for (const char* frame : {"p000_b0.png", "p000_b1.png", "p001_b0.png", "p001_b1.png"}) {
      WriteScratchFile(std::string("frames/") + frame, frame);
    }
    return true;
  }();
  (void)setup;
  WriteCatalog(ScratchDir() / "session.sqlite", brdfrig::fuzz::AsString(data, size));
  try {
    (void)brdfrig::session::ReadSession(ScratchDir());
  } catch (const brdfrig::Error&) {
    // The documented refusal of a catalog it cannot trust.
  }
  try {
    (void)brdfrig::session::VerifySession(ScratchDir());
  } catch (const brdfrig::Error&) {
  }
  return 0;
}
