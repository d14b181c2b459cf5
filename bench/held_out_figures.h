// The held-out photo views of the studies (evaluate::JudgeOptions' elevations × light azimuths,
// the study's 400x300 capture size) for several fits of one material: the figure issue 14 and
// issue 22 judge by (mean normalized sample PSNR over the views whose truth is not black).
// Shared by bench_prior_study and bench_model_ceiling so both judge the same views the same way.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "evaluate/held_out.h"
#include "evaluate/material_report.h"
#include "evaluate/sample_figures.h"
#include "jobs/material_study.h"
#include "jobs/study.h"

namespace brdfrig::bench {

// Held-out figures of one fit: the mean normalized sample PSNR over the views, and per elevation.
struct HeldOutFigures {
  double mean = NAN;
  std::vector<evaluate::ElevationSummary> by_elevation;
  std::vector<double> views;  // each view's normalized sample PSNR, in `views`' order
};

// `views` for every fit of the sample `brdf_yaml` (a sample_brdf: node, e.g.
// "{model: nbrdf, name: pvc}"); needs headless GL.
inline std::vector<HeldOutFigures> HeldOut(const std::string& brdf_yaml,
                                           const std::vector<const brdf::Brdf*>& fits,
                                           const std::vector<evaluate::HeldOutView>& views) {
  jobs::StudySettings settings;
  settings.width = jobs::MaterialStudyOptions{}.width;
  settings.height = jobs::MaterialStudyOptions{}.height;
  settings.sample_brdf = brdf_yaml;
  const sim::Scene scene =
      jobs::StudyScene(BRDFRIG_SOURCE_DIR "/sim/scenes/default.yaml", settings);
  std::vector<HeldOutFigures> figures;
  for (const auto& results : evaluate::EvaluateHeldOutEach(scene, fits, views)) {
    std::vector<double> psnr;
    for (const auto& r : results) psnr.push_back(r.normalized_sample.psnr_db);
    figures.push_back(
        {evaluate::MeanOfDefined(psnr).mean, evaluate::SummarizeByElevation(results), psnr});
  }
  return figures;
}

}  // namespace brdfrig::bench
