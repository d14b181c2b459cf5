// `brdfrig session verify DIR`: re-hashes every recorded file and compares the frames folder
// with the catalog, so that a copied or archived session can be trusted (or not).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::session {

struct VerifyReport {
  int checked = 0;                            // recorded files hashed
  std::vector<std::string> missing;           // recorded, but the file is gone
  std::vector<std::string> changed;           // the file's hash differs from the record
  std::vector<std::string> extra;             // in frames/ but never recorded (incl. temporaries)
  std::vector<std::string> snapshot_changed;  // rig snapshot files altered since capture
  bool ok() const {
    return missing.empty() && changed.empty() && extra.empty() && snapshot_changed.empty();
  }
  std::string ToString() const;
};

// Throws brdfrig::Error when `dir` is not a session.
VerifyReport VerifySession(const std::filesystem::path& dir);

}  // namespace brdfrig::session
