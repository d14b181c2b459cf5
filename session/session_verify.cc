#include "session/session_verify.h"

#include <set>
#include <sstream>

#include "common/sha256.h"
#include "session/catalog_checks.h"
#include "session/sqlite_db.h"

namespace brdfrig::session {

namespace fs = std::filesystem;

VerifyReport VerifySession(const fs::path& dir) {
  if (!fs::exists(dir / "session.sqlite")) {
    throw Error("'" + dir.string() + "' is not a session (no session.sqlite)");
  }
  SqliteDb db(dir / "session.sqlite", SqliteDb::Mode::kReadOnly);
  CheckSchemaVersion(db, dir);
  CheckCatalogPaths(db, dir);  // never hash (or name) a file outside the session
  VerifyReport report;
  std::set<std::string> recorded;
  {
    Statement q(db, "SELECT file, sha256 FROM frames ORDER BY id");
    while (q.Step()) {
      const std::string rel = q.Text(0);
      recorded.insert(rel);
      ++report.checked;
      if (!fs::exists(dir / rel)) {
        report.missing.push_back(rel);
      } else if (Sha256FileHex(dir / rel) != q.Text(1)) {
        report.changed.push_back(rel);
      }
    }
  }
  if (fs::is_directory(dir / "frames")) {
    for (const auto& entry : fs::directory_iterator(dir / "frames")) {
      const std::string rel = "frames/" + entry.path().filename().string();
      if (!recorded.count(rel)) report.extra.push_back(rel);
    }
  }
  {
    Statement q(db, "SELECT name, sha256 FROM snapshot_files");
    while (q.Step()) {
      const fs::path file = dir / "rig" / q.Text(0);
      if (!fs::exists(file) || Sha256FileHex(file) != q.Text(1)) {
        report.snapshot_changed.push_back("rig/" + q.Text(0));
      }
    }
  }
  return report;
}

std::string VerifyReport::ToString() const {
  std::ostringstream out;
  for (const std::string& f : missing) out << "missing: " << f << "\n";
  for (const std::string& f : changed) out << "changed: " << f << "\n";
  for (const std::string& f : extra) out << "extra: " << f << "\n";
  for (const std::string& f : snapshot_changed) out << "snapshot changed: " << f << "\n";
  out << checked << " recorded files checked: "
      << (ok() ? "OK"
               : std::to_string(missing.size()) + " missing, " + std::to_string(changed.size()) +
                     " changed, " + std::to_string(extra.size()) + " extra, " +
                     std::to_string(snapshot_changed.size()) + " snapshot files changed")
      << "\n";
  return out.str();
}

}  // namespace brdfrig::session
