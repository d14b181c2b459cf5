#include "sim/scene_board.h"

#include <algorithm>
#include <cmath>

#include "calibrate/target_sheets.h"
#include "common/angles.h"

namespace brdfrig::sim {
namespace {

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

SheetPrint PrintOfBoard(const SceneBoard& board) {
  return SheetPrint(calibrate::RasterizeCharucoSheet(board.spec, kPrintPxPerM), kPrintPxPerM,
                    board.spec.page_width_m, board.spec.page_height_m, board.paper_albedo,
                    board.ink_albedo);
}

}  // namespace brdfrig::sim
