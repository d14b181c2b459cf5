#include "acquire/auto_bracket.h"

#include <algorithm>
#include <cmath>

namespace brdfrig::acquire {
namespace {

// The metering shot's level at a point of the sample plane (nominal geometry); false when the
// point falls outside the image.
bool LevelAt(const cv::Mat& levels, const geometry::RigGeometry& g,
             const geometry::CameraPose& pose, double x, double y, float* level) {
  Eigen::Vector2d pixel;
  if (!geometry::ProjectToPixel(g.intrinsics, pose, geometry::Vec3(x, y, 0), &pixel)) return false;
  const int u = static_cast<int>(std::lround(pixel.x() * levels.cols / g.intrinsics.width));
  const int v = static_cast<int>(std::lround(pixel.y() * levels.rows / g.intrinsics.height));
  if (u < 0 || v < 0 || u >= levels.cols || v >= levels.rows) return false;
  *level = levels.at<float>(v, u);
  return true;
}

// Paper levels on a ring halfway between the cut-out and the paper's outer edge.
std::vector<float> PaperSamples(const cv::Mat& levels, const geometry::RigGeometry& g,
                                const geometry::AxisPositions& axes) {
  std::vector<float> samples;
  const geometry::CameraPose pose = g.CameraAt(axes);
  const double hx = 0.25 * (g.target.cutout_width + g.target.paper_width);
  const double hy = 0.25 * (g.target.cutout_height + g.target.paper_height);
  for (int i = 0; i < 32; ++i) {
    const double t = 2 * M_PI * i / 32;
    // A point on the rectangle of half-sizes (hx, hy) in direction t.
    const double c = std::cos(t), s = std::sin(t);
    const double k = 1.0 / std::max(std::abs(c) / hx, std::abs(s) / hy);
    float level = 0;
    if (LevelAt(levels, g, pose, k * c, k * s, &level)) samples.push_back(level);
  }
  return samples;
}

// Sample levels on a 9 × 9 grid over the inner 80 % of the cut-out (its edges stay clear of
// the paper however the nominal geometry is off).
std::vector<float> CutoutSamples(const cv::Mat& levels, const geometry::RigGeometry& g,
                                 const geometry::AxisPositions& axes) {
  std::vector<float> samples;
  const geometry::CameraPose pose = g.CameraAt(axes);
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      const double x = 0.4 * g.target.cutout_width * (i / 4.0 - 1);
      const double y = 0.4 * g.target.cutout_height * (j / 4.0 - 1);
      float level = 0;
      if (LevelAt(levels, g, pose, x, y, &level)) samples.push_back(level);
    }
  }
  return samples;
}

}  // namespace

MeteringResult ChooseBracket(const cv::Mat& levels, double metering_exposure_s,
                             const geometry::RigGeometry& geometry,
                             const geometry::AxisPositions& axes, const AutoBracket& settings) {
  MeteringResult result;
  double max_level = 0;
  cv::minMaxLoc(levels, nullptr, &max_level);
  result.highlight_level = max_level;
  if (max_level >= 0.98) {
    result.remeter_at_s = metering_exposure_s / 8;  // three stops down, then look again
    return result;
  }
  std::vector<float> paper = PaperSamples(levels, geometry, axes);
  if (paper.empty()) paper.assign(levels.begin<float>(), levels.end<float>());
  std::nth_element(paper.begin(), paper.begin() + paper.size() / 2, paper.end());
  result.paper_level = std::max(1e-6, static_cast<double>(paper[paper.size() / 2]));
  // Linear sensor: level scales with exposure.
  const double shortest = metering_exposure_s * settings.highlight_max / std::max(max_level, 1e-6);
  double longest = metering_exposure_s * settings.paper_level / result.paper_level;
  std::vector<float> sample = CutoutSamples(levels, geometry, axes);
  if (!sample.empty()) {
    std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
    // A sample too dark for the metering shot to see reads as (nearly) zero: it then needs
    // the longest exposure there is.
    result.sample_level = std::max(1e-9, static_cast<double>(sample[sample.size() / 2]));
    const double sample_longest = metering_exposure_s * settings.sample_level / result.sample_level;
    if (sample_longest > settings.longest_max_s) result.sample_needs_s = sample_longest;
    longest = std::max(longest, std::min(sample_longest, settings.longest_max_s));
  }
  const int n = settings.count;
  // Keep the bracket at least one stop apart so it still spans a useful range.
  longest = std::max(longest, shortest * std::pow(2.0, n - 1));
  for (int i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
    result.bracket_s.push_back(shortest * std::pow(longest / shortest, f));
  }
  return result;
}

}  // namespace brdfrig::acquire
