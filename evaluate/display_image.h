// Radiance images turned into pictures a person looks at (reports, `brdfrig render -o x.png`).
// Display only: measurements use the float images.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

namespace brdfrig::evaluate {

// The scale that maps the 99.5th percentile of the image's values to 1 (so a highlight may
// clip, the rest stays visible). Shared by images shown side by side.
double AutoDisplayScale(const cv::Mat& radiance);

// 8-bit sRGB picture of scale × radiance (clipped to [0, 1]); CV_8UC3, same channel order.
cv::Mat ToDisplay8(const cv::Mat& radiance, double scale);

// |a − b| scaled for display (same scale as the images it is shown with).
cv::Mat DifferenceImage(const cv::Mat& a, const cv::Mat& b);

// Writes .exr (float radiance) or .png/.jpg (display picture, auto scale). Throws on failure.
void WriteImageFile(const std::filesystem::path& path, const cv::Mat& radiance);

}  // namespace brdfrig::evaluate
