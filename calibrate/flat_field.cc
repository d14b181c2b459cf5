#include "calibrate/flat_field.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "calibrate/linear_grey.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "common/option_check.h"
#include "common/utc_time.h"

namespace brdfrig::calibrate {
namespace {

double Median(const cv::Mat& image) {
  std::vector<float> v(image.begin<float>(), image.end<float>());
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Monomials u^i v^j, i + j <= degree, at normalized coordinates (the image centre at 0, the
// half width at 1), which keeps the normal equations well conditioned.
void Monomials(double u, double v, int degree, double* out) {
  int k = 0;
  double ui = 1;
  for (int i = 0; i <= degree; ++i, ui *= u) {
    double vj = 1;
    for (int j = 0; i + j <= degree; ++j, vj *= v) out[k++] = ui * vj;
  }
}

}  // namespace

void FlatFieldOptions::Validate() const {
  CheckOption(degree >= 2 && degree <= 10, "FlatFieldOptions.degree", degree, "in 2..10");
  CheckOption(min_signal > 0 && min_signal < 1, "FlatFieldOptions.min_signal", min_signal,
              "in (0, 1)");
  CheckOption(max_clipped >= 0 && max_clipped < 1, "FlatFieldOptions.max_clipped", max_clipped,
              "in [0, 1)");
  CheckOption(max_fit_rms > 0, "FlatFieldOptions.max_fit_rms", max_fit_rms, "> 0");
  CheckOption(stride >= 1, "FlatFieldOptions.stride", stride, ">= 1");
}

std::string FlatFieldResult::ToString() const {
  std::ostringstream out;
  out << "flat field from " << photos << " photos, " << gain.cols << "x" << gain.rows << ": gain "
      << min_gain << " .. " << max_gain << " (mean 1), photos about the fit " << 100 * fit_rms
      << " % RMS";
  return out.str();
}

FlatFieldResult CalibrateFlatField(const std::vector<CalibrationPhoto>& photos,
                                   const FlatFieldOptions& options) {
  options.Validate();
  if (photos.empty()) throw Error("flat field: no photos");
  const cv::Size size = photos.front().image.size();
  cv::Mat sum = cv::Mat::zeros(size, CV_32F);
  for (const CalibrationPhoto& photo : photos) {
    if (photo.image.size() != size) {
      throw Error(photo.name + ": not the size of " + photos.front().name +
                  ": one flat field is of one camera at one image size");
    }
    const cv::Mat grey = LinearGrey(photo.image);
    const double clipped = cv::countNonZero(grey >= 0.999f) / static_cast<double>(grey.total());
    if (clipped > options.max_clipped) {
      throw Error(photo.name + ": overexposed (" + std::to_string(100 * clipped) +
                  " % of the pixels at full scale): shorten the exposure");
    }
    const double median = Median(grey);
    if (median < options.min_signal) {
      throw Error(photo.name + ": underexposed (median " + std::to_string(100 * median) +
                  " % of full scale, at least " + std::to_string(100 * options.min_signal) +
                  " % needed): lengthen the exposure");
    }
    sum += grey / median;  // each photo at its own level: exposures may differ
  }
  const cv::Mat mean = sum / static_cast<double>(photos.size());

  // Least squares on a grid of pixels: photo ≈ Σ c_k m_k(u, v).
  const int terms = (options.degree + 1) * (options.degree + 2) / 2;
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  const double scale = 0.5 * size.width;
  std::vector<double> m(static_cast<std::size_t>(terms));
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(terms, terms);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(terms);
  for (int y = options.stride / 2; y < size.height; y += options.stride) {
    for (int x = options.stride / 2; x < size.width; x += options.stride) {
      Monomials((x - cx) / scale, (y - cy) / scale, options.degree, m.data());
      const Eigen::Map<const Eigen::VectorXd> row(m.data(), terms);
      normal.noalias() += row * row.transpose();
      rhs += row * mean.at<float>(y, x);
    }
  }
  const Eigen::VectorXd c = normal.ldlt().solve(rhs);

  FlatFieldResult result;
  result.photos = static_cast<int>(photos.size());
  result.gain.create(size, CV_32F);
  double squares = 0;
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      Monomials((x - cx) / scale, (y - cy) / scale, options.degree, m.data());
      const double fit = Eigen::Map<const Eigen::VectorXd>(m.data(), terms).dot(c);
      result.gain.at<float>(y, x) = static_cast<float>(fit);
      const double r = mean.at<float>(y, x) / fit - 1;
      squares += r * r;
    }
  }
  result.fit_rms = std::sqrt(squares / static_cast<double>(size.area()));
  if (!(result.fit_rms <= options.max_fit_rms)) {
    throw Error("the photos depart from a smooth field by " + std::to_string(100 * result.fit_rms) +
                " % RMS (at most " + std::to_string(100 * options.max_fit_rms) +
                " %): the card is not uniform, not evenly lit or does not fill the frame");
  }
  result.gain /= cv::mean(result.gain)[0];
  cv::minMaxLoc(result.gain, &result.min_gain, &result.max_gain);
  if (!(result.min_gain > 0)) throw Error("flat field: the fitted gain is not positive everywhere");
  return result;
}

void WriteFlatField(const std::string& path, const FlatFieldResult& result,
                    const std::vector<CalibrationPhoto>& photos) {
  cv::Mat three;
  cv::merge(std::vector<cv::Mat>{result.gain, result.gain, result.gain}, three);
  WriteRadianceExr(path, three);
  nlohmann::json names = nlohmann::json::array();
  for (const CalibrationPhoto& p : photos) names.push_back(p.name);
  const nlohmann::json j = {{"format", "brdfrig-flat-field"},
                            {"version", 1},
                            {"created", NowUtcIso8601()},
                            {"software", std::string("brdfrig ") + BRDFRIG_VERSION},
                            {"gain_map", std::filesystem::path(path).filename().string()},
                            {"size", {result.gain.cols, result.gain.rows}},
                            {"photos", names},
                            {"fit_rms", result.fit_rms},
                            {"min_gain", result.min_gain},
                            {"max_gain", result.max_gain},
                            {"normalization", "mean 1"}};
  WriteFileAtomically(path + ".json", j.dump(2) + "\n");
}

}  // namespace brdfrig::calibrate
