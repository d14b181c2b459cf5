// Float RGB images as OpenEXR: HDR radiance written by the reconstruction and the simulator's
// truth, read back by tests and the evaluation. B,G,R in memory (OpenCV's order), R,G,B in the
// file.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

namespace brdfrig {

// Float radiance (CV_32FC3, B,G,R) as an EXR with FLOAT channels R, G, B; written atomically.
void WriteRadianceExr(const std::filesystem::path& path, const cv::Mat& radiance);
// Reads any EXR with R, G, B channels as CV_32FC3, B,G,R. Throws FileError.
cv::Mat ReadRadianceExr(const std::filesystem::path& path);

}  // namespace brdfrig
