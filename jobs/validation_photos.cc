#include "jobs/validation_photos.h"

#include <algorithm>
#include <cfloat>
#include <opencv2/imgproc.hpp>

#include "common/angles.h"
#include "common/error.h"
#include "reconstruct/predict_photo.h"

namespace brdfrig::jobs {
namespace {

// The photo's radiance and the prediction inside the mask's bounding box, zero elsewhere: the
// report shows the sample, not the whole frame.
void KeepImages(const cv::Mat& photo, const cv::Mat& prediction, const cv::Mat& mask,
                evaluate::ValidationPhotoResult* r) {
  const cv::Rect box = cv::boundingRect(mask);
  r->photo = cv::Mat(box.size(), CV_32FC3, cv::Scalar::all(0));
  r->prediction = cv::Mat(box.size(), CV_32FC3, cv::Scalar::all(0));
  photo(box).copyTo(r->photo, mask(box));
  prediction(box).copyTo(r->prediction, mask(box));
}

}  // namespace

void ValidationPhotoOptions::Validate() const {
  measure.hdr.Validate();
  measure.target.Validate();
  measure.light.Validate();
  measure.light_refine.Validate();
  measure.radiometry.Validate();
  measure.samples.Validate();
  measure.directions.Validate();
  measure.fit.Validate();
}

std::vector<int> ValidationPositionsOf(const reconstruct::CaptureSet& capture,
                                       const ValidationPhotoOptions& options) {
  std::vector<int> out;
  if (options.positions.empty()) {
    for (const reconstruct::CapturePosition& p : capture.positions) {
      if (p.validation) out.push_back(p.index);
    }
    if (out.empty()) {
      throw OptionsError(capture.name +
                         ": the capture has no validation positions (its plan marks none with "
                         "`validation: true`): name the positions to compare with --positions "
                         "i,j (they should be positions the material was not fitted to)");
    }
    return out;
  }
  std::string available;
  for (const reconstruct::CapturePosition& p : capture.positions) {
    available += (available.empty() ? "" : ", ") + std::to_string(p.index);
  }
  for (int index : options.positions) {
    const bool found = std::any_of(capture.positions.begin(), capture.positions.end(),
                                   [&](const auto& p) { return p.index == index; });
    if (!found) {
      throw OptionsError(capture.name + ": position " + std::to_string(index) +
                         " is not in the capture (its positions: " + available + ")");
    }
  }
  return options.positions;
}

std::vector<evaluate::ValidationPhotoResult> CompareValidationPhotos(
    const reconstruct::CaptureSet& capture, const brdf::Brdf& material,
    const ValidationPhotoOptions& options, const std::function<void(const std::string&)>& say) {
  options.Validate();
  const std::vector<int> wanted = ValidationPositionsOf(capture, options);
  reconstruct::MeasureState state;
  std::vector<evaluate::ValidationPhotoResult> results;
  for (const reconstruct::CapturePosition& position : capture.positions) {
    if (std::find(wanted.begin(), wanted.end(), position.index) == wanted.end()) continue;
    const std::string name = reconstruct::PositionName(position.index);
    if (say) say(name + ": measuring the validation photo");
    evaluate::ValidationPhotoResult r;
    r.position = position.index;
    try {
      const reconstruct::MeasuredPosition measured =
          reconstruct::MeasurePosition(position, capture.nominal, options.measure, &state);
      const reconstruct::PlaneView view(capture.nominal.intrinsics, measured.pose);
      const reconstruct::PositionReport& report = measured.report;
      reconstruct::PredictedSample predicted = reconstruct::PredictSampleRadiance(
          material, state.hdr.valid, view, report.light.position, report.radiometry,
          capture.nominal.target, options.measure.samples);
      // Pixels the merge left non-finite are no measurement (NaN compares false).
      cv::Mat channels[3];
      cv::split(state.hdr.radiance, channels);
      for (const cv::Mat& c : channels) predicted.mask &= cv::abs(c) <= FLT_MAX;
      r.figures = evaluate::CompareSampleRadiance(state.hdr.radiance, predicted.radiance,
                                                  predicted.mask, "photo");
      r.theta_in_deg = Degrees(report.theta_in);
      r.light = report.light.Source();
      r.measured = true;
      if (options.keep_images) {
        KeepImages(state.hdr.radiance, predicted.radiance, predicted.mask, &r);
      }
    } catch (const Error& e) {
      r.error = e.what();
      if (say) say(name + ": not measured: " + r.error);
    }
    results.push_back(std::move(r));
  }
  if (std::none_of(results.begin(), results.end(), [](const auto& r) { return r.measured; })) {
    std::string reasons;
    for (const auto& r : results) {
      reasons += "\n  " + reconstruct::PositionName(r.position) + ": " + r.error;
    }
    throw Error(capture.name + ": no validation photo could be measured:" + reasons);
  }
  return results;
}

}  // namespace brdfrig::jobs
