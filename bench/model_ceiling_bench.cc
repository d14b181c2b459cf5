// What each rung of the ladder can reach when the data are perfect: the rung fitted to
// noise-free samples of the true BRDF, judged by the sphere test. The prior rung of a measured
// material uses the prior built without that material (jobs::LeaveOneOutPriors). Four data sets
// per material:
//   dense     l and v over the whole hemisphere (the model form's ceiling)
//   designed  the directions the designed plan's photos see across the cut-out (nominal rig
//             geometry, coverage/), f from the truth: the plan's ceiling without the capture
//   captured  the study's simulated capture of the designed plan (400x300 px unless --size,
//             14-bit, noise),
//             measured by the reconstruction's own MeasurePosition: what the rungs get
//   geometry  the captured samples' directions with f from the truth: the capture's measured
//             geometry (pose, light) without its radiometry
// The gap between "designed" and "geometry" is what the measured geometry costs, between
// "geometry" and "captured" what the measured radiance costs, between "dense" and "designed"
// what six photos cost; "dense" is what the form can do at all. The median and spread of
// ln(f_captured / f_truth) per position say where the radiance is biased.
//
// With --choice: the captured data only, the whole ladder with its leave-one-position-out folds
// (reconstruct::FitLadder), and the sphere mean each rule for turning fold scores into a choice
// would get (mean over folds, median, mean without the worst fold), beside the oracle (the
// best rung by sphere). How the default rule was chosen; run it before changing that rule.
//
//   bench_model_ceiling [--set analytic|measured|all] [--materials a,b,...] [--positions N]
//                       [--rungs ggx,beckmann,microfacet,prior] [--size WxH] [--effects YAML]
//                       [--exposures t1,t2,t3] [--held-out]
//                       [--choice [--validation N]]
// --held-out: beside each sphere figure the held-out photo views' mean normalized sample PSNR
// (bench/held_out_figures.h, the studies' 16 views at 400x300): which step loses the held-out
// figure. Needs headless GL.
// --validation N adds N validation positions (coverage::DesignOptions::validation) to the plan
// of --choice and compares the folds alone, the validation photos alone and both (the product).
#include <unistd.h>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bench/held_out_figures.h"
#include "bench/plan_samples.h"
#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/format.h"
#include "common/yaml_reader.h"
#include "coverage/designer.h"
#include "evaluate/brdf_figures.h"
#include "evaluate/sphere_test.h"
#include "jobs/material_study.h"
#include "jobs/study.h"
#include "reconstruct/batch.h"
#include "reconstruct/fit_ladder.h"
#include "reconstruct/measure_position.h"
#include "sim/sample_brdf.h"
#include "sim/scene.h"
#include "sim/simulate.h"

namespace {

using namespace brdfrig;
namespace fs = std::filesystem;

brdf::Vec3 Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// theta_i, theta_o in 2.5°…85° (18 steps each), relative azimuth 0…180° (13 steps).
reconstruct::PositionSamples DenseSamples(const brdf::Brdf& truth) {
  reconstruct::PositionSamples p;
  for (int i = 0; i < 18; ++i) {
    for (int o = 0; o < 18; ++o) {
      for (int a = 0; a < 13; ++a) {
        const double ti = Radians(2.5 + 82.5 * i / 17), to = Radians(2.5 + 82.5 * o / 17);
        p.directions.samples.push_back(
            bench::SampleOf(truth, Direction(ti, M_PI), Direction(to, M_PI * a / 12)));
      }
    }
  }
  return p;
}

// The study's capture of `material` on `plan`, measured position by position.
// How the study's capture is taken: its size and the sensor's effects (empty: the scene's).
struct CaptureSize {
  int width = 400, height = 300;
  std::string effects;
  std::vector<double> exposures;  // seconds (empty: the scene's)
};

std::vector<reconstruct::PositionSamples> CapturedSamples(const jobs::StudyMaterial& material,
                                                          const jobs::StudyPlan& plan,
                                                          const fs::path& work,
                                                          CaptureSize size = {}) {
  const fs::path base = fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml";
  jobs::StudySettings settings;
  settings.width = size.width;
  settings.height = size.height;
  settings.effects = size.effects;
  settings.supersampling = 1;
  settings.sample_brdf = material.brdf_yaml;
  const auto scene = std::make_shared<const sim::Scene>(jobs::StudyScene(base, settings));
  fs::remove_all(work);
  sim::SimulateOptions simulate;
  simulate.scene = base;
  simulate.loaded_scene = scene;
  simulate.output_dir = work;
  simulate.write_truth = false;
  simulate.positions = plan.positions;
  simulate.exposures = size.exposures;
  sim::Simulate(simulate);
  reconstruct::CaptureSet capture = reconstruct::LoadCapture(work);
  capture.nominal = scene->rig;
  reconstruct::MeasureOptions options;
  reconstruct::MeasureState state;
  std::vector<reconstruct::PositionSamples> out;
  for (const reconstruct::CapturePosition& position : capture.positions) {
    reconstruct::MeasuredPosition m =
        reconstruct::MeasurePosition(position, capture.nominal, options, &state);
    out.push_back({position.index, std::move(m.samples), std::move(m.directions), {}});
  }
  fs::remove_all(work);
  return out;
}

std::vector<reconstruct::PositionSamples> WithTruth(std::vector<reconstruct::PositionSamples> p,
                                                    const brdf::Brdf& truth) {
  for (auto& position : p) {
    for (auto& s : position.directions.samples) {
      const brdf::Rgb f = truth.Eval(s.l, s.v, brdf::Vec3::UnitZ());
      for (int c = 0; c < 3; ++c) s.f[c] = f[c];
    }
  }
  return p;
}

// Per position: median of ln(f_captured / f_truth) over samples and channels, and the spread
// (median absolute deviation).
std::string RadianceBias(const std::vector<reconstruct::PositionSamples>& captured,
                         const brdf::Brdf& truth) {
  std::string out;
  for (const auto& position : captured) {
    std::vector<double> r;
    for (const auto& s : position.directions.samples) {
      const brdf::Rgb f = truth.Eval(s.l, s.v, brdf::Vec3::UnitZ());
      for (int c = 0; c < 3; ++c) {
        if (f[c] > 0 && s.f[c] > 0) r.push_back(std::log(s.f[c] / f[c]));
      }
    }
    if (r.empty()) continue;
    std::sort(r.begin(), r.end());
    const double median = r[r.size() / 2];
    std::vector<double> dev;
    for (double x : r) dev.push_back(std::abs(x - median));
    std::sort(dev.begin(), dev.end());
    out += (out.empty() ? "" : ", ") + Fixed(median, 3) + "±" + Fixed(dev[dev.size() / 2], 3);
  }
  return out;
}

// The rules for turning a rung's fold scores into one score (lower is better).
double MeanScore(std::vector<double> v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}
double MedianScore(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double TrimmedScore(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (v.size() > 2) v.pop_back();
  return MeanScore(v);
}

// A rule for turning a rung's held-out scores into one score (lower is better).
struct ChoiceRule {
  const char* name;
  double (*score)(const reconstruct::RungResult&);
};

// Without validation positions: three ways of combining the folds. With them: the folds alone,
// the validation photos alone, and the product's rule (the mean over both, RungResult::score).
const std::vector<ChoiceRule>& ChoiceRules(bool validation) {
  static const std::vector<ChoiceRule> folds = {
      {"mean rule", [](const reconstruct::RungResult& r) { return MeanScore(r.fold_scores); }},
      {"median rule", [](const reconstruct::RungResult& r) { return MedianScore(r.fold_scores); }},
      {"trimmed rule",
       [](const reconstruct::RungResult& r) { return TrimmedScore(r.fold_scores); }}};
  static const std::vector<ChoiceRule> with_validation = {
      {"folds only", [](const reconstruct::RungResult& r) { return MeanScore(r.fold_scores); }},
      {"validation only",
       [](const reconstruct::RungResult& r) { return MeanScore(r.validation_scores); }},
      {"folds + validation (product)", [](const reconstruct::RungResult& r) { return r.score; }}};
  return validation ? with_validation : folds;
}

// One material: every rung's sphere mean and the rung each rule chooses among the rungs that
// conserve energy. The last `validation` positions of the plan are validation positions.
// Returns the sphere mean per rule, then the oracle's.
std::vector<double> CompareChoices(const jobs::StudyMaterial& material, const jobs::StudyPlan& plan,
                                   int validation, const brdf::Brdf& truth) {
  auto captured = CapturedSamples(
      material, plan,
      fs::temp_directory_path() / ("brdfrig_model_ceiling." + std::to_string(getpid())));
  std::vector<reconstruct::PositionSamples> held(captured.end() - validation, captured.end());
  captured.resize(captured.size() - validation);
  const reconstruct::LadderResult ladder =
      reconstruct::FitLadder(captured, held, reconstruct::LadderOptions{});
  const std::vector<ChoiceRule>& rules = ChoiceRules(validation > 0);
  const std::size_t k_oracle = rules.size();
  std::vector<int> chosen(rules.size() + 1, -1);
  std::vector<double> best_score(rules.size() + 1, 1e300);
  best_score[k_oracle] = -1e300;
  std::vector<double> sphere(ladder.rungs.size(), NAN);
  std::printf("| %s |", material.name.c_str());
  for (std::size_t r = 0; r < ladder.rungs.size(); ++r) {
    const reconstruct::RungResult& rung = ladder.rungs[r];
    if (!rung.fitted) {
      std::printf(" failed |");
      continue;
    }
    sphere[r] = evaluate::SphereTest(truth, *rung.material.Model()).mean_psnr_db;
    std::printf(" %s (%s%s) |", Fixed(sphere[r], 1).c_str(), Fixed(rung.score, 3).c_str(),
                rung.ConservesEnergy() ? "" : ", creates energy");
    if (!rung.ConservesEnergy()) continue;
    for (std::size_t k = 0; k < rules.size(); ++k) {
      const double score = rules[k].score(rung);
      if (score < best_score[k]) {
        best_score[k] = score;
        chosen[k] = static_cast<int>(r);
      }
    }
    if (sphere[r] > best_score[k_oracle]) {
      best_score[k_oracle] = sphere[r];
      chosen[k_oracle] = static_cast<int>(r);
    }
  }
  std::vector<double> out;
  for (int c : chosen) {
    out.push_back(c >= 0 ? sphere[c] : NAN);
    std::printf(" %s |", c >= 0 ? brdf::ModelKindName(ladder.rungs[c].kind) : "-");
  }
  std::printf("\n");
  std::fflush(stdout);
  return out;
}

struct Cell {
  double sphere_db = NAN, worst_db = NAN;
  double albedo_error = NAN;  // evaluate::WorstAlbedoError, 0–75°, signed
  double held_out_db = NAN;   // bench::HeldOut's mean (--held-out only)
  std::shared_ptr<const brdf::Brdf> fit;
};

Cell Judge(brdf::ModelKind kind, const std::vector<reconstruct::PositionSamples>& positions,
           const brdf::Brdf& truth, const reconstruct::LadderOptions& options) {
  std::vector<const reconstruct::PositionSamples*> all;
  for (const auto& p : positions) all.push_back(&p);
  try {
    const auto fit = reconstruct::FitRung(kind, all, options, false).Model();
    const evaluate::SphereTestResult r = evaluate::SphereTest(truth, *fit);
    return {r.mean_psnr_db, r.worst_psnr_db, evaluate::WorstAlbedoError(truth, *fit), NAN, fit};
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", brdf::ModelKindName(kind), e.what());
    return {};
  }
}

// Every fitted cell's held-out figure, the truth photographed once per view for all of them.
void JudgeHeldOut(const std::string& brdf_yaml, std::vector<Cell>* cells) {
  std::vector<const brdf::Brdf*> fits;
  std::vector<Cell*> fitted;
  for (Cell& c : *cells) {
    if (!c.fit) continue;
    fits.push_back(c.fit.get());
    fitted.push_back(&c);
  }
  if (fits.empty()) return;
  const auto figures = bench::HeldOut(brdf_yaml, fits, evaluate::JudgeOptions{}.Views());
  for (std::size_t i = 0; i < fitted.size(); ++i) fitted[i]->held_out_db = figures[i].mean;
}

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string set = "all";
  std::vector<std::string> only;
  int count = 6;
  std::vector<std::string> rungs = {"ggx", "beckmann", "microfacet", "prior"};
  CaptureSize size;
  bool choice = false, held_out = false;
  int validation = 0;
  for (int i = 1; i < argc; ++i) {
    const bool more = i + 1 < argc;
    if (std::strcmp(argv[i], "--set") == 0 && more) {
      set = argv[++i];
    } else if (std::strcmp(argv[i], "--materials") == 0 && more) {
      only = SplitList(argv[++i]);
    } else if (std::strcmp(argv[i], "--positions") == 0 && more) {
      count = std::stoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--rungs") == 0 && more) {
      rungs = SplitList(argv[++i]);
    } else if (std::strcmp(argv[i], "--size") == 0 && more &&
               std::sscanf(argv[i + 1], "%dx%d", &size.width, &size.height) == 2) {
      ++i;
    } else if (std::strcmp(argv[i], "--exposures") == 0 && more) {
      for (const std::string& t : SplitList(argv[++i])) size.exposures.push_back(std::stod(t));
    } else if (std::strcmp(argv[i], "--effects") == 0 && more) {
      size.effects = argv[++i];
    } else if (std::strcmp(argv[i], "--choice") == 0) {
      choice = true;
    } else if (std::strcmp(argv[i], "--held-out") == 0) {
      held_out = true;
    } else if (std::strcmp(argv[i], "--validation") == 0 && more) {
      validation = std::stoi(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: bench_model_ceiling [--set analytic|measured|all] "
                   "[--materials a,b] [--positions N] [--rungs a,b] [--size WxH] [--effects YAML] "
                   "[--exposures t1,t2] [--held-out] "
                   "[--choice [--validation N]]\n");
      return 2;
    }
  }
  const fs::path source = BRDFRIG_SOURCE_DIR;
  std::vector<jobs::StudyMaterial> materials;
  if (set != "measured") materials = jobs::AnalyticStudyMaterials();
  if (set != "analytic") {
    for (auto& m : jobs::MeasuredStudyMaterials(source / "data/materials/nbrdf")) {
      materials.push_back(m);
    }
  }
  const sim::Scene scene = sim::LoadScene(source / "sim/scenes/default.yaml");
  const jobs::StudyPlan plan = jobs::DesignedPlan(count);
  if (choice) {
    coverage::DesignOptions design;
    design.count = count;
    design.validation = validation;
    const coverage::PlanDesign designed = coverage::DesignPlan(scene.rig, design);
    const jobs::StudyPlan choice_plan{
        plan.name +
            (validation ? " + " + std::to_string(validation) + " validation" : std::string()),
        designed.Positions()};
    const std::vector<ChoiceRule>& rules = ChoiceRules(validation > 0);
    std::printf(
        "Sphere mean (dB) of every rung fitted to the captured data, (its held-out score); the "
        "rung each rule chooses among those that conserve energy.\nPlan: %s\n\n| material "
        "| seed | seed_constrained | ggx | beckmann | microfacet |",
        choice_plan.name.c_str());
    for (const ChoiceRule& rule : rules) std::printf(" %s |", rule.name);
    std::printf(" oracle |\n|---|---|---|---|---|---|");
    for (std::size_t k = 0; k <= rules.size(); ++k) std::printf("---|");
    std::printf("\n");
    std::vector<double> sums(rules.size() + 1, 0.0);
    int n = 0;
    for (const jobs::StudyMaterial& material : materials) {
      if (!only.empty() && std::find(only.begin(), only.end(), material.name) == only.end()) {
        continue;
      }
      const YamlNode root = LoadYamlString("brdf: " + material.brdf_yaml, material.name);
      const auto truth = sim::ParseSampleBrdf(root.Required("brdf"), source / "sim/scenes");
      const std::vector<double> got = CompareChoices(material, choice_plan, validation, *truth);
      for (std::size_t k = 0; k < got.size(); ++k) sums[k] += got[k];
      ++n;
    }
    std::printf("| **mean of %d** | | | | | |", n);
    for (double s : sums) std::printf(" %s |", Fixed(s / n, 1).c_str());
    std::printf("\n");
    return 0;
  }
  std::vector<brdf::ModelKind> kinds;
  for (const std::string& name : rungs) kinds.push_back(brdf::ParseModelKind(name));
  std::printf(
      "Sphere test mean (worst light) in dB of each rung fitted to noise-free truth "
      "samples, and its directional-albedo error at 0-75°, the largest over channels and "
      "angles with its sign (> 0: too bright).\nPlan: %s; capture %dx%d px\n\n| material | data |",
      plan.name.c_str(), size.width, size.height);
  for (brdf::ModelKind k : kinds) std::printf(" %s |", brdf::ModelKindName(k));
  std::printf("\n|---|---|");
  for (std::size_t k = 0; k < kinds.size(); ++k) std::printf("---|");
  std::printf("\n");
  jobs::LeaveOneOutPriors priors;
  constexpr int kData = 4;
  const char* names[kData] = {"dense", "designed", "geometry", "captured"};
  std::vector<double> sums(kData * kinds.size(), 0.0), held_out_sums(sums);
  std::vector<int> albedo_within(kData * kinds.size(), 0);
  std::vector<std::string> biases;
  int judged = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const jobs::StudyMaterial& material : materials) {
    if (!only.empty() && std::find(only.begin(), only.end(), material.name) == only.end()) {
      continue;
    }
    const YamlNode root = LoadYamlString("brdf: " + material.brdf_yaml, material.name);
    const auto truth = sim::ParseSampleBrdf(root.Required("brdf"), source / "sim/scenes");
    std::vector<reconstruct::PositionSamples> captured;
    try {
      captured = CapturedSamples(
          material, plan,
          fs::temp_directory_path() / ("brdfrig_model_ceiling." + std::to_string(getpid())), size);
    } catch (const std::exception& e) {
      // Not counted in the means: the capture could not be measured at all.
      std::printf("| %s | capture failed: %s |\n", material.name.c_str(), e.what());
      std::fflush(stdout);
      continue;
    }
    reconstruct::LadderOptions options;
    options.prior.prior = priors.For(material);
    const std::vector<reconstruct::PositionSamples> data[kData] = {
        {DenseSamples(*truth)},
        bench::PlanSamples(*truth, scene.rig, plan.positions),
        WithTruth(captured, *truth),
        captured};
    std::vector<Cell> cells;
    for (int d = 0; d < kData; ++d) {
      for (brdf::ModelKind kind : kinds) cells.push_back(Judge(kind, data[d], *truth, options));
    }
    if (held_out) JudgeHeldOut(material.brdf_yaml, &cells);
    for (int d = 0; d < kData; ++d) {
      std::printf("| %s | %s |", d == 0 ? material.name.c_str() : "", names[d]);
      for (std::size_t k = 0; k < kinds.size(); ++k) {
        const std::size_t i = d * kinds.size() + k;
        const Cell& c = cells[i];
        std::printf(" %s (%s) %s%%", Fixed(c.sphere_db, 1).c_str(), Fixed(c.worst_db, 1).c_str(),
                    Fixed(100 * c.albedo_error, 0).c_str());
        if (held_out) std::printf(", held-out %s", Fixed(c.held_out_db, 2).c_str());
        std::printf(" |");
        sums[i] += c.sphere_db;
        held_out_sums[i] += c.held_out_db;
        albedo_within[i] += std::abs(c.albedo_error) <= 0.1;
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    biases.push_back(material.name + ": " + RadianceBias(captured, *truth));
    ++judged;
  }
  for (int d = 0; d < kData; ++d) {
    std::printf("| **mean of %d** | %s |", judged, names[d]);
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const std::size_t i = d * kinds.size() + k;
      std::printf(" %s, albedo within 10 %%: %d", Fixed(sums[i] / std::max(judged, 1), 1).c_str(),
                  albedo_within[i]);
      if (held_out) {
        std::printf(", held-out %s", Fixed(held_out_sums[i] / std::max(judged, 1), 2).c_str());
      }
      std::printf(" |");
    }
    std::printf("\n");
  }
  std::printf("\nln(f_captured / f_truth) per position, median ± median absolute deviation:\n");
  for (const std::string& b : biases) std::printf("- %s\n", b.c_str());
  std::printf("\nwall time %.0f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}
