#include "session/session_reader.h"

#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "common/error.h"
#include "common/json_parse.h"
#include "common/yaml_reader.h"
#include "session/catalog_checks.h"
#include "session/rig_snapshot.h"
#include "session/sqlite_db.h"

namespace brdfrig::session {
namespace {

namespace fs = std::filesystem;

// A JSON cell of the catalog, converted by `convert`; a cell that is not JSON, or not the JSON
// this version writes, is an error naming the catalog and the cell (the catalog is input like
// any file: a damaged or edited one must not end in an internal error).
template <typename Convert>
auto FromJsonCell(const fs::path& catalog, const std::string& cell, const std::string& text,
                  Convert convert) {
  std::string problem;
  try {
    return convert(ParseJson(text, cell));
  } catch (const nlohmann::json::exception& e) {
    problem = e.what();
  } catch (const FileError& e) {  // not JSON, or nested too deep
    problem = e.what();
  }
  throw FileError(catalog.string(), cell + " holds '" + text.substr(0, 80) +
                                        "', not what this version writes (" + problem + ")");
}

// {"axis": radians, ...}; anything else throws a json type_error.
geometry::AxisPositions AxesFromJson(const nlohmann::json& j) {
  geometry::AxisPositions axes;
  for (const auto& [name, value] : j.get<std::map<std::string, double>>()) axes[name] = value;
  return axes;
}

}  // namespace

bool SessionContents::Complete() const {
  std::map<int, int> shots;
  for (const RecordedFrame& f : frames)
    shots[f.position_index] = std::max(shots[f.position_index], f.bracket_index + 1);
  for (std::size_t p = 0; p < planned_positions.size(); ++p) {
    const int want = p < planned_brackets.size() ? static_cast<int>(planned_brackets[p].size()) : 0;
    if (want == 0 || shots[static_cast<int>(p)] != want) return false;
  }
  return true;
}

SessionContents ReadSession(const fs::path& dir) {
  const fs::path db_file = dir / "session.sqlite";
  if (!fs::exists(db_file))
    throw Error("'" + dir.string() + "' is not a session (no session.sqlite)");
  SqliteDb db(db_file, SqliteDb::Mode::kReadOnly);
  CheckSchemaVersion(db, dir);
  CheckCatalogPaths(db, dir);
  SessionContents s;
  s.dir = fs::absolute(dir);
  bool auto_bracket = false;
  std::vector<double> explicit_bracket;
  {
    Statement q(db,
                "SELECT name, sample, operator, notes, software_version, positions_json, "
                "exposures_json FROM session");
    if (!q.Step()) throw Error("'" + dir.string() + "' has no start record");
    s.name = q.Text(0);
    s.sample = q.Text(1);
    s.operator_name = q.Text(2);
    s.notes = q.Text(3);
    s.software_version = q.Text(4);
    s.planned_positions =
        FromJsonCell(db_file, "session.positions_json", q.Text(5), [](const nlohmann::json& j) {
          std::vector<geometry::AxisPositions> positions;
          for (const nlohmann::json& p : j.get<std::vector<nlohmann::json>>()) {
            positions.push_back(AxesFromJson(p));
          }
          return positions;
        });
    FromJsonCell(db_file, "session.exposures_json", q.Text(6), [&](const nlohmann::json& j) {
      auto_bracket = j.is_string();
      if (!auto_bracket) explicit_bracket = j.get<std::vector<double>>();
      return 0;
    });
  }
  s.planned_validation.assign(s.planned_positions.size(), false);
  {
    // Schema 2 records the validation positions in meta; schema 1 sessions have no such row.
    Statement q(db, "SELECT value FROM meta WHERE key = 'validation_positions'");
    if (q.Step()) {
      const auto indices =
          FromJsonCell(db_file, "meta.validation_positions", q.Text(0),
                       [](const nlohmann::json& j) { return j.get<std::vector<int>>(); });
      for (const int index : indices) {
        if (index >= 0 && index < static_cast<int>(s.planned_validation.size())) {
          s.planned_validation[static_cast<std::size_t>(index)] = true;
        }
      }
    }
  }
  {
    Statement q(db, "SELECT exit_status, reason, stopped_at FROM runs ORDER BY id DESC LIMIT 1");
    if (q.Step()) {
      s.exit_status = q.IsNull(2) ? "interrupted" : q.Text(0);
      s.stop_reason = q.Text(1);
    }
  }
  std::set<int> complete;
  {
    Statement q(db, "SELECT position_index FROM positions");
    while (q.Step()) complete.insert(static_cast<int>(q.Int(0)));
  }
  s.planned_brackets.assign(s.planned_positions.size(),
                            auto_bracket ? std::vector<double>() : explicit_bracket);
  {
    Statement q(db,
                "SELECT position_index, bracket_index, axis_readings_json, requested_exposure_s, "
                "exposure_s, file, sha256, saturated_fraction, file_index FROM frames "
                "ORDER BY position_index, bracket_index, file_index");
    while (q.Step()) {
      RecordedFrame f;
      f.position_index = static_cast<int>(q.Int(0));
      f.bracket_index = static_cast<int>(q.Int(1));
      f.axis_readings = FromJsonCell(db_file, "frames.axis_readings_json", q.Text(2), AxesFromJson);
      f.requested_exposure_s = q.Double(3);
      f.exposure_s = q.Double(4);
      f.file = CatalogFile(s.dir, "frames", q.Text(5), "frames.file");
      f.sha256 = q.Text(6);
      f.saturated_fraction = q.Double(7);
      // Auto-bracketing decides a bracket when its position is captured; only a complete
      // position's bracket is known for sure.
      if (auto_bracket && q.Int(8) == 0 && complete.count(f.position_index) &&
          f.position_index >= 0 && f.position_index < static_cast<int>(s.planned_brackets.size())) {
        s.planned_brackets[f.position_index].push_back(f.requested_exposure_s);
      }
      s.frames.push_back(std::move(f));
    }
  }
  s.rig = ReadRigSnapshot(dir);
  return s;
}

}  // namespace brdfrig::session
