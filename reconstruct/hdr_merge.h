// Merging a bracket into one linear radiance image.
//
// Linear inputs (16-bit PNG/TIFF from a linear sensor, RAW): each exposure gives S_k / t_k; the
// estimates are averaged with inverse-variance weights w_k = t_k² / (S_k + read_floor) (shot
// noise grows with S, read noise does not), skipping clipped (S >= saturation) values. A dark
// value, even 0, is kept: it is the longest exposure's measurement of a dark surface, and
// dropping it would leave the pixel to a shorter exposure's noise, larger by the exposure
// ratio and, once the zeros are gone, all positive (a black sample read several times too bright).
// Non-linear inputs (8-bit JPEG): the camera response is recovered once (Debevec–Malik, OpenCV's
// CalibrateDebevec), then the same merge runs on the linearized values with a hat weight on the
// code value. A pixel clipped in every exposure is invalid: it keeps the lower bound S_min / t_min
// as its value and is flagged, never guessed. One fused pass over the inputs, rows split across
// threads.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace brdfrig::reconstruct {

struct HdrMergeOptions {
  double saturation = 0.98;  // linear value (1 = full scale) at and above which a value is clipped
  double read_floor = 2e-3;  // read-noise floor in the weight (full-scale units)
  // Full-scale level below which the longest exposure's values are mostly read noise
  // (HdrImage::noise_floor): twice the read noise of the simulated 14-bit sensor (σ 5e-4), about
  // 2 % above the truth for a mean of values clipped at zero there. Halving it from 2e-3 gained
  // 4 dB on four dark measured materials (bench_model_ceiling); a camera with a known read noise
  // σ sets 2σ.
  double noise_floor = 1e-3;
  int threads = 0;  // 0 = all hardware threads
  void Validate() const;
};

struct HdrImage {
  cv::Mat radiance;  // CV_32FC3, B,G,R, relative units (sensor full scale per second)
  cv::Mat valid;     // CV_8UC1, 255 where at least one exposure was usable
  double invalid_fraction = 0;
  // Radiance of HdrMergeOptions::noise_floor in the longest exposure. Below it a value is mostly
  // read noise, and photos written without a black level clip that noise at zero, so even a mean
  // over many pixels stays biased upwards (up to 0.4 σ for a black surface): a sample that dark is
  // no measurement (direction_samples.h).
  double noise_floor = 0;
};

// `images`: CV_16UC3 or CV_32FC3 (linear; float from EXR, where NaN/Inf count as clipped) or
// CV_8UC3 (with `response`), all the same size.
// `response`: for 8-bit inputs, the linear value of each code (CV_32FC3 of 256×1, from
// RecoverResponse); empty for linear inputs. Throws brdfrig::Error on inconsistent inputs.
HdrImage MergeBracket(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s,
                      const cv::Mat& response, const HdrMergeOptions& options = {});

// The same merge into `out`, reusing its buffers when they already have the right size: the
// output is ~13 bytes per pixel, and faulting in fresh pages for it costs as much as the merge.
void MergeBracketInto(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s,
                      const cv::Mat& response, HdrImage* out, const HdrMergeOptions& options = {});

// Debevec–Malik response recovery from one or more 8-bit brackets (OpenCV CalibrateDebevec),
// normalized so that code 255 maps to about 1.
cv::Mat RecoverResponse(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s);

// Reads photos (PNG, TIFF, JPEG, EXR, camera RAW through LibRaw) keeping their bit depth; throws
// FileError for unreadable files and for grey (single-channel) photos.
cv::Mat ReadPhoto(const std::string& path);

}  // namespace brdfrig::reconstruct
