// The seed's photo-count analysis and the accuracy-versus-time sweep, on the default scene, and
// the hemisphere study over analytic and measured materials.
//   bench_evaluate_study [photo-count|sweep|materials|all] [--out DIR] [--size WxH]
//   bench_evaluate_study hemisphere [--set analytic|measured|all] [--study-size WxH]
//                        [--measured-dir DIR] [--only SUBSTRING] [--docs DIR]
// Prints markdown tables and writes SVG plots into DIR (default: docs/figures); the hemisphere
// study writes DOCS/hemisphere_study.md and DOCS/figures/hemisphere_study.svg (default DOCS:
// docs/).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/report.h"
#include "evaluate/svg_plot.h"
#include "jobs/material_study.h"
#include "jobs/study.h"

namespace {

using namespace brdfrig;

std::vector<double> Spread(int count, double from, double to) {
  if (count == 1) return {0.5 * (from + to)};
  std::vector<double> v;
  for (int i = 0; i < count; ++i) v.push_back(from + (to - from) * i / (count - 1));
  return v;
}

jobs::StudySettings Base(int width, int height) {
  jobs::StudySettings s;
  s.width = width;
  s.height = height;
  s.position_degrees = Spread(6, 15, 65);
  s.work_dir = std::filesystem::temp_directory_path() / "brdfrig_study";
  return s;
}

void PhotoCount(int width, int height, const std::filesystem::path& out) {
  std::printf("\n## Held-out PSNR against orientation phi, by number of photos (positions)\n\n");
  std::printf(
      "Default scene at %dx%d; positions spread evenly over 15..65 deg; held-out views at "
      "elevation 40 deg, light turned by phi. Each cell: whole photo / sample only (dB).\n\n",
      width, height);
  const std::vector<int> counts = {1, 2, 3, 4, 5, 6, 8};
  std::vector<evaluate::Series> whole, sample;
  bool header = false;
  for (int count : counts) {
    jobs::StudySettings s = Base(width, height);
    s.position_degrees = Spread(count, 15, 65);
    const jobs::StudyResult r = jobs::RunStudyPoint(s);
    if (!header) {
      std::printf("| photos |");
      for (const auto& v : r.views) std::printf(" phi %3.0f |", Degrees(v.view.phi));
      std::printf(" mean | BRDF err | capture (s) | reconstruct (s) |\n|---|");
      for (std::size_t i = 0; i < r.views.size() + 4; ++i) std::printf("---|");
      std::printf("\n");
      header = true;
    }
    std::printf("| %d |", count);
    evaluate::Series w{std::to_string(count) + " photos", {}, {}, true};
    evaluate::Series p = w;
    for (const auto& v : r.views) {
      std::printf(" %s / %s |", Fixed(v.whole_photo.psnr_db, 1).c_str(),
                  Fixed(v.sample_only.psnr_db, 1).c_str());
      w.x.push_back(Degrees(v.view.phi));
      w.y.push_back(v.whole_photo.psnr_db);
      p.x.push_back(Degrees(v.view.phi));
      p.y.push_back(v.sample_only.psnr_db);
    }
    std::printf(" %s / %s | %s | %s | %s |\n", Fixed(r.mean_psnr_whole, 1).c_str(),
                Fixed(r.mean_psnr_sample, 1).c_str(), Fixed(r.brdf_error, 3).c_str(),
                Fixed(r.capture_time_s, 1).c_str(), Fixed(r.reconstruct_time_s, 2).c_str());
    std::fflush(stdout);
    whole.push_back(w);
    sample.push_back(p);
  }
  WriteFileAtomically(out / "photo_count_whole.svg",
                      evaluate::SvgLinePlot(whole, {"Held-out PSNR, whole photo", "phi (degrees)",
                                                    "PSNR (dB)", 640, 400}));
  WriteFileAtomically(out / "photo_count_sample.svg",
                      evaluate::SvgLinePlot(sample, {"Held-out PSNR, sample only", "phi (degrees)",
                                                     "PSNR (dB)", 640, 400}));
}

void Sweep(int width, int height, const std::filesystem::path& out) {
  std::printf("\n## Accuracy against time\n\n");
  std::printf(
      "Default scene; one knob changed at a time from the default (6 positions, 3 "
      "exposures, %dx%d, 0.02 deg bins, spline). Capture time: the rig's virtual clock "
      "(moves + exposures + downloads). PSNR: mean over 7 held-out views.\n\n",
      width, height);
  std::printf(
      "| setting | PSNR whole (dB) | PSNR sample (dB) | BRDF err | capture (s) | "
      "reconstruct (s) |\n|---|---|---|---|---|---|\n");
  struct Point {
    std::string name;
    jobs::StudySettings settings;
  };
  std::vector<Point> points;
  const auto add = [&](const std::string& name, auto change) {
    jobs::StudySettings s = Base(width, height);
    change(s);
    points.push_back({name, s});
  };
  add("default", [](auto&) {});
  add("3 positions", [](auto& s) { s.position_degrees = Spread(3, 15, 65); });
  add("8 positions", [](auto& s) { s.position_degrees = Spread(8, 15, 65); });
  add("1 exposure", [](auto& s) { s.exposures = {0.008}; });
  add("2 exposures", [](auto& s) { s.exposures = {0.001, 0.0666667}; });
  add("half resolution", [&](auto& s) {
    s.width = width / 2;
    s.height = height / 2;
  });
  add("no binning", [](auto& s) { s.bin_width_deg = 0; });
  add("0.2 deg bins", [](auto& s) { s.bin_width_deg = 0.2; });
  add("5 fit iterations", [](auto& s) { s.fit_iterations = 5; });
  add("linear interpolation", [](auto& s) { s.linear_interpolation = true; });
  evaluate::Series frontier{"settings", {}, {}, false};
  for (const Point& p : points) {
    const jobs::StudyResult r = jobs::RunStudyPoint(p.settings);
    std::printf("| %s | %s | %s | %s | %s | %s |\n", p.name.c_str(),
                Fixed(r.mean_psnr_whole, 2).c_str(), Fixed(r.mean_psnr_sample, 2).c_str(),
                Fixed(r.brdf_error, 3).c_str(), Fixed(r.capture_time_s, 1).c_str(),
                Fixed(r.reconstruct_time_s, 2).c_str());
    std::fflush(stdout);
    frontier.x.push_back(r.capture_time_s + r.reconstruct_time_s);
    frontier.y.push_back(r.mean_psnr_sample);
  }
  WriteFileAtomically(out / "accuracy_time.svg",
                      evaluate::SvgLinePlot(
                          {frontier}, {"Accuracy against time", "capture + reconstruction time (s)",
                                       "mean held-out PSNR, sample only (dB)", 640, 400}));
}

// The reconstruction on analytic samples under realistic sensors: how far the seed's model
// gets on materials it was not made from.
void Materials(int width, int height) {
  std::printf("\n## Analytic samples under realistic sensors\n\n");
  std::printf(
      "Default rig at %dx%d, 6 positions (15..65 deg), 3 exposures. 14-bit: shot + read noise, "
      "saturation, 14-bit linear PNG. 8-bit: shot + read noise, saturation, sRGB response, "
      "8-bit JPEG-like codes. PSNR: mean over 7 held-out views (whole photo / sample only); "
      "BRDF err: log-cosine error against the true BRDF.\n\n",
      width, height);
  std::printf(
      "| sample | sensor | PSNR whole (dB) | PSNR sample (dB) | BRDF err | slices |\n"
      "|---|---|---|---|---|---|\n");
  const std::vector<std::pair<std::string, std::string>> samples = {
      {"GGX alpha 0.05",
       "{model: ggx, alpha: 0.05, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}"},
      {"GGX alpha 0.1",
       "{model: ggx, alpha: 0.1, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}"},
      {"GGX alpha 0.3",
       "{model: ggx, alpha: 0.3, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}"},
      {"Cook-Torrance alpha 0.15",
       "{model: cook_torrance, alpha: 0.15, f0: 0.5, diffuse: [0.2, 0.1, 0.05]}"},
      {"Ward alpha 0.15", "{model: ward, alpha: 0.15, specular: 0.3, diffuse: [0.15, 0.2, 0.3]}"},
      {"Lambert + Blinn-Phong n=200",
       "{model: blinn_phong, exponent: 200, specular: 0.5, diffuse: [0.4, 0.3, 0.2]}"},
  };
  const std::vector<std::tuple<std::string, std::string, std::string>> sensors = {
      {"14-bit", "png16",
       "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
       "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]"},
      {"8-bit sRGB", "jpeg8",
       "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
       "{type: saturation, level: 1.0}, {type: response_curve, curve: srgb}]"},
  };
  for (const auto& [name, brdf] : samples) {
    for (const auto& [sensor, format, effects] : sensors) {
      jobs::StudySettings s = Base(width, height);
      s.sample_brdf = brdf;
      s.sensor_format = format;
      s.effects = effects;
      try {
        const jobs::StudyResult r = jobs::RunStudyPoint(s);
        std::printf("| %s | %s | %s | %s | %s | %d |\n", name.c_str(), sensor.c_str(),
                    Fixed(r.mean_psnr_whole, 2).c_str(), Fixed(r.mean_psnr_sample, 2).c_str(),
                    Fixed(r.brdf_error, 3).c_str(), r.slices);
      } catch (const Error& e) {
        std::printf("| %s | %s | failed: %s | | | |\n", name.c_str(), sensor.c_str(), e.what());
      }
      std::fflush(stdout);
    }
  }
}

// Every material of the set on today's mirror plan, every figure: the baseline the model work
// is judged against.
void Hemisphere(const std::string& set, const std::string& only, int width, int height,
                const std::filesystem::path& measured_dir, const std::filesystem::path& docs) {
  std::vector<jobs::StudyMaterial> materials;
  if (set == "analytic" || set == "all") materials = jobs::AnalyticStudyMaterials();
  if (set == "measured" || set == "all") {
    const auto measured = jobs::MeasuredStudyMaterials(measured_dir);
    if (measured.empty()) {
      std::printf("(no measured materials in %s)\n", measured_dir.string().c_str());
    }
    materials.insert(materials.end(), measured.begin(), measured.end());
  }
  if (!only.empty()) {
    std::erase_if(materials, [&](const auto& m) { return m.name.find(only) == std::string::npos; });
  }
  const jobs::StudyPlan plan = jobs::MirrorPlan();
  jobs::MaterialStudyOptions options;
  options.width = width;
  options.height = height;
  options.work_dir = std::filesystem::temp_directory_path() / "brdfrig_hemisphere_study";
  std::printf("\n## Hemisphere study (%zu materials, %dx%d, supersampling %d)\n\n",
              materials.size(), width, height, options.supersampling);
  std::vector<jobs::MaterialStudyRow> rows;
  for (const auto& material : materials) {
    rows.push_back(jobs::RunMaterialStudyPoint(material, plan, options));
    std::printf("%s (%.1f s)\n", rows.back().Report().c_str(), rows.back().wall_s);
    std::fflush(stdout);
  }
  const std::string table = jobs::MarkdownTable(rows, plan);
  std::printf("\n%s\nsummary: %s\n", table.c_str(), jobs::Summarize(rows).Report().c_str());
  std::filesystem::create_directories(docs / "figures");
  WriteFileAtomically(
      docs / "hemisphere_study.md",
      "# Hemisphere study (generated by `bench_evaluate_study hemisphere`)\n\nSeed model, " +
          std::to_string(width) + "x" + std::to_string(height) +
          " px captures. Sphere: mean over lights and per light (orthographic sphere, truth's "
          "99th percentile = 1, clamped, sRGB, PSNR). Held-out: normalized sample PSNR (peak = "
          "truth's 99th percentile of the view's sample radiance), mean over light azimuths "
          "per elevation, and the lowest view. Albedo err: max over channels of the relative "
          "directional-albedo error. BRDF err: log-cosine error.\n\n" +
          table);
  WriteFileAtomically(docs / "figures" / "hemisphere_study.svg",
                      jobs::StudyPlot(rows, "Hemisphere study, " + plan.name));
}

}  // namespace

int main(int argc, char** argv) {
  std::string mode = "all";
  std::filesystem::path out = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "docs/figures";
  int width = 800, height = 600;
  int study_width = 400, study_height = 300;
  std::string set = "analytic", only;
  std::filesystem::path docs = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "docs";
  std::filesystem::path measured_dir =
      std::filesystem::path(BRDFRIG_SOURCE_DIR) / "data/materials/nbrdf";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      out = argv[++i];
    } else if (std::strcmp(argv[i], "--size") == 0 && i + 1 < argc) {
      std::sscanf(argv[++i], "%dx%d", &width, &height);
    } else if (std::strcmp(argv[i], "--study-size") == 0 && i + 1 < argc) {
      std::sscanf(argv[++i], "%dx%d", &study_width, &study_height);
    } else if (std::strcmp(argv[i], "--set") == 0 && i + 1 < argc) {
      set = argv[++i];
    } else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else if (std::strcmp(argv[i], "--docs") == 0 && i + 1 < argc) {
      docs = argv[++i];
    } else if (std::strcmp(argv[i], "--measured-dir") == 0 && i + 1 < argc) {
      measured_dir = argv[++i];
    } else {
      mode = argv[i];
    }
  }
  std::filesystem::create_directories(out);
  if (mode == "photo-count" || mode == "all") PhotoCount(width, height, out);
  if (mode == "sweep" || mode == "all") Sweep(width, height, out);
  if (mode == "materials" || mode == "all") Materials(width, height);
  if (mode == "hemisphere") Hemisphere(set, only, study_width, study_height, measured_dir, docs);
  return 0;
}
