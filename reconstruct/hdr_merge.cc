#include "reconstruct/hdr_merge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <type_traits>

#include "common/error.h"
#include "common/exr_io.h"
#include "common/option_check.h"
#include "common/parallel.h"
#include "common/photo_signature.h"
#include "reconstruct/raw_photo.h"

namespace brdfrig::reconstruct {

namespace {

// 8-bit codes: the linear value per channel (the recovered response) and a hat weight on the
// code, whose ends carry little information.
struct CodeTable {
  std::vector<std::array<float, 3>> value;
  std::vector<float> weight;
  CodeTable() = default;
  explicit CodeTable(const cv::Mat& response) : value(256), weight(256) {
    for (int i = 0; i < 256; ++i) {
      for (int c = 0; c < 3; ++c) value[i][c] = response.at<cv::Vec3f>(i, 0)[c];
      weight[i] = static_cast<float>(std::min(i, 255 - i) + 1) / 128.0f;
    }
  }
};

// A code's linear value (1 = full scale) and its weight, per input type.
template <typename T>
struct Decode;
template <>
struct Decode<uchar> {
  const CodeTable& table;
  float Value(uchar code, int c) const { return table.value[code][c]; }
  float Weight(uchar code) const { return table.weight[code]; }
};
template <>
struct Decode<ushort> {
  const CodeTable& table;  // unused: 16-bit codes are linear
  float Value(ushort code, int) const { return code * (1.0f / 65535.0f); }
  float Weight(ushort) const { return 1.0f; }
};
template <>
struct Decode<float> {
  const CodeTable& table;  // unused
  // Float inputs (EXR) are linear already; NaN/Inf fall out through the range checks.
  float Value(float v, int) const { return std::isfinite(v) ? v : -1.0f; }
  float Weight(float) const { return 1.0f; }
};

// One fused pass: for every pixel and channel the inverse-variance weighted mean of S_k / t_k
// over the exposures where S_k is not clipped (8-bit: nor code 0, a JPEG's crushed black, whose
// recovered value says nothing).
template <typename T>
void MergeRows(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s,
               const std::vector<std::size_t>& order, const CodeTable& table,
               const HdrMergeOptions& options, HdrImage* out, std::vector<long>* invalid_per_row) {
  const Decode<T> decode{table};
  const auto saturation = static_cast<float>(options.saturation);
  const auto floor = static_cast<float>(options.read_floor);
  const std::size_t n = order.size();
  std::vector<float> times(n), inverse_times(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = static_cast<float>(exposures_s[order[i]]);
    inverse_times[i] = 1.0f / times[i];
  }
  const int width = out->radiance.cols;
  // Integer codes: every weighted term comes from a table, so the pixel loop has no division
  // and no branch. 8-bit: (exposure, channel, code) → {w·S/t, w}, the hat weight included.
  // 16-bit linear: the value is the same for every channel and exposure, so one shared table
  // per code holds {S/(S+f), 1/(S+f)} (zero when clipped) and the exposure enters as
  // w·S/t = t·S/(S+f) and w = t²/(S+f).
  struct Terms {
    float num = 0, den = 0;
  };
  std::vector<Terms> table8, table16;
  std::vector<float> times_squared(n);
  for (std::size_t i = 0; i < n; ++i) times_squared[i] = times[i] * times[i];
  if constexpr (std::is_same_v<T, uchar>) {
    table8.resize(n * 3 * 256);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        for (int code = 0; code < 256; ++code) {
          const float s = decode.Value(static_cast<T>(code), c);
          if (!(s < saturation) || code == 0) continue;
          const float w = decode.Weight(static_cast<T>(code)) * times_squared[i] / (s + floor);
          table8[(i * 3 + static_cast<std::size_t>(c)) * 256 + code] = {w * s * inverse_times[i],
                                                                        w};
        }
      }
    }
  } else if constexpr (std::is_same_v<T, ushort>) {
    table16.resize(65536);
    for (int code = 0; code < 65536; ++code) {
      const float s = decode.Value(static_cast<T>(code), 0);
      if (!(s < saturation)) continue;
      table16[static_cast<std::size_t>(code)] = {s / (s + floor), 1.0f / (s + floor)};
    }
  }
  // Per row, two passes. The first runs over the row's values as one flat array (x and
  // channel together) with no branch, so the compiler vectorizes it; a value no exposure could
  // measure gets den = 0 and is marked -1. The second, scalar pass handles only those (rare)
  // values and the validity mask.
  ParallelFor(
      static_cast<std::size_t>(out->radiance.rows),
      [&](std::size_t begin, std::size_t end) {
        std::vector<const T*> rows(n);
        const int values = 3 * width;
        for (std::size_t y = begin; y < end; ++y) {
          const int row = static_cast<int>(y);
          for (std::size_t i = 0; i < n; ++i) rows[i] = images[order[i]].ptr<T>(row);
          float* dst = out->radiance.ptr<float>(row);
          if constexpr (std::is_same_v<T, uchar>) {
            // Table lookups do not vectorize; walk pixels so the channel is a constant.
            for (int x = 0; x < width; ++x) {
              for (int c = 0; c < 3; ++c) {
                const int j = 3 * x + c;
                float num = 0, den = 0;
                for (std::size_t i = 0; i < n; ++i) {
                  const Terms& t = table8[(i * 3 + static_cast<std::size_t>(c)) * 256 + rows[i][j]];
                  num += t.num;
                  den += t.den;
                }
                dst[j] = den > 0 ? num / den : -1.0f;
              }
            }
          } else {
            for (int j = 0; j < values; ++j) {
              float num = 0, den = 0;
              for (std::size_t i = 0; i < n; ++i) {
                if constexpr (std::is_same_v<T, ushort>) {
                  const Terms& t = table16[rows[i][j]];
                  num += times[i] * t.num;
                  den += times_squared[i] * t.den;
                } else {
                  // Float (EXR): NaN/Inf fail both comparisons and drop out.
                  const float s = rows[i][j];
                  const bool usable = s < saturation && s >= 0;
                  const float w = usable ? times_squared[i] / (s + floor) : 0.0f;
                  num += w * (usable ? s : 0.0f) * inverse_times[i];
                  den += w;
                }
              }
              dst[j] = den > 0 ? num / den : -1.0f;
            }
          }
          auto* ok = out->valid.ptr<uchar>(row);
          long invalid = 0;
          for (int x = 0; x < width; ++x) {
            bool clipped_everywhere = false;
            for (int c = 0; c < 3; ++c) {
              const int j = 3 * x + c;
              if (dst[j] >= 0) continue;
              const float shortest = decode.Value(rows[0][j], c);
              if (shortest >= saturation || !std::isfinite(static_cast<float>(rows[0][j]))) {
                // Clipped (or not a number) in every exposure: keep a lower bound, flag it.
                clipped_everywhere = true;
                dst[j] = std::max(shortest, 0.0f) * inverse_times[0];
              } else {
                // No usable value (8-bit code 0 or a negative float in every exposure): as dark
                // as the longest exposure can tell.
                dst[j] = std::max(decode.Value(rows[n - 1][j], c), 0.0f) * inverse_times[n - 1];
              }
            }
            ok[x] = clipped_everywhere ? 0 : 255;
            invalid += clipped_everywhere ? 1 : 0;
          }
          (*invalid_per_row)[y] = invalid;
        }
      },
      options.threads);
}

}  // namespace

void HdrMergeOptions::Validate() const {
  CheckOption(saturation > 0 && saturation <= 1, "HdrMergeOptions.saturation", saturation,
              "in (0, 1]");
  CheckOption(read_floor > 0, "HdrMergeOptions.read_floor", read_floor, "> 0");
  CheckOption(noise_floor >= 0 && noise_floor < saturation, "HdrMergeOptions.noise_floor",
              noise_floor, "in [0, saturation)");
}

cv::Mat ReadPhoto(const std::string& path) {
  // EXR through OpenEXR itself (OpenCV's reader is disabled by default in Debian's build).
  if (std::filesystem::path(path).extension() == ".exr") return ReadRadianceExr(path);
  if (IsRawPhoto(path)) return ReadRawPhoto(path);
  {
    std::ifstream in(path, std::ios::binary);
    std::array<std::byte, 8> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    if (!HasPhotoSignature(std::span(head.data(), static_cast<std::size_t>(in.gcount())))) {
      throw FileError(path, "not a PNG, JPEG or TIFF photo (missing, truncated or another format)");
    }
  }
  cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH);
  if (image.empty())
    throw FileError(path, "cannot read photo (missing, truncated or not an image)");
  if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
  // A grey photo used as colour would fit a grey material with nothing saying so.
  if (image.channels() != 3) {
    throw FileError(path, std::to_string(image.channels()) +
                              "-channel (grey) photo: the reconstruction needs colour (RGB) "
                              "photos");
  }
  if (image.depth() == CV_16F || image.depth() == CV_64F) image.convertTo(image, CV_32F);
  if (image.depth() != CV_8U && image.depth() != CV_16U && image.depth() != CV_32F) {
    throw FileError(path, "unsupported photo depth (expected 8 or 16 bits or float per channel)");
  }
  return image;
}

cv::Mat RecoverResponse(const std::vector<cv::Mat>& images,
                        const std::vector<double>& exposures_s) {
  std::vector<float> times(exposures_s.begin(), exposures_s.end());
  cv::Mat response;
  cv::createCalibrateDebevec()->process(images, response, times);
  // Normalize: code 255 → 1 (the response is defined up to a scale).
  const cv::Vec3f top = response.at<cv::Vec3f>(255, 0);
  for (int i = 0; i < 256; ++i) {
    cv::Vec3f& r = response.at<cv::Vec3f>(i, 0);
    for (int c = 0; c < 3; ++c) r[c] /= std::max(top[c], 1e-12f);
  }
  return response;
}

HdrImage MergeBracket(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s,
                      const cv::Mat& response, const HdrMergeOptions& options) {
  HdrImage out;
  MergeBracketInto(images, exposures_s, response, &out, options);
  return out;
}

void MergeBracketInto(const std::vector<cv::Mat>& images, const std::vector<double>& exposures_s,
                      const cv::Mat& response, HdrImage* out_image,
                      const HdrMergeOptions& options) {
  options.Validate();
  HdrImage& out = *out_image;
  if (images.empty() || images.size() != exposures_s.size()) {
    throw Error("HDR merge: need one exposure time per image");
  }
  const cv::Size size = images[0].size();
  const int depth = images[0].depth();
  for (std::size_t k = 0; k < images.size(); ++k) {
    if (images[k].size() != size || images[k].type() != images[0].type() ||
        images[k].channels() != 3) {
      throw Error("HDR merge: exposure " + std::to_string(k) +
                  " differs in size or type from the first (a bracket must be one framing)");
    }
    if (!(exposures_s[k] > 0) || !std::isfinite(exposures_s[k])) {
      throw Error("HDR merge: exposure time " + std::to_string(k) + " must be > 0");
    }
  }
  if (depth == CV_8U && response.rows != 256) {
    throw Error("HDR merge: 8-bit photos need a recovered camera response");
  }
  if (depth != CV_8U && depth != CV_16U && depth != CV_32F) {
    throw Error("HDR merge: photos must be 8-bit, 16-bit or float");
  }
  // Shortest exposure first: its value is the fallback for pixels clipped everywhere.
  std::vector<std::size_t> order(images.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](auto a, auto b) { return exposures_s[a] < exposures_s[b]; });
  out.radiance.create(size, CV_32FC3);  // reuses the buffers when the size is unchanged
  out.valid.create(size, CV_8UC1);
  std::vector<long> invalid_per_row(static_cast<std::size_t>(size.height), 0);
  switch (depth) {
    case CV_8U:
      MergeRows<uchar>(images, exposures_s, order, CodeTable(response), options, &out,
                       &invalid_per_row);
      break;
    case CV_16U:
      MergeRows<ushort>(images, exposures_s, order, {}, options, &out, &invalid_per_row);
      break;
    default:
      MergeRows<float>(images, exposures_s, order, {}, options, &out, &invalid_per_row);
  }
  const long invalid = std::accumulate(invalid_per_row.begin(), invalid_per_row.end(), 0L);
  out.invalid_fraction = static_cast<double>(invalid) / (static_cast<double>(size.area()));
  out.noise_floor = options.noise_floor / exposures_s[order.back()];
}

}  // namespace brdfrig::reconstruct
