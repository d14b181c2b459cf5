// A prior over isotropic BRDFs learned from measured materials: the principal components of
// their Rusinkiewicz tables (brdf/rusinkiewicz_table.h) in the mapped variable
// q = ln(f·c + ε), with the components' coefficients of every training channel and their
// variances (the fit's prior is built from both, prior_fit.h). Each colour channel of each training
// material is one sample (channels stacked): a channel is one curve of the same physics, and three
// times the samples estimate the covariance better than one joint RGB vector would.
//
// The file (data/priors/*.prior) is versioned and self-describing: a first line
// "brdfrig-prior", a JSON header (format, version, name, grid, noise level, training list with
// each material's database, licence and SHA-256, what built it), then little-endian float32
// arrays: the mean table, the components, their variances, and the training channels'
// coefficients (which let the plan designer judge a plan leave-one-material-out without the
// training files).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "brdf/rusinkiewicz_table.h"

namespace brdfrig::prior {

struct TrainingMaterial {
  std::string name;
  std::string database;  // merl | rgl | dtu | ...
  std::string licence;
  std::string sha256;  // of the file it was read from
};

struct MeasuredPrior {
  std::string name;  // e.g. "measured-80"
  int version = 1;   // of the file format
  brdf::RusinkiewiczGrid grid;
  // Standard deviation of one observation's q (unit weight) in the fit: photo noise plus what
  // the components cannot represent. Chosen by leave-one-material-out (docs/prior.md).
  double noise_sigma = 1;
  // Weight of the prior's own value against the measured samples when the fit corrects the
  // table where photos saw the material (prior_fit.h).
  double correction_weight = 1;
  std::vector<TrainingMaterial> training;
  std::string built_with;  // "brdfrig <version>"

  Eigen::VectorXd mean;                   // q per node (grid.Cells())
  Eigen::MatrixXd components;             // cells × K, orthonormal columns
  Eigen::VectorXd variances;              // K, descending: variance of each coefficient
  Eigen::MatrixXd training_coefficients;  // (3 · training.size()) × K, rows material-major, RGB

  int Components() const { return static_cast<int>(components.cols()); }
  // Throws brdfrig::Error when the arrays do not match the grid and each other.
  void Validate() const;
};

// Throws FileError naming the file and what is wrong (magic, header, sizes, non-finite values).
MeasuredPrior ReadPrior(const std::filesystem::path& path);
// Atomic write; throws brdfrig::Error naming the path.
void WritePrior(const MeasuredPrior& prior, const std::filesystem::path& path);

// The prior shipped with this build (data/priors/measured.prior of the source tree).
std::filesystem::path DefaultPriorPath();
// ReadPrior(DefaultPriorPath()) once per process (the file is a few MB).
const MeasuredPrior& DefaultPrior();

}  // namespace brdfrig::prior
