#include "calibrate/linear_grey.h"

#include <algorithm>

namespace brdfrig::calibrate {

cv::Mat LinearGrey(const cv::Mat& photo) {
  double full_scale = 1.0;
  if (photo.depth() == CV_8U) full_scale = 255.0;
  if (photo.depth() == CV_16U) full_scale = 65535.0;
  cv::Mat values;
  photo.convertTo(values, CV_32F, 1.0 / full_scale);
  if (values.channels() == 1) return values;
  // Colour channels only: a fourth channel is alpha.
  const int colours = std::min(values.channels(), 3);
  cv::Mat weights(1, values.channels(), CV_32F, cv::Scalar(0));
  weights(cv::Rect(0, 0, colours, 1)).setTo(1.0 / colours);
  cv::Mat grey;
  cv::transform(values, grey, weights);
  return grey;
}

}  // namespace brdfrig::calibrate
