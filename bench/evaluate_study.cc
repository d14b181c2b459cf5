// The seed's photo-count analysis and the accuracy-versus-time sweep, on the default scene, and
// the hemisphere study over analytic and measured materials.
//   bench_evaluate_study [photo-count|sweep|materials|all] [--out DIR] [--size WxH]
//   bench_evaluate_study hemisphere [--set analytic|measured|all] [--study-size WxH]
//                        [--measured-dir DIR] [--only SUBSTRING] [--docs DIR]
//                        [--plan mirror|designed] [--positions N] [--model KIND]
//                        [--materials NAME,NAME,...] [--name NAME] [--albedo-goal X]
//                        [--brdf-only] [--keep-materials DIR] [--jobs N]
//   bench_evaluate_study photo-count-rungs [--counts 1,2,3,...] [--materials ...] [--set ...]
// Prints markdown tables and writes SVG plots into DIR (default: docs/figures); the hemisphere
// study writes DOCS/NAME.md and DOCS/figures/NAME.svg (default DOCS: docs/, NAME:
// study_hemisphere; photo-count-rungs: photo_count_study). Without --model the hemisphere study
// judges every rung of the ladder side by side; --model seed is the issue-13 baseline.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <map>
#include <mutex>
#include <optional>
#include "brdf/nbrdf_library.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "common/parallel.h"
#include "evaluate/report.h"
#include "evaluate/svg_plot.h"
#include "jobs/material_study.h"
#include "jobs/study.h"
#include "prior/build_prior.h"

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

struct HemisphereArgs {
  std::string set = "analytic", only, plan = "mirror", model, name = "study_hemisphere";
  std::vector<std::string> materials;  // exact names (empty: the whole set)
  std::vector<int> counts = {1, 2, 3, 4, 6, 8, 12};
  int positions = 6;
  int jobs = 1;  // materials judged at once (each mostly on one core); the table keeps the order
  bool brdf_only = false;                // sphere test and BRDF figures only (no held-out views)
  std::filesystem::path keep_materials;  // keep each reconstructed material.json here
  int width = 400, height = 300;
  double albedo_goal = 0;  // 0: 0.05 for the analytic set, else 0.10
  std::filesystem::path measured_dir, docs;
  std::string command;  // the command line, for the generated files
};

std::vector<jobs::StudyMaterial> StudyMaterials(const HemisphereArgs& a) {
  std::vector<jobs::StudyMaterial> materials;
  if (a.set == "analytic" || a.set == "all") materials = jobs::AnalyticStudyMaterials();
  if (a.set == "measured" || a.set == "all") {
    const auto measured = jobs::MeasuredStudyMaterials(a.measured_dir);
    if (measured.empty()) {
      std::printf("(no measured materials in %s)\n", a.measured_dir.string().c_str());
    }
    materials.insert(materials.end(), measured.begin(), measured.end());
  }
  if (!a.only.empty()) {
    std::erase_if(materials,
                  [&](const auto& m) { return m.name.find(a.only) == std::string::npos; });
  }
  if (!a.materials.empty()) {
    std::erase_if(materials, [&](const auto& m) {
      return std::find(a.materials.begin(), a.materials.end(), m.name) == a.materials.end();
    });
  }
  return materials;
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string RunNote(const HemisphereArgs& a, double wall_s) {
  return "Command: `" + a.command + "` — wall time " + Fixed(wall_s / 60, 1) + " min (" +
         Fixed(wall_s, 0) + " s) on the shared 2-core development machine.\n\n";
}

// Every material of the set on a plan (today's mirror plan or the designer's), every figure;
// with --model one rung (the issue-13 baseline: --model seed), otherwise every rung of the
// ladder judged side by side from one capture and one reconstruction.
void Hemisphere(const HemisphereArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<jobs::StudyMaterial> materials = StudyMaterials(a);
  const jobs::StudyPlan plan =
      a.plan == "designed" ? jobs::DesignedPlan(a.positions) : jobs::MirrorPlan();
  jobs::MaterialStudyOptions options;
  options.width = a.width;
  options.height = a.height;
  options.model = a.model;
  options.every_rung = a.model.empty();
  options.brdf_only = a.brdf_only;
  options.keep_materials_dir = a.keep_materials;
  options.work_dir = std::filesystem::temp_directory_path() / "brdfrig_hemisphere_study";
  // A measured material is judged by a prior that was never trained on it: the shipped prior's
  // settings rebuilt from every shipped material but that one.
  jobs::LeaveOneOutPriors priors;
  options.prior_for = [&](const jobs::StudyMaterial& m) { return priors.For(m); };
  std::printf("\n## Hemisphere study (%zu materials, %dx%d, supersampling %d, plan %s, %s)\n\n",
              materials.size(), a.width, a.height, options.supersampling, plan.name.c_str(),
              a.model.empty() ? "every rung" : a.model.c_str());
  // Made here, before any worker: a scratch directory removes its parent only when it made it.
  std::filesystem::create_directories(options.work_dir);
  std::vector<jobs::MaterialStudyRow> rows(materials.size());
  // Each worker takes the next material not taken yet: materials differ in cost by 2x and more.
  std::atomic<std::size_t> next{0};
  std::mutex print;
  ParallelFor(
      static_cast<std::size_t>(a.jobs),
      [&](std::size_t, std::size_t) {
        for (std::size_t i = next++; i < materials.size(); i = next++) {
          rows[i] = jobs::RunMaterialStudyPoint(materials[i], plan, options);
          const std::lock_guard lock(print);
          std::printf("%s (%.1f s)\n", rows[i].Report().c_str(), rows[i].wall_s);
          std::fflush(stdout);
        }
      },
      a.jobs);
  const double goal = a.albedo_goal > 0 ? a.albedo_goal : (a.set == "analytic" ? 0.05 : 0.10);
  const std::string table =
      (a.model.empty() ? jobs::LadderMarkdown(rows, plan, goal) : jobs::MarkdownTable(rows, plan)) +
      "\nThe written material's glTF version (material.json's `gltf`, reconstruct/gltf_fit.h) on "
      "the same sphere test against the truth; loss = rung − glTF version:\n\n" +
      jobs::GltfMarkdown(rows);
  const double wall = Seconds(start);
  std::printf("\n%s\nsummary: %s\nwall time %.1f s\n", table.c_str(),
              jobs::Summarize(rows).Report().c_str(), wall);
  std::filesystem::create_directories(a.docs / "figures");
  const std::string what =
      a.model.empty() ? "Every rung of the model ladder judged side by side (one capture, one "
                        "reconstruction per material); *chosen*: the rung leave-one-position-out "
                        "validation chose (the written material); *best*: the highest sphere mean."
                      : "Model forced to `" + a.model + "`.";
  WriteFileAtomically(
      a.docs / (a.name + ".md"),
      "# " + a.name + " (generated by `bench_evaluate_study hemisphere`)\n\n" + RunNote(a, wall) +
          what + " " + std::to_string(a.width) + "x" + std::to_string(a.height) +
          " px captures, supersampling 1, 3 exposures, 14-bit sensor with noise. Sphere: mean "
          "over lights 0°, 30°, 60°, 80° and the worst light (orthographic sphere, truth's 99th "
          "percentile = 1, clamped, sRGB, PSNR). Held-out: normalized sample PSNR (peak = "
          "truth's 99th percentile of the view's sample radiance) over views at elevations 20°, "
          "40°, 60°, 75° × light azimuths 0°, 45°, 90°, 180°: mean, and the lowest view. Albedo "
          "err: max over channels and 0°–75° of the relative directional-albedo error. BRDF err: "
          "log-cosine error. Size: the model in material.json. Fit: the rung's final fit "
          "(validation folds not included).\n\n" +
          table);
  WriteFileAtomically(a.docs / "figures" / (a.name + ".svg"),
                      a.model.empty() ? jobs::LadderPlot(rows, a.name + ", " + plan.name)
                                      : jobs::StudyPlot(rows, a.name + ", " + plan.name));
}

// The photo-count study per rung: designed plans of each count, every rung fitted from one
// capture per material and count, judged by the sphere test (CPU; no held-out views).
void PhotoCountRungs(const HemisphereArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<jobs::StudyMaterial> materials = StudyMaterials(a);
  jobs::MaterialStudyOptions options;
  options.width = a.width;
  options.height = a.height;
  options.every_rung = true;
  options.brdf_only = true;
  options.work_dir = std::filesystem::temp_directory_path() / "brdfrig_photo_count_study";
  // Each measured material judged by the prior built without it, as in the hemisphere study.
  jobs::LeaveOneOutPriors priors;
  options.prior_for = [&](const jobs::StudyMaterial& m) { return priors.For(m); };
  std::vector<std::string> kinds;
  std::vector<evaluate::Series> series;
  std::ostringstream table, detail;
  std::vector<std::vector<std::string>> cells;  // per count: one cell per column
  for (int count : a.counts) {
    const jobs::StudyPlan plan = jobs::DesignedPlan(count);
    std::vector<jobs::MaterialStudyRow> rows;
    for (const auto& material : materials) {
      rows.push_back(jobs::RunMaterialStudyPoint(material, plan, options));
      std::printf("[%d positions] %s (%.1f s)\n", count, rows.back().Report().c_str(),
                  rows.back().wall_s);
      std::fflush(stdout);
      const auto& r = rows.back();
      detail << "| " << count << " | " << r.material.name << " | " << r.result.positions_used
             << " |";
      if (!r.error.empty()) {
        detail << " failed: " << r.error << " |\n";
        continue;
      }
      for (const jobs::RungRow& rung : r.rungs) {
        detail << " " << (rung.fitted ? Fixed(rung.sphere_mean_db, 1) : std::string("—"))
               << (rung.chosen ? " (c)" : "") << " |";
      }
      detail << "\n";
    }
    for (const auto& r : rows) {
      for (const auto& rung : r.rungs) {
        if (std::find(kinds.begin(), kinds.end(), rung.kind) == kinds.end())
          kinds.push_back(rung.kind);
      }
    }
    std::vector<std::string> row = {std::to_string(count)};
    std::vector<std::string> columns = kinds;
    columns.push_back("chosen");
    columns.push_back("best");
    for (const std::string& kind : columns) {
      const jobs::RungSummary s = jobs::SummarizeRung(rows, kind, 0.1);
      row.push_back(Fixed(s.sphere_mean_db, 1) + " (" + Fixed(s.worst_sphere_db, 1) + ")");
      auto it = std::find_if(series.begin(), series.end(),
                             [&](const evaluate::Series& x) { return x.label == kind; });
      if (it == series.end()) {
        series.push_back({kind, {}, {}, true});
        it = series.end() - 1;
      }
      it->x.push_back(count);
      it->y.push_back(s.sphere_mean_db);
    }
    cells.push_back(row);
  }
  table << "| positions |";
  for (const auto& k : kinds) table << " " << k << " |";
  table << " validation-chosen | best by sphere |\n|---|";
  for (std::size_t i = 0; i < kinds.size() + 2; ++i) table << "---|";
  table << "\n";
  for (const auto& row : cells) {
    table << "|";
    for (const auto& c : row) table << " " << c << " |";
    table << "\n";
  }
  const double wall = Seconds(start);
  std::string names;
  for (const auto& m : materials) names += (names.empty() ? "" : ", ") + m.name;
  std::string header = "| positions | material | positions used |";
  std::string rule = "|---|---|---|";
  for (const auto& k : kinds) {
    header += " " + k + " |";
    rule += "---|";
  }
  const std::string text =
      "# Photo-count study per rung (generated by `bench_evaluate_study photo-count-rungs`)\n\n" +
      RunNote(a, wall) + "Materials (" + std::to_string(materials.size()) + "): " + names +
      ". Each count: coverage::DesignPlan for the default rig with that many positions, one "
      "simulated capture per material (" +
      std::to_string(a.width) + "x" + std::to_string(a.height) +
      " px, 3 exposures, 14-bit sensor with noise), every rung fitted (the prior rung of a "
      "measured material with the prior built without it), each judged by the sphere "
      "test (lights 0°, 30°, 60°, 80°). Cells: mean sphere PSNR over materials (dB), worst "
      "material in brackets.\n\n" +
      table.str() + "\nPer material (sphere mean dB per rung; (c): validation's choice):\n\n" +
      header + "\n" + rule + "\n" + detail.str();
  std::printf("\n%s\nwall time %.1f s\n", text.c_str(), wall);
  std::filesystem::create_directories(a.docs / "figures");
  WriteFileAtomically(a.docs / (a.name + ".md"), text);
  WriteFileAtomically(
      a.docs / "figures" / (a.name + ".svg"),
      evaluate::SvgLinePlot(series, {"Mean sphere PSNR by number of designed positions",
                                     "positions", "sphere mean PSNR (dB)", 640, 400}));
}

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mode = "all";
  std::filesystem::path out = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "docs/figures";
  int width = 800, height = 600;
  HemisphereArgs h;
  h.docs = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "docs";
  h.measured_dir = std::filesystem::path(BRDFRIG_SOURCE_DIR) / "data/materials/nbrdf";
  h.command = "bench_evaluate_study";
  bool named = false;
  for (int i = 1; i < argc; ++i) h.command += std::string(" ") + argv[i];
  try {
    for (int i = 1; i < argc; ++i) {
      const bool more = i + 1 < argc;
      if (std::strcmp(argv[i], "--out") == 0 && more) {
        out = argv[++i];
      } else if (std::strcmp(argv[i], "--size") == 0 && more) {
        std::sscanf(argv[++i], "%dx%d", &width, &height);
      } else if (std::strcmp(argv[i], "--study-size") == 0 && more) {
        std::sscanf(argv[++i], "%dx%d", &h.width, &h.height);
      } else if (std::strcmp(argv[i], "--set") == 0 && more) {
        h.set = argv[++i];
      } else if (std::strcmp(argv[i], "--only") == 0 && more) {
        h.only = argv[++i];
      } else if (std::strcmp(argv[i], "--materials") == 0 && more) {
        h.materials = SplitList(argv[++i]);
      } else if (std::strcmp(argv[i], "--docs") == 0 && more) {
        h.docs = argv[++i];
      } else if (std::strcmp(argv[i], "--measured-dir") == 0 && more) {
        h.measured_dir = argv[++i];
      } else if (std::strcmp(argv[i], "--plan") == 0 && more) {
        h.plan = argv[++i];
        if (h.plan != "mirror" && h.plan != "designed") {
          throw OptionsError("--plan " + h.plan + ": must be mirror or designed");
        }
      } else if (std::strcmp(argv[i], "--jobs") == 0 && more) {
        h.jobs = std::stoi(argv[++i]);
        if (h.jobs < 1) throw OptionsError("--jobs " + std::to_string(h.jobs) + ": must be >= 1");
      } else if (std::strcmp(argv[i], "--positions") == 0 && more) {
        h.positions = std::stoi(argv[++i]);
      } else if (std::strcmp(argv[i], "--counts") == 0 && more) {
        h.counts.clear();
        for (const std::string& c : SplitList(argv[++i])) h.counts.push_back(std::stoi(c));
      } else if (std::strcmp(argv[i], "--model") == 0 && more) {
        h.model = argv[++i];
      } else if (std::strcmp(argv[i], "--name") == 0 && more) {
        h.name = argv[++i];
        named = true;
      } else if (std::strcmp(argv[i], "--brdf-only") == 0) {
        h.brdf_only = true;
      } else if (std::strcmp(argv[i], "--keep-materials") == 0 && more) {
        h.keep_materials = argv[++i];
      } else if (std::strcmp(argv[i], "--albedo-goal") == 0 && more) {
        h.albedo_goal = std::stod(argv[++i]);
      } else if (argv[i][0] == '-') {
        throw OptionsError(std::string("unknown option ") + argv[i]);
      } else {
        mode = argv[i];
      }
    }
    std::filesystem::create_directories(out);
    if (mode == "photo-count" || mode == "all") PhotoCount(width, height, out);
    if (mode == "sweep" || mode == "all") Sweep(width, height, out);
    if (mode == "materials" || mode == "all") Materials(width, height);
    if (mode == "hemisphere") Hemisphere(h);
    if (mode == "photo-count-rungs") {
      if (!named) h.name = "photo_count_study";
      PhotoCountRungs(h);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_evaluate_study: %s\n", e.what());
    return 1;
  }
  return 0;
}
