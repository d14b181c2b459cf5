// The reconstruction's costs and the HDR merge against OpenCV, in one run:
//   1. HDR merge of three 8-bit exposures (sRGB response) and three 16-bit linear exposures of
//      the default scene, ours vs cv::MergeDebevec: time and error against the simulator's
//      true radiance (after one best scale per channel: HDR is defined up to a scale).
//   2. The full reconstruction of the default capture (sim/scenes/default.yaml as it is:
//      1600×1200, its designed 6 positions × 3 exposures, every rung, the choice, the glTF
//      version): wall and CPU time per stage, per rung (final fit and its leave-one-position-out
//      folds), the chosen rung and its sphere PSNR against the scene's true material (the
//      figure a speed-up must not lower). CPU seconds are the process's (every thread): on a
//      shared machine they move much less than wall time.
// --large adds 24 MP (6000×4000) to the merge and a 24 MP capture of the same scene.
//   bench_reconstruct [--large] [--merge-only] [--stages-only] [--repeat N] [--capture DIR]
// --capture DIR: simulate the default capture into DIR once and reuse it on later runs (the
// simulation is not part of the figure; it takes longer than the reconstruction).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <opencv2/photo.hpp>
#include <regex>
#include <string>

#include "brdf/material_file.h"
#include "brdf/sphere_figure.h"
#include "common/atomic_file.h"
#include "common/median.h"
#include "common/parallel.h"
#include "common/sha256.h"
#include "reconstruct/batch.h"
#include "reconstruct/hdr_merge.h"
#include "reconstruct/stage_timer.h"
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

// The default scene's capture at `width`×`height` (its own 1600×1200: the scene file as it is),
// simulated into `dir` unless a capture is already there.
void SimulateDefaultCapture(int width, int height, const std::filesystem::path& dir) {
  if (std::filesystem::exists(dir / "capture" / "photos" / "capture.json")) return;
  std::filesystem::create_directories(dir);
  const std::filesystem::path scenes = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "sim/scenes";
  sim::SimulateOptions simulate;
  if (width == 1600 && height == 1200) {
    simulate.scene = scenes / "default.yaml";
  } else {
    std::ofstream(dir / "scene.yaml")
        << SceneText(width, height, "png16",
                     "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
                     "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]");
    simulate.scene = dir / "scene.yaml";  // the scene names no files: it can live anywhere
  }
  simulate.output_dir = dir / "capture";
  simulate.write_truth = false;
  const auto start = Clock::now();
  sim::Simulate(simulate);
  std::printf("(simulated %dx%d into %s in %.1f s)\n", width, height, dir.string().c_str(),
              Seconds(start));
}

struct Run {
  reconstruct::ReconstructionResult result;
  double wall = 0, cpu = 0;
};

void StageTimes(int width, int height, std::filesystem::path dir, int repeats) {
  const bool keep = !dir.empty();
  if (!keep) {
    dir = std::filesystem::temp_directory_path() /
          ("brdfrig_bench_stages_" + std::to_string(width) + "x" + std::to_string(height));
    std::filesystem::remove_all(dir);
  }
  SimulateDefaultCapture(width, height, dir);
  const reconstruct::CaptureSet capture = reconstruct::LoadCapture(dir / "capture");
  // The median run by wall time: the machine is shared.
  std::vector<Run> runs;
  for (int r = 0; r < repeats; ++r) {
    Run run;
    const auto start = Clock::now();
    const double cpu_start = reconstruct::ProcessCpuSeconds();
    run.result = reconstruct::Reconstruct(capture, {});
    run.wall = Seconds(start);
    run.cpu = reconstruct::ProcessCpuSeconds() - cpu_start;
    runs.push_back(std::move(run));
  }
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.wall < b.wall; });
  const Run& run = runs[runs.size() / 2];
  const reconstruct::ReconstructionResult& result = run.result;
  std::printf(
      "\nFull reconstruction of the default capture at %dx%d: %zu positions, %zu "
      "photos, every rung, the choice, the glTF version (median of %d)\n\n",
      width, height, capture.positions.size(),
      capture.positions.empty() ? 0 : capture.positions.size() * capture.positions[0].frames.size(),
      repeats);
  const auto stage = [&](const char* name, double* wall, double* cpu) {
    const auto w = result.stage_seconds.find(name);
    const auto c = result.stage_cpu_seconds.find(name);
    *wall = w == result.stage_seconds.end() ? 0.0 : w->second;
    *cpu = c == result.stage_cpu_seconds.end() ? 0.0 : c->second;
  };
  std::printf("| stage | wall (s) | CPU (s) |\n|---|---:|---:|\n");
  double wall_sum = 0, cpu_sum = 0, wall = 0, cpu = 0;
  stage("measure", &wall, &cpu);
  std::printf("| measure (every position, %d threads) | %.3f | %.3f |\n", DefaultThreadCount(),
              wall, cpu);
  wall_sum += wall;
  cpu_sum += cpu;
  // Within it, summed over positions: positions are measured side by side, so these walls add
  // up to more than the measure stage's, and their CPU is the measuring threads' own.
  for (const char* name : {"load", "hdr", "target", "light", "radiometry", "samples"}) {
    stage(name, &wall, &cpu);
    std::printf("| &nbsp;&nbsp;%s (summed over positions) | %.3f | %.3f |\n", name, wall, cpu);
  }
  for (const char* name : {"fit", "gltf"}) {
    stage(name, &wall, &cpu);
    wall_sum += wall;
    cpu_sum += cpu;
    std::printf("| %s | %.3f | %.3f |\n", name, wall, cpu);
  }
  std::printf("| other | %.3f | %.3f |\n", run.wall - wall_sum, run.cpu - cpu_sum);
  std::printf("| **total** | **%.3f** | **%.3f** |\n", run.wall, run.cpu);

  const sim::Scene scene =
      sim::LoadScene(keep || (width == 1600 && height == 1200)
                         ? std::filesystem::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml"
                         : dir / "scene.yaml");
  const reconstruct::LadderResult& ladder = result.ladder;
  double final_cpu = 0, fold_cpu = 0;
  for (const reconstruct::RungResult& rung : ladder.rungs) {
    final_cpu += rung.fit_cpu_seconds;
    fold_cpu += rung.fold_cpu_seconds;
  }
  std::printf(
      "\nThe fit stage per rung (CPU of the fits on every position %.3f s, of the %zu "
      "leave-one-position-out folds %.3f s; the fits run on %d threads at once); sphere PSNR "
      "against the scene's material\n\n",
      final_cpu, ladder.rungs.empty() ? 0 : ladder.rungs[0].fold_scores.size(), fold_cpu,
      DefaultThreadCount());
  std::printf(
      "| rung | fit wall (s) | fit CPU (s) | folds CPU (s) | score | sphere (dB) |\n"
      "|---|---:|---:|---:|---:|---:|\n");
  for (const reconstruct::RungResult& rung : ladder.rungs) {
    const double psnr =
        rung.fitted ? brdf::SpherePsnr(*scene.sample.brdf, *rung.material.Model()).mean_psnr_db
                    : 0.0;
    std::printf("| %s%s | %.3f | %.3f | %.3f | %.4f | %.2f |\n", brdf::ModelKindName(rung.kind),
                rung.chosen ? " (chosen)" : "", rung.fit_seconds, rung.fit_cpu_seconds,
                rung.fold_cpu_seconds, rung.score, psnr);
  }
  // The figures a speed-up must leave alone, to compare runs: every fold's score, and a hash of
  // the material that is written (equal hashes: the same bytes).
  for (const reconstruct::RungResult& rung : ladder.rungs) {
    std::printf("%s folds:", brdf::ModelKindName(rung.kind));
    for (double score : rung.fold_scores) std::printf(" %.6f", score);
    std::printf("\n");
  }
  std::printf("material.json sha256 %s\n",
              Sha256Hex(brdf::SerializeMaterial(result.material)).substr(0, 16).c_str());
  const brdf::SphereFigure chosen = brdf::SpherePsnr(*scene.sample.brdf, *result.material.Model());
  std::printf(
      "\nchosen rung: %s, sphere PSNR %.2f dB (worst light %.2f dB); glTF version %s dB "
      "against the rung\n",
      brdf::ModelKindName(result.material.kind), chosen.mean_psnr_db, chosen.worst_psnr_db,
      result.material.gltf_fit["sphere_vs_model"]["mean_psnr_db"].dump().c_str());
  std::printf("every run (wall s / CPU s):");
  for (const Run& r : runs) std::printf(" %.2f/%.2f", r.wall, r.cpu);
  std::printf("\n");
  if (!keep) std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  bool large = false, merge_only = false, stages_only = false;
  int repeats = 1;
  std::filesystem::path capture_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--large") {
      large = true;
    } else if (arg == "--merge-only") {
      merge_only = true;
    } else if (arg == "--stages-only") {
      stages_only = true;
    } else if (arg == "--repeat" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--capture" && i + 1 < argc) {
      capture_dir = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_reconstruct [--large] [--merge-only] [--stages-only] "
                   "[--repeat N] [--capture DIR]\n");
      return 2;
    }
  }
  if (!stages_only) {
    std::vector<std::pair<int, int>> sizes = {{2000, 1000}};
    if (large) sizes.emplace_back(6000, 4000);
    std::printf(
        "HDR merge of 3 exposures: ours (one fused multi-threaded pass) vs cv::MergeDebevec\n");
    std::printf(
        "error = RMS of ln(estimate/truth) after one scale per channel (truth: simulator)\n"
        "times: median of 7 interleaved runs (3 at 24 MP)\n\n");
    std::printf(
        "| size      | input         | ours (s) | OpenCV (s) | speed-up | ours err | OpenCV err "
        "| response (s) |\n");
    std::printf(
        "|-----------|---------------|----------|------------|----------|----------|-----------"
        "-|--------------|\n");
    for (const auto& [w, h] : sizes) MergeComparison(w, h, w * h > 4000000 ? 3 : 7);
    if (merge_only) return 0;
  }
  StageTimes(1600, 1200, capture_dir, repeats);
  if (large) StageTimes(6000, 4000, {}, 1);
  return 0;
}
