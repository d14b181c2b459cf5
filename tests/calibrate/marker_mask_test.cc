// The marker mask: a ring of markers around the cut-out, on the paper, apart from each other,
// and printed where the layout (targets.json) says: ArUco finds each at its corners.
#include "calibrate/marker_mask.h"

#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>
#include <set>

#include "calibrate/target_sheets.h"
#include "common/error.h"

namespace brdfrig::calibrate {
namespace {

TEST(MarkerMaskTest, MarkersRingTheCutOutOnThePaperApartFromEachOther) {
  geometry::TargetGeometry target;  // 100 mm cut-out, 300 mm paper
  const MarkerMaskSpec spec = MarkerMaskSpec::ForTarget(target);
  spec.Validate();
  const std::vector<MaskMarker> markers = MaskMarkers(spec);
  ASSERT_GE(markers.size(), 12u);
  std::set<int> ids;
  for (const MaskMarker& m : markers) {
    ids.insert(m.id);
    const double x0 = m.corners[0].x(), x1 = m.corners[1].x();
    const double y0 = m.corners[2].y(), y1 = m.corners[0].y();  // bottom, top
    EXPECT_NEAR(x1 - x0, spec.marker_m, 1e-12);
    EXPECT_NEAR(y1 - y0, spec.marker_m, 1e-12);
    // Outside the cut-out by at least the gap, inside the paper.
    const bool beside = x0 >= 0.5 * spec.cutout_width_m + spec.gap_m - 1e-12 ||
                        x1 <= -0.5 * spec.cutout_width_m - spec.gap_m + 1e-12;
    const bool above_or_below = y0 >= 0.5 * spec.cutout_height_m + spec.gap_m - 1e-12 ||
                                y1 <= -0.5 * spec.cutout_height_m - spec.gap_m + 1e-12;
    EXPECT_TRUE(beside || above_or_below) << "marker " << m.id;
    EXPECT_LT(std::max(std::abs(x0), std::abs(x1)), 0.5 * spec.paper_width_m);
    EXPECT_LT(std::max(std::abs(y0), std::abs(y1)), 0.5 * spec.paper_height_m);
  }
  EXPECT_EQ(ids.size(), markers.size());
  for (std::size_t i = 0; i < markers.size(); ++i) {
    for (std::size_t j = i + 1; j < markers.size(); ++j) {
      const Eigen::Vector2d d = (markers[i].corners[0] - markers[j].corners[0]).cwiseAbs();
      EXPECT_TRUE(d.x() >= spec.marker_m + spec.spacing_m - 1e-9 ||
                  d.y() >= spec.marker_m + spec.spacing_m - 1e-9)
          << "markers " << markers[i].id << " and " << markers[j].id << " too close";
    }
  }
}

TEST(MarkerMaskTest, PrintedMarkersAreFoundAtTheirLayoutCorners) {
  const MarkerMaskSpec spec = MarkerMaskSpec::ForTarget(geometry::TargetGeometry{});
  const double px_per_m = 4000;  // 4 px/mm: a 20 mm marker is 80 px
  const cv::Mat ink = RasterizeMaskSheet(spec, px_per_m);
  const cv::Mat photo = 255 - ink;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(photo, DictionaryNamed(spec.dictionary), corners, ids);
  const std::vector<MaskMarker> markers = MaskMarkers(spec);
  ASSERT_EQ(ids.size(), markers.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const MaskMarker& m = markers.at(static_cast<std::size_t>(ids[i] - spec.first_id));
    ASSERT_EQ(m.id, ids[i]);
    for (int c = 0; c < 4; ++c) {
      // Mask coordinates to pixels (centres at integers): world +y is up the page.
      const double u = (m.corners[c].x() + 0.5 * spec.paper_width_m) * px_per_m - 0.5;
      const double v = (0.5 * spec.paper_height_m - m.corners[c].y()) * px_per_m - 0.5;
      EXPECT_NEAR(corners[i][c].x, u, 1.0) << "marker " << m.id << " corner " << c;
      EXPECT_NEAR(corners[i][c].y, v, 1.0) << "marker " << m.id << " corner " << c;
    }
  }
}

TEST(MarkerMaskTest, MaskThatDoesNotFitItsPaperIsRefused) {
  geometry::TargetGeometry target;
  target.cutout_width = 0.25;  // the ring would run off a 300 mm sheet
  EXPECT_THROW(MarkerMaskSpec::ForTarget(target).Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::calibrate
