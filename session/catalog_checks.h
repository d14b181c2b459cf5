// What a session's catalog says is checked before it is trusted: the schema version (a
// catalog written by a newer brdfrig is refused, not misread), and every path read from it
// (frames.file, snapshot names) stays inside the session directory — a cell holding an
// absolute path or "../" must never make a resume delete, or a reader use, a file elsewhere.
#pragma once

#include <filesystem>
#include <string>

#include "session/sqlite_db.h"

namespace brdfrig::session {

// The newest catalog schema this build reads and writes (docs/acquire.md, "Schema").
inline constexpr int kSessionSchemaVersion = 2;

// Reads meta.schema_version; throws Error naming the session when it is missing, not a
// number, or newer than kSessionSchemaVersion. Returns it.
int CheckSchemaVersion(SqliteDb& db, const std::filesystem::path& dir);

// `relative` (a catalog cell) as a path inside dir/folder: exactly "<folder>/<name>" with one
// plain file name. Throws Error naming the session, the column and the value otherwise.
std::filesystem::path CatalogFile(const std::filesystem::path& dir, const std::string& folder,
                                  const std::string& relative, const std::string& column);

// Checks every frames.file and snapshot_files.name of the catalog (CatalogFile), so that a
// session is refused as a whole before anything in it is deleted or read.
void CheckCatalogPaths(SqliteDb& db, const std::filesystem::path& dir);

}  // namespace brdfrig::session
