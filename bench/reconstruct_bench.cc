// The reconstruction's costs and the HDR merge against OpenCV, in one run:
//   1. HDR merge of three 8-bit exposures (sRGB response) and three 16-bit linear exposures of
//      the default scene, ours vs cv::MergeDebevec: time and error against the simulator's
//      true radiance (after one best scale per channel: HDR is defined up to a scale).
//   2. Time per pipeline stage for the default 6-position × 3-exposure capture.
// Sizes: 2 MP (2000×1000) and, with --large, 24 MP (6000×4000).
//   bench_reconstruct [--large] [--merge-only]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <opencv2/photo.hpp>
#include <regex>
#include <string>

#include "common/atomic_file.h"
#include "reconstruct/batch.h"
#include "reconstruct/hdr_merge.h"
#include "sim/scene.h"
#include "sim/simulate.h"
#include "sim/simulator.h"

namespace {

using namespace brdfrig;
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string SceneText(int width, int height, const std::string& format,
                      const std::string& effects) {
  std::string text = ReadFileToString(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/default.yaml");
  text = std::regex_replace(
      text, std::regex("resolution: \\[1600, 1200\\]"),
      "resolution: [" + std::to_string(width) + ", " + std::to_string(height) + "]");
  text = std::regex_replace(text, std::regex("format: png16"), "format: " + format);
  const auto at = text.find("effects:");
  return text.substr(0, at) + "effects: " + effects + "\n";
}

// Relative RMS error of ln(estimate) against ln(truth) after the best scale per channel, over
// pixels where the truth is above the darkest exposure's floor and `valid` (if given) is set.
double LogError(const cv::Mat& estimate, const cv::Mat& truth) {
  double sum = 0;
  long count = 0;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> ratios;
    for (int y = 0; y < truth.rows; y += 7) {
      for (int x = 0; x < truth.cols; x += 7) {
        const double t = truth.at<cv::Vec3f>(y, x)[c], e = estimate.at<cv::Vec3f>(y, x)[c];
        if (t > 1e-3 && e > 0 && std::isfinite(e)) ratios.push_back(std::log(e / t));
      }
    }
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2),
                     ratios.end());
    const double offset = ratios[ratios.size() / 2];
    for (int y = 0; y < truth.rows; ++y) {
      for (int x = 0; x < truth.cols; ++x) {
        const double t = truth.at<cv::Vec3f>(y, x)[c], e = estimate.at<cv::Vec3f>(y, x)[c];
        if (!(t > 1e-3)) continue;
        const double d = (e > 0 && std::isfinite(e)) ? std::log(e / t) - offset : 5.0;
        sum += d * d;
        ++count;
      }
    }
  }
  return std::sqrt(sum / std::max(count, 1L));
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void MergeComparison(int width, int height, int repeats) {
  const std::vector<double> exposures = {0.001, 0.008, 0.0666667};
  for (const bool eight_bit : {true, false}) {
    const std::string effects =
        eight_bit ? "[{type: shot_noise, full_well: 30000}, {type: saturation, level: 1.0}, "
                    "{type: response_curve, curve: srgb}, {type: quantization, bits: 8}]"
                  : "[{type: shot_noise, full_well: 30000}, {type: saturation, level: 1.0}, "
                    "{type: quantization, bits: 14}]";
    const sim::Simulator simulator(
        sim::LoadSceneString(SceneText(width, height, eight_bit ? "jpeg8" : "png16", effects),
                             "bench.yaml", std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes"));
    const geometry::AxisPositions at = {{"camera_arm", 0.6}, {"light_arm", -0.6}};
    const cv::Mat radiance = simulator.RenderRadiance(at);
    cv::Mat truth = radiance * simulator.scene().sensor.gain;
    std::vector<cv::Mat> images;
    for (std::size_t k = 0; k < exposures.size(); ++k) {
      const cv::Mat sensor = simulator.Expose(radiance, exposures[k], k + 1);
      cv::Mat codes;
      sensor.convertTo(codes, eight_bit ? CV_8UC3 : CV_16UC3, eight_bit ? 255.0 : 65535.0);
      images.push_back(codes);
    }
    std::vector<float> times(exposures.begin(), exposures.end());
    cv::Mat response, opencv_response, ours_hdr, opencv_hdr;
    auto start = Clock::now();
    if (eight_bit) response = reconstruct::RecoverResponse(images, exposures);
    const double calibrate_s = Seconds(start);
    // OpenCV: its own response for 8-bit; a linear one for 16-bit is what MergeDebevec needs,
    // but it accepts only 8-bit images, so the 16-bit case uses the top byte.
    std::vector<cv::Mat> opencv_inputs = images;
    if (eight_bit) {
      cv::createCalibrateDebevec()->process(images, opencv_response, times);
    } else {
      for (cv::Mat& m : opencv_inputs) m.convertTo(m, CV_8UC3, 1.0 / 256);
      opencv_response.create(256, 1, CV_32FC3);
      for (int i = 0; i < 256; ++i)
        opencv_response.at<cv::Vec3f>(i) = cv::Vec3f::all((i + 0.5f) / 256);
    }
    // Median of interleaved repeats: a noisy, shared machine slows both alike.
    reconstruct::HdrImage ours;
    std::vector<double> ours_runs, opencv_runs;
    for (int run = 0; run < repeats; ++run) {
      start = Clock::now();
      // Both merges write into their output of the previous repeat (OpenCV's dst is reused too).
      reconstruct::MergeBracketInto(images, exposures, response, &ours);
      ours_runs.push_back(Seconds(start));
      start = Clock::now();
      cv::createMergeDebevec()->process(opencv_inputs, opencv_hdr, times, opencv_response);
      opencv_runs.push_back(Seconds(start));
    }
    const double ours_s = Median(ours_runs), opencv_s = Median(opencv_runs);
    std::printf("| %4dx%-4d | %-13s | %8.3f | %8.3f | %6.1fx | %8.4f | %8.4f | %6.3f |\n", width,
                height, eight_bit ? "8-bit sRGB" : "14-bit linear", ours_s, opencv_s,
                opencv_s / ours_s, LogError(ours.radiance, truth), LogError(opencv_hdr, truth),
                calibrate_s);
  }
}

void StageTimes(int width, int height) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_bench_stages";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.yaml")
      << SceneText(width, height, "png16",
                   "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
                   "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]");
  // The scene names no files, so it can live anywhere.
  sim::SimulateOptions simulate;
  simulate.scene = dir / "scene.yaml";
  simulate.output_dir = dir / "capture";
  simulate.write_truth = false;
  sim::Simulate(simulate);
  const reconstruct::CaptureSet capture = reconstruct::LoadCapture(dir / "capture");
  const auto start = Clock::now();
  const reconstruct::ReconstructionResult result = reconstruct::Reconstruct(capture, {});
  const double total = Seconds(start);
  std::printf("| %4dx%-4d |", width, height);
  for (const char* stage : {"load", "hdr", "target", "light", "radiometry", "samples", "fit"}) {
    const auto it = result.stage_seconds.find(stage);
    std::printf(" %7.3f |", it == result.stage_seconds.end() ? 0.0 : it->second);
  }
  std::printf(" %7.3f |\n", total);
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  bool large = false, merge_only = false;
  for (int i = 1; i < argc; ++i) {
    large = large || std::strcmp(argv[i], "--large") == 0;
    merge_only = merge_only || std::strcmp(argv[i], "--merge-only") == 0;
  }
  std::vector<std::pair<int, int>> sizes = {{2000, 1000}};
  if (large) sizes.emplace_back(6000, 4000);
  std::printf(
      "HDR merge of 3 exposures: ours (one fused multi-threaded pass) vs cv::MergeDebevec\n");
  std::printf(
      "error = RMS of ln(estimate/truth) after one scale per channel (truth: simulator)\n"
      "times: median of 7 interleaved runs (3 at 24 MP)\n\n");
  std::printf(
      "| size      | input         | ours (s) | OpenCV (s) | speed-up | ours err | OpenCV err | "
      "response (s) |\n");
  std::printf(
      "|-----------|---------------|----------|------------|----------|----------|------------|----"
      "----------|\n");
  for (const auto& [w, h] : sizes) MergeComparison(w, h, w * h > 4000000 ? 3 : 7);
  if (merge_only) return 0;
  std::printf("\nPipeline stages (s), 6 positions × 3 exposures, 14-bit PNG, default scene\n\n");
  std::printf(
      "| size      |    load |     hdr |  target |   light | radiom. | samples |     fit |   total "
      "|\n");
  std::printf(
      "|-----------|---------|---------|---------|---------|---------|---------|---------|---------"
      "|\n");
  for (const auto& [w, h] : sizes) StageTimes(w, h);
  return 0;
}
