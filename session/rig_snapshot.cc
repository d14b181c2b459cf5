#include "session/rig_snapshot.h"

#include <algorithm>
#include <set>

#include "common/atomic_file.h"
#include "common/sha256.h"
#include "common/yaml_reader.h"
#include "geometry/rig_calibration.h"
#include "session/sqlite_db.h"

namespace brdfrig::session {
namespace {

namespace fs = std::filesystem;

// Files referenced by `scene:` keys of the rig's devices (the simulator's scene), so that a
// session records the world it was captured in.
std::vector<fs::path> SceneFiles(const fs::path& rig_file) {
  std::vector<fs::path> files;
  try {
    const YAML::Node root = YAML::LoadFile(rig_file.string());
    auto add = [&](const YAML::Node& device) {
      if (device.IsMap() && device["scene"] && device["scene"].IsScalar()) {
        fs::path p = device["scene"].as<std::string>();
        if (p.is_relative()) p = rig_file.parent_path() / p;
        files.push_back(p);
      }
    };
    for (const char* key : {"camera", "light"}) {
      if (root[key]) add(root[key]);
    }
    if (root["axes"] && root["axes"].IsMap()) {
      for (const auto& item : root["axes"]) add(item.second);
    }
  } catch (const YAML::Exception&) {
    // The rig file was already validated by ReadRigDescription; nothing more to add.
  }
  return files;
}

// The snapshot's file name for a role, from the catalog.
std::string SnapshotName(SqliteDb& db, const std::string& role) {
  Statement q(db, "SELECT name FROM snapshot_files WHERE role = ?1 ORDER BY name LIMIT 1");
  q.Bind(1, role);
  return q.Step() ? q.Text(0) : std::string();
}

}  // namespace

std::vector<SnapshotFile> WriteRigSnapshot(const fs::path& session_dir,
                                           const geometry::RigDescription& rig) {
  std::vector<SnapshotFile> files;
  std::set<std::string> seen;
  auto add = [&](const fs::path& original, const std::string& role, std::string name) {
    std::error_code ec;
    if (!seen.insert(fs::weakly_canonical(original, ec).string()).second) return;
    // Two files with one name (rig.yaml in two folders): the later one gets a prefix.
    while (std::any_of(files.begin(), files.end(),
                       [&](const SnapshotFile& f) { return f.name == name; })) {
      name = "_" + name;
    }
    files.push_back({name, role, fs::absolute(original), ""});
  };
  add(rig.file, "rig", "rig.yaml");
  for (std::size_t i = 1; i < rig.source_files.size(); ++i) {
    add(rig.source_files[i], "geometry", rig.source_files[i].filename().string());
  }
  for (const geometry::CalibrationKind& kind : geometry::kCalibrationKinds) {
    const fs::path& file = rig.calibration.*kind.file;
    if (!file.empty()) add(file, kind.snapshot_role, file.filename().string());
  }
  for (const fs::path& scene : SceneFiles(rig.file)) {
    if (fs::exists(scene)) add(scene, "scene", scene.filename().string());
  }
  fs::create_directories(session_dir / "rig");
  for (SnapshotFile& f : files) {
    const std::string content = ReadFileToString(f.original);
    WriteFileAtomically(session_dir / "rig" / f.name, content);
    f.sha256 = Sha256Hex(content);
  }
  SyncDirectory(session_dir / "rig");
  return files;
}

geometry::RigDescription ReadRigSnapshot(const fs::path& session_dir) {
  const fs::path rig_dir = session_dir / "rig";
  const fs::path rig_file = rig_dir / "rig.yaml";
  geometry::RigDescription description;
  description.file = rig_file;
  description.source_files.push_back(rig_file);
  const YamlNode root = LoadYamlFile(rig_file.string());
  const YamlNode geometry = root.Required("geometry");
  SqliteDb db(session_dir / "session.sqlite", SqliteDb::Mode::kReadOnly);
  // The calibrations the rig referenced at capture time, from the snapshot's own copies.
  auto apply_calibration = [&] {
    const auto calibration = root.Optional("calibration");
    if (!calibration) return;
    geometry::RigCalibrationFiles& files = description.calibration;
    for (const geometry::CalibrationKind& kind : geometry::kCalibrationKinds) {
      if (!calibration->Optional(kind.key)) continue;
      const std::string name = SnapshotName(db, kind.snapshot_role);
      if (name.empty() || !fs::exists(rig_dir / name)) {
        calibration->Fail(std::string("the session's rig snapshot lacks the ") + kind.key +
                          " calibration");
      }
      files.*kind.file = rig_dir / name;
    }
    const std::string model = root.Required("camera").Get("model", std::string());
    geometry::ApplyRigCalibration(files, model, &description.geometry);
  };
  if (!geometry.IsScalar()) {
    description.geometry = geometry::ParseRigGeometry(geometry);
    apply_calibration();
    return description;
  }
  const std::string name = SnapshotName(db, "geometry");
  const fs::path geometry_file = rig_dir / (name.empty() ? "rig.yaml" : name);
  if (name.empty() || !fs::exists(geometry_file)) {
    geometry.Fail("the session's rig snapshot lacks the geometry file");
  }
  description.geometry =
      geometry::ParseRigGeometry(LoadYamlFile(geometry_file.string()).Required("rig"));
  description.source_files.push_back(geometry_file);
  apply_calibration();
  return description;
}

std::vector<std::string> RigChangesSince(const fs::path& session_dir,
                                         const geometry::RigDescription& rig) {
  std::vector<std::string> changes;
  SqliteDb db(session_dir / "session.sqlite", SqliteDb::Mode::kReadOnly);
  auto compare = [&](const fs::path& live, const std::string& role) {
    Statement q(db, "SELECT sha256 FROM snapshot_files WHERE role = ?1 ORDER BY name LIMIT 1");
    q.Bind(1, role);
    if (!q.Step()) {
      changes.push_back(live.string() + ": not part of the session's snapshot");
    } else if (Sha256FileHex(live) != q.Text(0)) {
      changes.push_back(live.string() +
                        " changed since the session started (the session keeps "
                        "the original in rig/)");
    }
  };
  compare(rig.file, "rig");
  if (rig.source_files.size() > 1) compare(rig.source_files[1], "geometry");
  for (const geometry::CalibrationKind& kind : geometry::kCalibrationKinds) {
    const fs::path& file = rig.calibration.*kind.file;
    if (!file.empty()) compare(file, kind.snapshot_role);
  }
  return changes;
}

}  // namespace brdfrig::session
