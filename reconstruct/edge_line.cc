#include "reconstruct/edge_line.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "common/option_check.h"

namespace brdfrig::reconstruct {
namespace {

constexpr int kProfileSamples = 256;

float Bilinear(const cv::Mat& image, const cv::Point2d& p) {
  const double x = std::clamp(p.x, 0.0, image.cols - 1.001);
  const double y = std::clamp(p.y, 0.0, image.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const float* r0 = image.ptr<float>(y0);
  const float* r1 = image.ptr<float>(y0 + 1);
  return static_cast<float>((1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
                            fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]));
}

struct Candidate {
  int profile = 0;
  cv::Point2d point;  // undistorted pixels
};

// A profile across the edge: pixel positions, and per channel the radiance and its log.
struct Profile {
  std::array<cv::Point2d, kProfileSamples> pixel;
  std::array<std::array<float, kProfileSamples>, 3> linear, log;
};

// Sub-pixel position of a step by area: an area-sampled edge (and its linear interpolation
// along the profile) holds exactly as much of the left side's light as the left side's extent,
// so the edge lies at the start plus the integral of the left side's fraction. Each side is
// extrapolated linearly (the sample's side is rarely flat: the lobe falls off across it).
// Interpolating to a half level instead would be biased by up to 0.08 px.
double StepPosition(const std::array<float, kProfileSamples>& linear, int best, int reach) {
  const auto side = [&](int near, int far, int j) {
    const double slope = (linear[near] - linear[far]) / (near - far);
    return linear[near] + slope * (j - near);
  };
  const auto left_fraction = [&](int j) {
    const double left = side(best - reach, best - 2 * reach, j);
    const double right = side(best + reach, best + 2 * reach, j);
    if (left == right) return 0.5;
    return std::clamp((linear[j] - right) / (left - right), 0.0, 1.0);
  };
  double crossing = best - reach;
  for (int j = best - reach; j < best + reach; ++j) {
    crossing += 0.5 * (left_fraction(j) + left_fraction(j + 1));
  }
  return crossing;
}

// The clear steps of one profile, strongest first.
void FindSteps(const Profile& profile, const EdgeLineOptions& options,
               const geometry::Intrinsics& undistorted, const geometry::Intrinsics& intrinsics,
               int profile_index, std::vector<Candidate>* out) {
  const double spacing = std::max(cv::norm(profile.pixel[1] - profile.pixel[0]), 1e-6);
  const int reach = std::max(2, static_cast<int>(std::ceil(2.0 / spacing)));  // 2 px
  std::array<double, kProfileSamples> gradient{};
  for (int j = 1; j + 1 < kProfileSamples; ++j) {
    double sum = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = profile.log[c][j + 1] - profile.log[c][j - 1];
      sum += d * d;
    }
    gradient[j] = std::sqrt(sum);
  }
  struct Step {
    double size;
    int at;
    int channel;
  };
  std::vector<Step> steps;
  for (int j = 2 * reach; j + 2 * reach < kProfileSamples; ++j) {
    bool peak = gradient[j] > 0;
    for (int k = j - reach; k <= j + reach && peak; ++k) {
      // Ties go to the first sample so that a flat-topped peak gives one step.
      peak = k == j || (k < j ? gradient[k] < gradient[j] : gradient[k] <= gradient[j]);
    }
    if (!peak) continue;
    double sum = 0, largest = 0;
    int channel = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = profile.log[c][j + reach] - profile.log[c][j - reach];
      sum += d * d;
      if (std::abs(d) > largest) {
        largest = std::abs(d);
        channel = c;
      }
    }
    const double size = std::sqrt(sum);
    if (size >= options.min_log_step) steps.push_back({size, j, channel});
  }
  std::sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) {
    return a.size > b.size || (a.size == b.size && a.at < b.at);
  });
  if (steps.size() > static_cast<std::size_t>(options.max_candidates)) {
    steps.resize(options.max_candidates);
  }
  for (const Step& s : steps) {
    const double crossing = StepPosition(profile.linear[s.channel], s.at, reach);
    const int j0 = std::clamp(static_cast<int>(std::floor(crossing)), 0, kProfileSamples - 2);
    const cv::Point2d p =
        profile.pixel[j0] + (crossing - j0) * (profile.pixel[j0 + 1] - profile.pixel[j0]);
    // Undistort: the ray through the pixel, projected again without distortion.
    cv::Point2d q = p;
    if (intrinsics.k1 != 0 || intrinsics.k2 != 0) {
      const geometry::Vec3 ray =
          geometry::PixelRayInWorld(intrinsics, geometry::CameraPose{}, {p.x, p.y});
      q = {undistorted.fx * ray.x() / ray.z() + undistorted.cx,
           undistorted.fy * ray.y() / ray.z() + undistorted.cy};
    }
    out->push_back({profile_index, q});
  }
}

// Total least squares line through points.
cv::Vec4d FitLine(const std::vector<cv::Point2d>& points) {
  cv::Point2d mean(0, 0);
  for (const auto& p : points) mean += p;
  mean *= 1.0 / static_cast<double>(points.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const auto& p : points) {
    const cv::Point2d d = p - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  return {std::cos(angle), std::sin(angle), mean.x, mean.y};
}

std::vector<cv::Point2d> Inliers(const std::vector<Candidate>& candidates, const cv::Vec4d& line,
                                 double tolerance) {
  std::vector<cv::Point2d> inliers;
  for (const Candidate& c : candidates) {
    if (LineDistance(line, c.point) <= tolerance) inliers.push_back(c.point);
  }
  return inliers;
}

// Profiles with a candidate within `tolerance` of the line: a profile counts once however many
// of its steps lie near the line (the two flanks of a thin dark line are one piece of evidence).
std::size_t Support(const std::vector<Candidate>& candidates, const cv::Vec4d& line,
                    double tolerance) {
  std::size_t n = 0;
  int last = -1;
  for (const Candidate& c : candidates) {  // in profile order
    if (c.profile != last && LineDistance(line, c.point) <= tolerance) {
      ++n;
      last = c.profile;
    }
  }
  return n;
}

// The best-supported line through the candidates close to the nominal direction, refit on its
// inliers by total least squares; false when none has `needed` supporting profiles.
bool BestLine(const std::vector<Candidate>& candidates, const Eigen::Vector2d& nominal_direction,
              std::size_t needed, const EdgeLineOptions& options, EdgeLine* out) {
  if (candidates.size() < needed) return false;
  // RANSAC over pairs from different profiles, seeded: the same image gives the same line.
  std::mt19937 rng(12345);
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  const double min_cos = std::cos(options.max_angle_rad);
  std::size_t best_count = 0;
  cv::Vec4d best;
  for (int iteration = 0; iteration < 400; ++iteration) {
    const Candidate& p = candidates[pick(rng)];
    const Candidate& q = candidates[pick(rng)];
    if (p.profile == q.profile) continue;
    const cv::Point2d d = q.point - p.point;
    const double length = cv::norm(d);
    if (length < 1e-9) continue;
    if (std::abs(d.x * nominal_direction.x() + d.y * nominal_direction.y()) / length < min_cos) {
      continue;
    }
    const cv::Vec4d line(d.x / length, d.y / length, p.point.x, p.point.y);
    const std::size_t n = Support(candidates, line, options.inlier_px);
    if (n > best_count) {
      best_count = n;
      best = line;
    }
  }
  if (best_count < needed) return false;
  // Refit on the inliers, then once more on the refit's inliers.
  std::vector<cv::Point2d> inliers = Inliers(candidates, best, options.inlier_px);
  cv::Vec4d line = best;
  for (int pass = 0; pass < 2 && inliers.size() >= 2; ++pass) {
    line = FitLine(inliers);
    inliers = Inliers(candidates, line, options.inlier_px);
  }
  if (inliers.size() < 2 || Support(candidates, line, options.inlier_px) < needed) return false;
  out->line = FitLine(inliers);
  double sum_sq = 0;
  for (const auto& p : inliers) sum_sq += std::pow(LineDistance(out->line, p), 2);
  out->inliers = static_cast<int>(Support(candidates, out->line, options.inlier_px));
  out->rms_px = std::sqrt(sum_sq / static_cast<double>(inliers.size()));
  return true;
}

}  // namespace

void EdgeLineOptions::Validate() const {
  CheckOption(search_band_m > 0, "EdgeLineOptions.search_band_m", search_band_m, "> 0");
  CheckOption(max_candidates >= 1, "EdgeLineOptions.max_candidates", max_candidates, ">= 1");
  CheckOption(inlier_px > 0, "EdgeLineOptions.inlier_px", inlier_px, "> 0");
  CheckOption(max_lines >= 1, "EdgeLineOptions.max_lines", max_lines, ">= 1");
}

double LineDistance(const cv::Vec4d& line, const cv::Point2d& p) {
  return std::abs((p.x - line[2]) * line[1] - (p.y - line[3]) * line[0]);
}

EdgeImage MakeEdgeImage(const cv::Mat& radiance) {
  EdgeImage image;
  cv::Mat channels[3];
  cv::split(radiance, channels);
  for (int c = 0; c < 3; ++c) {
    // B,G,R in the image; the order does not matter to the profiles.
    const double floor = std::max(cv::mean(channels[c])[0] * 1e-3, 1e-12);
    cv::max(channels[c], floor, image.linear[c]);
    cv::log(image.linear[c], image.log[c]);
  }
  return image;
}

EdgeLines FindEdgeLines(const EdgeImage& image, const geometry::Intrinsics& intrinsics,
                        const geometry::CameraPose& nominal, const geometry::Vec3& a,
                        const geometry::Vec3& b, const EdgeLineOptions& options) {
  options.Validate();
  EdgeLines result;
  geometry::Intrinsics undistorted = intrinsics;
  undistorted.k1 = undistorted.k2 = 0;
  Eigen::Vector2d pa, pb;
  if (!geometry::ProjectToPixel(undistorted, nominal, a, &pa) ||
      !geometry::ProjectToPixel(undistorted, nominal, b, &pb)) {
    return result;
  }
  const Eigen::Vector2d nominal_direction = (pb - pa).normalized();
  const geometry::Vec3 along = (b - a).normalized();
  const geometry::Vec3 across = along.cross(geometry::Vec3::UnitZ()).normalized();
  const int count = std::max(8, static_cast<int>((pb - pa).norm() * (1 - 2 * options.corner_skip) /
                                                 options.profile_step_px));
  const int cols = image.log[0].cols, rows = image.log[0].rows;
  std::vector<Candidate> candidates;
  Profile profile;
  for (int i = 0; i < count; ++i) {
    const double t = options.corner_skip + (1 - 2 * options.corner_skip) * (i + 0.5) / count;
    const geometry::Vec3 on_edge = a + t * (b - a);
    bool inside = true;
    for (int j = 0; j < kProfileSamples && inside; ++j) {
      const double u = options.search_band_m * (2.0 * j / (kProfileSamples - 1) - 1);
      Eigen::Vector2d p;
      inside = geometry::ProjectToPixel(intrinsics, nominal, on_edge + u * across, &p) &&
               p.x() >= 1 && p.y() >= 1 && p.x() <= cols - 2 && p.y() <= rows - 2;
      profile.pixel[j] = {p.x(), p.y()};
    }
    if (!inside) continue;
    for (int j = 0; j < kProfileSamples; ++j) {
      for (int c = 0; c < 3; ++c) {
        profile.linear[c][j] = Bilinear(image.linear[c], profile.pixel[j]);
        profile.log[c][j] = Bilinear(image.log[c], profile.pixel[j]);
      }
    }
    FindSteps(profile, options, undistorted, intrinsics, result.profiles, &candidates);
    ++result.profiles;
  }
  for (const Candidate& c : candidates) result.points.push_back(c.point);
  const std::size_t needed = std::max<std::size_t>(
      4, static_cast<std::size_t>(std::ceil(options.min_inlier_fraction * result.profiles)));
  result.needed = static_cast<int>(needed);
  // Each further line is searched among the steps no earlier line explains (with a margin, so
  // that the blurred flank of a found edge does not come back as a second line).
  EdgeLine line;
  while (static_cast<int>(result.lines.size()) < options.max_lines &&
         BestLine(candidates, nominal_direction, needed, options, &line)) {
    result.lines.push_back(line);
    std::erase_if(candidates, [&](const Candidate& c) {
      return LineDistance(line.line, c.point) <= 2 * options.inlier_px;
    });
  }
  return result;
}

bool IntersectLines(const cv::Vec4d& a, const cv::Vec4d& b, cv::Point2d* crossing) {
  // a: p = (a2,a3) + s (a0,a1); solve for the crossing with b.
  const double det = a[0] * (-b[1]) - a[1] * (-b[0]);
  if (std::abs(det) < 1e-9) return false;
  const double dx = b[2] - a[2], dy = b[3] - a[3];
  const double s = (dx * (-b[1]) - dy * (-b[0])) / det;
  *crossing = {a[2] + s * a[0], a[3] + s * a[1]};
  return true;
}

}  // namespace brdfrig::reconstruct
