// A session's copy of its rig configuration (<session>/rig/): the rig file, the file holding
// its geometry, and the scene files its simulated devices name. It makes a session readable on
// its own (the reconstruction takes the nominal geometry from here, never from the live rig
// file) and lets a resume notice that the rig configuration changed in between.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::session {

struct SnapshotFile {
  std::string name;  // file name under <session>/rig/
  std::string role;  // "rig", "geometry" or "scene"
  std::filesystem::path original;
  std::string sha256;
};

// Copies the files into <session_dir>/rig/ (durably) and returns what it copied, for the
// catalog's snapshot_files table. The rig file is always rig/rig.yaml.
std::vector<SnapshotFile> WriteRigSnapshot(const std::filesystem::path& session_dir,
                                           const geometry::RigDescription& rig);

// The rig description saved in a session (geometry parsed from the snapshot). Throws
// brdfrig::Error / FileError when the snapshot is missing or malformed.
geometry::RigDescription ReadRigSnapshot(const std::filesystem::path& session_dir);

// Which of the live rig's files (rig file, geometry file) differ from the session's snapshot:
// one line per changed file; empty when none did.
std::vector<std::string> RigChangesSince(const std::filesystem::path& session_dir,
                                         const geometry::RigDescription& rig);

}  // namespace brdfrig::session
