// Reading a finished (or interrupted) session: the stable interface through which the
// reconstruction and every other consumer see a capture. It depends only on the session
// directory: the rig is read from the session's own snapshot, not from the live rig file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"
#include "session/rig_snapshot.h"  // ReadRigSnapshot

namespace brdfrig::session {

// One recorded file. A shot normally gives one file; a camera giving RAW + JPEG gives two
// RecordedFrames with the same position and bracket index.
struct RecordedFrame {
  int position_index = 0;                 // index into SessionContents::planned_positions
  int bracket_index = 0;                  // 0 = first shot of the position's bracket
  geometry::AxisPositions axis_readings;  // axis name -> radians, read back from the drives
  double requested_exposure_s = 0;        // what the plan (or auto-bracketing) asked for
  double exposure_s = 0;                  // what the camera used
  std::filesystem::path file;             // absolute path of the image file
  std::string sha256;                     // lowercase hex of the file's content when recorded
  double saturated_fraction = 0;          // fraction of pixels at full scale (0 when not decoded)
};

struct SessionContents {
  std::filesystem::path dir;
  std::string name;
  std::string sample;
  std::string operator_name;
  std::string software_version;  // BRDFRIG_VERSION of the software that created the session
  std::string notes;
  // "success", "aborted", "failed" (from the last run's stop record), "interrupted" (the last
  // run never stopped: killed, crashed, power cut) or "" (never started).
  std::string exit_status;
  std::string stop_reason;
  std::vector<geometry::AxisPositions> planned_positions;  // radians
  // Per planned position: a validation position (captured, not fitted). Schema 1 sessions
  // have no roles: every position is fitted.
  std::vector<bool> planned_validation;
  // Requested exposures (s) per position: the plan's explicit bracket, or for auto-bracketing
  // the exposures chosen by metering (empty for a position not captured yet).
  std::vector<std::vector<double>> planned_brackets;
  geometry::RigDescription rig;  // from the snapshot in <dir>/rig/
  // Recorded frames ordered by position, bracket, file. A session that is not Complete() may
  // also hold frames of positions its last run left incomplete (a resume discards and redoes
  // them); use only positions whose bracket is all there.
  std::vector<RecordedFrame> frames;

  bool Complete() const;  // every planned position has its bracket recorded
};

// Throws brdfrig::Error when `dir` is not a readable session.
SessionContents ReadSession(const std::filesystem::path& dir);

}  // namespace brdfrig::session
