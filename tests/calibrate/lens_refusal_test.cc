// What the simulated board photos are, and when the lens calibration refuses them: the board's
// corners lie where the true camera projects the printed corners, and a photo with too few
// corners, a photo out of focus, or corners covering too little of the frame is refused with
// an error naming the photo and the limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

#include "calibrate/board_detection.h"
#include "calibrate/lens_calibration.h"
#include "common/error.h"
#include "geometry/camera.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "tests/calibrate/simulated_board_photos.h"

namespace brdfrig::calibrate {
namespace {

class LensRefusalTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // At 800 x 600: the refusals and the corners' truth do not depend on the pixel count.
    scene_ = new sim::Scene(testing::HalfResolution(sim::LoadScene(testing::ChArUcoScenePath())));
    // Pose 0 as the scene has it, then the board pushed almost out of view.
    sim::Scene edited = *scene_;
    Eigen::Isometry3d off = Eigen::Isometry3d::Identity();
    off.translation() = Eigen::Vector3d(0.23, 0.17, 0);
    edited.board->world_from_page = {scene_->board->world_from_page[0],
                                     off * scene_->board->world_from_page[0]};
    photos_ = new std::vector<CalibrationPhoto>(testing::SimulatedBoardPhotos(edited, {0, 1}));
    // A small board (6 x 5 squares of 10 mm) in the middle of the frame.
    sim::Scene small = *scene_;
    small.board->spec.squares_x = 6;
    small.board->spec.squares_y = 5;
    small.board->spec.square_m = 0.010;
    small.board->spec.marker_m = 0.0075;
    small.board->spec.page_width_m = small.board->spec.page_height_m = 0.1;
    Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
    centre.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    centre.translation() = Eigen::Vector3d(-0.05, 0.05, 0.1);
    small.board->world_from_page = {centre};
    small_ = new sim::Scene(small);
    photos_->push_back(testing::SimulatedBoardPhotos(small, {0}).front());
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete small_;
    delete photos_;
  }
  static std::string Refusal(const std::vector<CalibrationPhoto>& photos,
                             const LensCalibrationOptions& options) {
    try {
      CalibrateLens(photos, options);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  static sim::Scene* scene_;
  static sim::Scene* small_;
  static std::vector<CalibrationPhoto>* photos_;
};

sim::Scene* LensRefusalTest::scene_ = nullptr;
sim::Scene* LensRefusalTest::small_ = nullptr;
std::vector<CalibrationPhoto>* LensRefusalTest::photos_ = nullptr;

TEST_F(LensRefusalTest, BoardCornersAreWhereTheTrueCameraProjectsThePrintedCorners) {
  const BoardDetection d = DetectBoard((*photos_)[0].image, scene_->board->spec, "pose 0");
  ASSERT_EQ(static_cast<int>(d.corners.size()), scene_->board->spec.InnerCorners());
  const sim::TrueGeometry g = sim::Simulator(*scene_).GeometryAt({}, true, 0);
  const auto board = scene_->board->spec.MakeBoard();
  const Eigen::Vector2d origin = scene_->board->spec.OriginOnPage();
  std::vector<double> errors;
  for (std::size_t i = 0; i < d.ids.size(); ++i) {
    const cv::Point3f c = board->chessboardCorners[static_cast<std::size_t>(d.ids[i])];
    const Eigen::Vector3d on_page(origin.x() + c.x, origin.y() + c.y, 0);
    Eigen::Vector2d pixel;
    ASSERT_TRUE(
        geometry::ProjectToPixel(g.intrinsics, g.camera, g.world_from_page * on_page, &pixel));
    errors.push_back((pixel - Eigen::Vector2d(d.corners[i].x, d.corners[i].y)).norm());
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.1) << "median corner error (px)";
  EXPECT_LT(errors.back(), 0.3) << "largest corner error (px)";
}

TEST_F(LensRefusalTest, PhotoWithTooFewBoardCornersIsRefusedByName) {
  LensCalibrationOptions options;
  options.board = scene_->board->spec;
  const std::vector<CalibrationPhoto> photos = {(*photos_)[0], (*photos_)[1], (*photos_)[0],
                                                (*photos_)[0]};
  const std::string error = Refusal(photos, options);
  EXPECT_NE(error.find((*photos_)[1].name), std::string::npos) << error;
  EXPECT_NE(error.find("board corners found"), std::string::npos) << error;
}

TEST_F(LensRefusalTest, BlurredPhotoIsRefusedAsOutOfFocus) {
  LensCalibrationOptions options;
  options.board = scene_->board->spec;
  CalibrationPhoto blurred{"blurred.png", {}};
  cv::GaussianBlur((*photos_)[0].image, blurred.image, cv::Size(), 3.0);
  const BoardDetection sharp = DetectBoard((*photos_)[0].image, options.board, "sharp");
  const BoardDetection soft = DetectBoard(blurred.image, options.board, "blurred");
  EXPECT_LT(sharp.edge_width_px, options.max_edge_width_px);
  EXPECT_GT(soft.edge_width_px, options.max_edge_width_px);
  const std::string error =
      Refusal({(*photos_)[0], blurred, (*photos_)[0], (*photos_)[0]}, options);
  EXPECT_NE(error.find("blurred.png: out of focus"), std::string::npos) << error;
}

TEST_F(LensRefusalTest, SmallBoardCoveringTooLittleOfTheFrameIsRefused) {
  // Four photos of a small board in the middle of the frame: enough corners, sharp, but the
  // lens's edges were never seen.
  LensCalibrationOptions options;
  options.board = small_->board->spec;
  const std::vector<CalibrationPhoto> same(4, (*photos_)[2]);
  const BoardDetection d = DetectBoard(same[0].image, options.board, "small");
  EXPECT_EQ(static_cast<int>(d.corners.size()), options.board.InnerCorners());
  const std::string error = Refusal(same, options);
  EXPECT_NE(error.find("cover only"), std::string::npos) << error;
  // The big board's views cover the frame: accepted with the same thresholds.
  options.board = scene_->board->spec;
  EXPECT_GE(
      FrameCoverage({DetectBoard((*photos_)[0].image, options.board, "0")},
                    (*photos_)[0].image.size(), options.coverage_columns, options.coverage_rows),
      options.min_coverage);
}

TEST_F(LensRefusalTest, TooFewPhotosAreRefused) {
  LensCalibrationOptions options;
  options.board = scene_->board->spec;
  EXPECT_NE(Refusal({(*photos_)[0], (*photos_)[0]}, options).find("at least 4 photos"),
            std::string::npos);
}

}  // namespace
}  // namespace brdfrig::calibrate
