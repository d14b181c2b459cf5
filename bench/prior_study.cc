// The measured prior judged leave-one-material-out on the shipped measured materials, with
// noise-free samples at the directions a plan's photos see (25 x 25 cut-out points per photo,
// nominal geometry of sim/scenes/default.yaml): the "designed" row of the ceiling table for
// the prior rung beside the compact rungs fitted to the same samples. For every material the
// prior is rebuilt without it; the plan is designed under that left-out prior (--loo-design)
// or once under the prior of all materials (the default: the plan's positions then know every
// material's covariance, the fit never its table).
//
//   bench_prior_study [--materials a,b,...] [--counts 4,6,8,12] [--components K]
//                     [--noise SIGMA] [--design-noise SIGMA] [--design-components K]
//                     [--correction W] [--correction-reach NODES] [--loo-design]
//                     [--epsilon E] [--cos-floor C] [--bandwidth H]
//                     [--no-compact] [--held-out] [--views]
//                     [--rig-changes] [--objective prior|coverage]
// --design-noise: the noise level of the prior the plan is designed under (default: --noise,
// as the shipped prior serves both), to tell what the plan and the fit each gain.
// --design-components: the leading components the designer judges plans by (default 32).
// --epsilon, --cos-floor: the table's mapping q = ln(f·c + ε), c the product of the cosines,
// each floored (brdf/rusinkiewicz_table.h), for every prior of the run.
// --held-out: also the held-out photo views of the issue-14 protocol (400x300, elevations 20°,
// 40°, 60°, 75° × light azimuths 0°, 45°, 90°, 180°; mean normalized sample PSNR over the views
// whose truth is not black) for the prior rung, the true table and its projection: where the
// held-out figure is lost (the plan, the prior, or the table itself). Needs headless GL.
// --views: --held-out with every view's figure per material (which views the fit loses).
// --rig-changes: the 6-position design of the default rig and of the rig with one change (a
// cut-out 1.5 times larger, the light at 0.6 of its distance, an extra axis turning the camera
// about the normal), each with its leave-one-material-out figures.
//
// Prints per material the sphere PSNR of the prior, ggx and microfacet rungs, the worst
// albedo error over 0-75° with its sign (evaluate::WorstAlbedoError), what the table
// representation and the prior's components allow with dense data, and a summary per position
// count.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "bench/held_out_figures.h"
#include "bench/plan_samples.h"
#include "brdf/nbrdf.h"
#include "brdf/nbrdf_library.h"
#include "brdf/rusinkiewicz_table.h"
#include "common/angles.h"
#include "common/yaml_reader.h"
#include "coverage/designer.h"
#include "evaluate/brdf_figures.h"
#include "evaluate/held_out.h"
#include "evaluate/material_report.h"
#include "evaluate/sample_figures.h"
#include "evaluate/sphere_test.h"
#include "jobs/material_study.h"
#include "jobs/study.h"
#include "prior/build_prior.h"
#include "reconstruct/fit_ladder.h"

namespace {

using namespace brdfrig;

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < s.size()) {
    const std::size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

struct Judged {
  double sphere_db = NAN;
  double albedo_signed = NAN;  // evaluate::WorstAlbedoError over 0–75° (> 0: too bright)
  bool outside = false;
};

Judged Judge(const brdf::Brdf& truth, const brdf::Brdf& fit) {
  Judged j;
  j.sphere_db = evaluate::SphereTest(truth, fit).mean_psnr_db;
  j.albedo_signed = evaluate::WorstAlbedoError(truth, fit);
  return j;
}

struct RigVariant {
  std::string name;
  geometry::RigGeometry rig;
};

std::vector<RigVariant> RigChanges(const geometry::RigGeometry& rig) {
  std::vector<RigVariant> out = {{"default rig", rig}};
  geometry::RigGeometry cut = rig;
  cut.target.cutout_width *= 1.5;
  cut.target.cutout_height *= 1.5;
  out.push_back({"cut-out 1.5x (150 mm)", cut});
  geometry::RigGeometry light = rig;
  light.light_position *= 0.6;
  out.push_back({"light at 0.6x distance", light});
  geometry::RigGeometry axis = rig;
  geometry::RotationAxis azimuth;
  azimuth.name = "camera_azimuth";
  azimuth.moves = geometry::RotationAxis::Moves::kCamera;
  azimuth.direction = geometry::Vec3::UnitZ();
  azimuth.min = -M_PI;
  azimuth.max = M_PI;
  axis.axes.insert(axis.axes.begin() + 1, azimuth);  // after camera_arm: turns the arm's plane
  out.push_back({"extra axis: camera azimuth", axis});
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names;
  std::vector<int> counts = {6};
  prior::PriorBuildOptions build;
  bool loo_design = false, compact = true, rig_changes = false, held_out = false, per_view = false;
  double design_noise = NAN;
  int design_components = coverage::DesignOptions{}.prior_components;
  prior::PriorFitOptions fit;
  std::string objective = "prior";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--materials") {
      names = SplitList(next());
    } else if (a == "--counts") {
      counts.clear();
      for (const std::string& c : SplitList(next())) counts.push_back(std::stoi(c));
    } else if (a == "--components") {
      build.max_components = std::stoi(next());
    } else if (a == "--noise") {
      build.noise_sigma = std::stod(next());
    } else if (a == "--design-components") {
      design_components = std::stoi(next());
    } else if (a == "--design-noise") {
      design_noise = std::stod(next());
    } else if (a == "--correction") {
      build.correction_weight = std::stod(next());
    } else if (a == "--correction-reach") {
      fit.correction_reach = std::stod(next());
    } else if (a == "--bandwidth") {
      fit.bandwidth = std::stod(next());
    } else if (a == "--epsilon") {
      build.grid.epsilon = std::stod(next());
    } else if (a == "--cos-floor") {
      build.grid.cos_floor = std::stod(next());
    } else if (a == "--loo-design") {
      loo_design = true;
    } else if (a == "--held-out") {
      held_out = true;
    } else if (a == "--views") {
      held_out = per_view = true;
    } else if (a == "--no-compact") {
      compact = false;
    } else if (a == "--objective") {
      objective = next();
    } else if (a == "--rig-changes") {
      rig_changes = true;
    } else {
      std::fprintf(stderr, "unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  const prior::TrainingSet set = prior::ReadTrainingSet({brdf::NbrdfDirectory()}, build);
  if (names.empty()) {
    for (const auto& m : set.materials) names.push_back(m.name);
  }
  const geometry::RigGeometry rig = geometry::ParseRigGeometry(
      LoadYamlFile(BRDFRIG_SOURCE_DIR "/sim/scenes/default.yaml").Required("rig"));
  prior::PriorBuildOptions design_build = build;
  if (std::isfinite(design_noise)) design_build.noise_sigma = design_noise;
  const prior::MeasuredPrior full = prior::BuildPrior(set, design_build);
  std::printf(
      "prior study: %zu materials, leave-one-material-out priors (%d components, noise "
      "%.3g, correction %.3g, epsilon %.3g, cos floor %.3g, bandwidth %.3g), noise-free samples "
      "at the plan's directions, %s plans designed with noise %.3g\n",
      names.size(), full.Components(), build.noise_sigma, build.correction_weight,
      build.grid.epsilon, build.grid.cos_floor, fit.bandwidth,
      loo_design ? "left-out" : "all-material", design_build.noise_sigma);
  const std::vector<evaluate::HeldOutView> held_out_views = evaluate::JudgeOptions{}.Views();
  std::vector<RigVariant> variants = {{"default rig", rig}};
  if (rig_changes) variants = RigChanges(rig);
  for (const RigVariant& variant : variants) {
    for (const int count : counts) {
      coverage::DesignOptions design;
      design.count = count;
      design.prior = &full;
      design.prior_components = design_components;
      design.objective = objective;
      const coverage::PlanDesign designed = coverage::DesignPlan(variant.rig, design);
      std::vector<geometry::AxisPositions> plan = designed.Positions();
      std::printf("\n%s, %d positions: design RMS per node %.3f expected, %.3f leave-one-out\n",
                  variant.name.c_str(), count, designed.expected_rms, designed.leave_one_out_rms);
      std::printf("\n%d positions\n%-30s %8s %8s %8s %9s %8s %8s %7s %7s %7s %7s\n", count,
                  "material", "prior", "ggx", "micro", "albedo", "misfit", "outside", "table",
                  "albedo", "project", "albedo");
      if (held_out)
        std::printf("%-30s %8s %8s %8s\n", "held-out (dB):", "prior", "table", "project");
      std::map<std::string, std::vector<double>> sphere;
      std::map<std::string, std::vector<bench::HeldOutFigures>> held;
      std::vector<double> albedo;
      int outside = 0;
      for (const std::string& name : names) {
        const auto it = std::find_if(set.materials.begin(), set.materials.end(),
                                     [&](const auto& m) { return m.name == name; });
        if (it == set.materials.end()) {
          std::fprintf(stderr, "no material %s\n", name.c_str());
          return 2;
        }
        const int index = static_cast<int>(it - set.materials.begin());
        const prior::MeasuredPrior loo = prior::BuildPrior(set, build, index);
        if (loo_design) {
          design.prior = &loo;
          plan = coverage::DesignPlan(variant.rig, design).Positions();
        }
        const brdf::NeuralBrdf truth = brdf::ReadNbrdfMaterial(name);
        const auto positions = bench::PlanSamples(truth, variant.rig, plan);
        std::vector<const reconstruct::PositionSamples*> all;
        for (const auto& p : positions) all.push_back(&p);
        reconstruct::LadderOptions options;
        options.prior.prior = &loo;
        options.prior.fit = fit;
        const brdf::Material pm =
            reconstruct::FitRung(brdf::ModelKind::kPrior, all, options, false);
        const Judged jp = Judge(truth, *pm.Model());
        // What the representation allows at all: the true table, and its projection on the
        // left-out prior's components (dense data, no regularisation).
        const brdf::RusinkiewiczTable true_table(loo.grid, brdf::TabulateBrdf(truth, loo.grid));
        const Judged jt = Judge(truth, true_table);
        brdf::TableValues table = true_table.values();
        for (std::vector<double>& q : table) {
          Eigen::Map<Eigen::VectorXd> values(q.data(), static_cast<Eigen::Index>(q.size()));
          const Eigen::VectorXd centred = values - loo.mean;
          values = loo.mean + loo.components * (loo.components.transpose() * centred);
          for (double& v : q) v = std::clamp(v, std::log(loo.grid.epsilon), 80.0);
        }
        const brdf::RusinkiewiczTable projected(loo.grid, table);
        const Judged jj = Judge(truth, projected);
        double ggx = NAN, micro = NAN;
        if (compact) {
          try {
            const brdf::Material g =
                reconstruct::FitRung(brdf::ModelKind::kGgx, all, options, false);
            ggx = Judge(truth, *g.Model()).sphere_db;
            const brdf::Material mf = reconstruct::FitRung(brdf::ModelKind::kMicrofacet, all,
                                                           options, false, nullptr, &g.microfacet);
            micro = Judge(truth, *mf.Model()).sphere_db;
          } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
          }
        }
        const bool out = reconstruct::OutsidePrior(pm);
        outside += out;
        sphere["prior"].push_back(jp.sphere_db);
        sphere["ggx"].push_back(ggx);
        sphere["microfacet"].push_back(micro);
        albedo.push_back(std::abs(jp.albedo_signed));
        std::printf("%-30s %8.2f %8.2f %8.2f %8.1f%% %8.3f %8s %7.2f %6.1f%% %7.2f %6.1f%%\n",
                    name.c_str(), jp.sphere_db, ggx, micro, 100 * jp.albedo_signed,
                    pm.fit.value("misfit", NAN), out ? "yes" : "", jt.sphere_db,
                    100 * jt.albedo_signed, jj.sphere_db, 100 * jj.albedo_signed);
        if (held_out) {
          const auto fitted = pm.Model();
          const auto h = bench::HeldOut("{model: nbrdf, name: " + name + "}",
                                        {fitted.get(), &true_table, &projected}, held_out_views);
          held["prior"].push_back(h[0]);
          held["table"].push_back(h[1]);
          held["project"].push_back(h[2]);
          std::printf("%-30s %8.2f %8.2f %8.2f  (held-out)\n", "", h[0].mean, h[1].mean, h[2].mean);
          if (per_view) {
            for (std::size_t v = 0; v < h[0].views.size(); ++v) {
              std::printf("%-30s %8.2f %8.2f %8.2f  (%s)\n", "", h[0].views[v], h[1].views[v],
                          h[2].views[v], held_out_views[v].name.c_str());
            }
          }
        }
        std::fflush(stdout);
      }
      for (const auto& [what, rows] : held) {
        std::vector<double> means;
        for (const bench::HeldOutFigures& r : rows) means.push_back(r.mean);
        const evaluate::DefinedMean m = evaluate::MeanOfDefined(means);
        std::printf("%d positions, held-out %-8s mean %.2f dB (%d materials); by elevation", count,
                    what.c_str(), m.mean, m.count);
        for (std::size_t e = 0; e < rows.front().by_elevation.size(); ++e) {
          std::vector<double> column;
          for (const bench::HeldOutFigures& r : rows) {
            column.push_back(r.by_elevation[e].normalized_sample_psnr_db);
          }
          std::printf(" %.0f° %.2f", rows.front().by_elevation[e].elevation_deg,
                      evaluate::MeanOfDefined(column).mean);
        }
        std::printf("\n");
      }
      if (per_view && !held.empty()) {
        std::printf(
            "%d positions, held-out per view (mean over materials): prior, table, project\n",
            count);
        for (std::size_t v = 0; v < held_out_views.size(); ++v) {
          std::printf("  %-24s", held_out_views[v].name.c_str());
          for (const char* what : {"prior", "table", "project"}) {
            std::vector<double> column;
            for (const bench::HeldOutFigures& r : held[what]) column.push_back(r.views[v]);
            std::printf(" %8.2f", evaluate::MeanOfDefined(column).mean);
          }
          std::printf("\n");
        }
      }
      for (const auto& [rung, values] : sphere) {
        double sum = 0, worst = INFINITY;
        int n = 0;
        for (const double v : values) {
          if (std::isfinite(v)) sum += v, worst = std::min(worst, v), ++n;
        }
        std::printf("%d positions, %-10s sphere mean %.2f dB, worst %.2f dB (%d materials)\n",
                    count, rung.c_str(), n ? sum / n : NAN, worst, n);
      }
      const long within =
          std::count_if(albedo.begin(), albedo.end(), [](double a) { return a <= 0.1; });
      std::printf(
          "%d positions, prior albedo within 10 %% at 0-75°: %ld of %zu; outside the prior: "
          "%d\n",
          count, within, albedo.size(), outside);
    }
  }
  return 0;
}
