#include "session/catalog_checks.h"

#include "common/error.h"

namespace brdfrig::session {

namespace fs = std::filesystem;

int CheckSchemaVersion(SqliteDb& db, const fs::path& dir) {
  Statement q(db, "SELECT value FROM meta WHERE key = 'schema_version'");
  if (!q.Step()) throw Error("session '" + dir.string() + "' has no schema_version in its catalog");
  const std::string text = q.Text(0);
  int version = 0;
  try {
    std::size_t used = 0;
    version = std::stoi(text, &used);
    if (used != text.size()) version = 0;
  } catch (const std::exception&) {
    version = 0;
  }
  if (version < 1) {
    throw Error("session '" + dir.string() + "': schema_version '" + text + "' is not a version");
  }
  if (version > kSessionSchemaVersion) {
    throw Error("session '" + dir.string() + "' has schema_version " + std::to_string(version) +
                ", newer than this brdfrig reads (" + std::to_string(kSessionSchemaVersion) +
                "): use the brdfrig that wrote it, or a newer one");
  }
  return version;
}

fs::path CatalogFile(const fs::path& dir, const std::string& folder, const std::string& relative,
                     const std::string& column) {
  const fs::path p(relative);
  const std::string name = p.filename().string();
  const bool plain = !relative.empty() && relative.find('\0') == std::string::npos &&
                     p.is_relative() && p.parent_path() == folder && !name.empty() && name != "." &&
                     name != "..";
  if (!plain) {
    throw Error("session '" + dir.string() + "': " + column + " '" + relative +
                "' is not a file in " + folder + "/ (a catalog path must stay inside its " +
                "session); the session is refused, nothing was changed");
  }
  return dir / p;
}

void CheckCatalogPaths(SqliteDb& db, const fs::path& dir) {
  {
    Statement q(db, "SELECT file FROM frames");
    while (q.Step()) CatalogFile(dir, "frames", q.Text(0), "frames.file");
  }
  Statement q(db, "SELECT name FROM snapshot_files");
  while (q.Step()) CatalogFile(dir, "rig", "rig/" + q.Text(0), "snapshot_files.name");
}

}  // namespace brdfrig::session
