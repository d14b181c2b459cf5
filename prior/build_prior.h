// Building a measured prior from a directory of measured materials (`brdfrig prior build`):
// every material tabulated on the grid, the principal components of the channels' tables, the
// coefficients' variances. A lab rebuilds it from its own library; the study (bench/
// prior_study) builds one per left-out material.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "prior/measured_prior.h"

namespace brdfrig::prior {

struct PriorBuildOptions {
  std::string name = "measured";
  brdf::RusinkiewiczGrid grid;
  int max_components = 64;  // K; fewer when the training set has fewer channels
  // Recorded in the prior (MeasuredPrior::noise_sigma). 1: the best of 0.1–4 on the sphere test
  // of 16 materials left out one at a time (docs/prior.md).
  double noise_sigma = 1;
  double correction_weight = 1;
  std::vector<std::string> exclude;  // material names left out of the training set
  void Validate() const;
};

// The training set: one table per material (q per channel and node) with its record.
struct TrainingSet {
  std::vector<TrainingMaterial> materials;
  std::vector<brdf::TableValues> tables;
};

// Reads and tabulates every nbrdf-mlp *.json in the directories (sorted by name; duplicates by
// name refused), leaving out `exclude`. Throws FileError for an unreadable material.
TrainingSet ReadTrainingSet(const std::vector<std::filesystem::path>& directories,
                            const PriorBuildOptions& options);

// The options that rebuild `prior` (its grid, components, noise and correction weight), for
// studies that rebuild it without one material.
PriorBuildOptions OptionsOf(const MeasuredPrior& prior);

// The prior of a training set. `leave_out`: an index into the set to leave out (-1: none).
MeasuredPrior BuildPrior(const TrainingSet& set, const PriorBuildOptions& options,
                         int leave_out = -1);

}  // namespace brdfrig::prior
