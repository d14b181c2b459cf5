#include "prior/build_prior.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>

#include "brdf/nbrdf.h"
#include "common/check.h"
#include "common/error.h"
#include "common/option_check.h"
#include "common/parallel.h"
#include "common/sha256.h"

namespace brdfrig::prior {

void PriorBuildOptions::Validate() const {
  grid.Validate();
  CheckOption(max_components >= 1 && max_components <= 4096, "PriorBuildOptions.max_components",
              max_components, "in [1, 4096]");
  CheckOption(noise_sigma > 0 && noise_sigma < 100, "PriorBuildOptions.noise_sigma", noise_sigma,
              "in (0, 100)");
  CheckOption(correction_weight > 0 && correction_weight < 1e9,
              "PriorBuildOptions.correction_weight", correction_weight, "in (0, 1e9)");
}

TrainingSet ReadTrainingSet(const std::vector<std::filesystem::path>& directories,
                            const PriorBuildOptions& options) {
  options.Validate();
  std::map<std::string, std::filesystem::path> files;  // sorted by material name
  for (const std::filesystem::path& dir : directories) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
      throw FileError(dir.string(), "not a directory of measured materials");
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".json" || !entry.is_regular_file()) continue;
      const std::string name = entry.path().stem().string();
      if (std::find(options.exclude.begin(), options.exclude.end(), name) !=
          options.exclude.end()) {
        continue;
      }
      const auto [it, added] = files.emplace(name, entry.path());
      if (!added) {
        throw FileError(entry.path().string(),
                        "a material named '" + name + "' is also " + it->second.string());
      }
    }
  }
  if (files.size() < 2) throw Error("prior build: fewer than two measured materials found");
  TrainingSet set;
  std::vector<brdf::NeuralBrdf> brdfs;
  for (const auto& [name, path] : files) {
    brdfs.push_back(brdf::NeuralBrdf::Read(path));
    const std::string& db = brdfs.back().database();
    set.materials.push_back(
        {name, db,
         "MIT (neural fit, Sztrajman et al. 2021, asztr/Neural-BRDF) of a " + db + " measurement",
         Sha256FileHex(path)});
  }
  set.tables.resize(brdfs.size());
  ParallelFor(brdfs.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      set.tables[i] = brdf::TabulateBrdf(brdfs[i], options.grid);
    }
  });
  return set;
}

PriorBuildOptions OptionsOf(const MeasuredPrior& prior) {
  PriorBuildOptions o;
  o.name = prior.name;
  o.grid = prior.grid;
  o.max_components = prior.Components();
  o.noise_sigma = prior.noise_sigma;
  o.correction_weight = prior.correction_weight;
  return o;
}

MeasuredPrior BuildPrior(const TrainingSet& set, const PriorBuildOptions& options, int leave_out) {
  options.Validate();
  const int cells = options.grid.Cells();
  std::vector<int> used;
  for (int i = 0; i < static_cast<int>(set.tables.size()); ++i) {
    if (i != leave_out) used.push_back(i);
  }
  const int rows = 3 * static_cast<int>(used.size());
  Eigen::MatrixXd y(rows, cells);
  for (std::size_t m = 0; m < used.size(); ++m) {
    const brdf::TableValues& t = set.tables[used[m]];
    for (int c = 0; c < 3; ++c) {
      BRDFRIG_CHECK(static_cast<int>(t[c].size()) == cells, "table size");
      y.row(3 * m + c) = Eigen::Map<const Eigen::RowVectorXd>(t[c].data(), cells);
    }
  }
  MeasuredPrior p;
  p.name = options.name;
  p.grid = options.grid;
  p.noise_sigma = options.noise_sigma;
  p.correction_weight = options.correction_weight;
  p.built_with = std::string("brdfrig ") + BRDFRIG_VERSION;
  for (const int i : used) p.training.push_back(set.materials[i]);
  p.mean = y.colwise().mean().transpose();
  y.rowwise() -= p.mean.transpose();
  // Principal components through the rows' Gram matrix (rows << cells).
  const Eigen::MatrixXd gram = y * y.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
  const int k = std::min(options.max_components, rows - 1);
  p.components.resize(cells, k);
  p.variances.resize(k);
  for (int j = 0; j < k; ++j) {
    const int col = rows - 1 - j;  // eigenvalues ascend
    const double lambda = std::max(eig.eigenvalues()[col], 1e-12);
    p.components.col(j) = y.transpose() * eig.eigenvectors().col(col) / std::sqrt(lambda);
    p.variances[j] = lambda / (rows - 1);
  }
  p.training_coefficients = y * p.components;
  return p;
}

}  // namespace brdfrig::prior
