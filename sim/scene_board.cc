#include "sim/scene_board.h"

#include <algorithm>
#include <cmath>

#include "calibrate/target_sheets.h"
#include "common/angles.h"

namespace brdfrig::sim {
namespace {

// 20 samples per millimetre: a tenth of a pixel of the default camera at 0.4 m, so the print
// is as sharp as a laser print is to the camera, and edges land at their exact positions.
constexpr double kPrintPxPerM = 20000;

Eigen::Vector3d ReadVector(const YamlNode& node) {
  const std::vector<double> v = node.AsDoubles();
  if (v.size() != 3) node.Fail("expected [x, y, z]");
  return {v[0], v[1], v[2]};
}

}  // namespace

SceneBoard ParseSceneBoard(const YamlNode& node) {
  SceneBoard board;
  if (auto target = node.Optional("target")) board.spec = calibrate::CharucoSpec::FromYaml(*target);
  if (auto albedo = node.Optional("albedo")) {
    if (auto paper = albedo->Optional("paper")) {
      board.paper_albedo = paper->InRange(paper->AsDouble(), 0, 1);
    }
    if (auto ink = albedo->Optional("ink")) board.ink_albedo = ink->InRange(ink->AsDouble(), 0, 1);
    albedo->Finish();
  }
  if (auto exposure = node.Optional("exposure_s")) {
    board.exposure_s = exposure->Positive(exposure->AsDouble());
  }
  const YamlNode poses = node.Required("poses");
  for (const YamlNode& pose : poses.Elements()) {
    const Eigen::Vector3d center = ReadVector(pose.Required("center"));
    Eigen::Vector3d angles = Eigen::Vector3d::Zero();
    if (auto rotation = pose.Optional("rotation_deg")) angles = ReadVector(*rotation);
    pose.Finish();
    // Face up, top towards +y: page x → world x, page y (down the page) → world −y, into the
    // sheet → world −z; the page's centre at the origin.
    Eigen::Isometry3d face_up = Eigen::Isometry3d::Identity();
    face_up.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    face_up.translation() =
        Eigen::Vector3d(-0.5 * board.spec.page_width_m, 0.5 * board.spec.page_height_m, 0);
    const Eigen::Matrix3d turn = (Eigen::AngleAxisd(Radians(angles.z()), Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(Radians(angles.y()), Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(Radians(angles.x()), Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    Eigen::Isometry3d world_from_page = Eigen::Isometry3d::Identity();
    world_from_page.linear() = turn;
    world_from_page.translation() = center;
    board.world_from_page.push_back(world_from_page * face_up);
  }
  if (board.world_from_page.empty()) poses.Fail("expected at least one pose");
  node.Finish();
  return board;
}

BoardPrint::BoardPrint(const SceneBoard& board)
    : ink_(calibrate::RasterizeCharucoSheet(board.spec, kPrintPxPerM)),
      px_per_m_(kPrintPxPerM),
      width_m_(board.spec.page_width_m),
      height_m_(board.spec.page_height_m),
      paper_(board.paper_albedo),
      ink_albedo_(board.ink_albedo) {}

double BoardPrint::Coverage(double x, double y) const {
  // Bilinear between sample centres (sample (i, j) covers [i, i + 1) / px_per_m).
  const double u = x * px_per_m_ - 0.5, v = y * px_per_m_ - 0.5;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, ink_.cols - 2);
  const int j = std::clamp(static_cast<int>(std::floor(v)), 0, ink_.rows - 2);
  const double fu = std::clamp(u - i, 0.0, 1.0), fv = std::clamp(v - j, 0.0, 1.0);
  const std::uint8_t* row0 = ink_.ptr<std::uint8_t>(j);
  const std::uint8_t* row1 = ink_.ptr<std::uint8_t>(j + 1);
  const double top = row0[i] * (1 - fu) + row0[i + 1] * fu;
  const double bottom = row1[i] * (1 - fu) + row1[i + 1] * fu;
  return (top * (1 - fv) + bottom * fv) / 255.0;
}

double BoardPrint::Albedo(double x, double y) const {
  return paper_ + (ink_albedo_ - paper_) * Coverage(x, y);
}

bool BoardPrint::Ink(double x, double y) const { return Coverage(x, y) >= 0.5; }

}  // namespace brdfrig::sim
