#include "prior/measured_prior.h"

#include <cmath>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>

#include "brdf/json_reader.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::prior {
namespace {

constexpr char kMagic[] = "brdfrig-prior\n";
constexpr std::size_t kMaxPriorBytes = std::size_t{256} << 20;

void AppendFloats(const double* data, std::size_t n, std::string* out) {
  const std::size_t at = out->size();
  out->resize(at + 4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const float f = static_cast<float>(data[i]);
    std::memcpy(out->data() + at + 4 * i, &f, 4);  // little-endian hosts only (x86, arm64)
  }
}

// Reads n floats at *offset of `bytes` into `out`; false when the file is too short or a
// value is not finite.
bool TakeFloats(const std::string& bytes, std::size_t* offset, std::size_t n, double* out) {
  if (bytes.size() < *offset || (bytes.size() - *offset) / 4 < n) return false;
  for (std::size_t i = 0; i < n; ++i) {
    float f;
    std::memcpy(&f, bytes.data() + *offset + 4 * i, 4);
    if (!std::isfinite(f)) return false;
    out[i] = f;
  }
  *offset += 4 * n;
  return true;
}

}  // namespace

void MeasuredPrior::Validate() const {
  grid.Validate();
  const int cells = grid.Cells();
  const int k = Components();
  const auto fail = [&](const std::string& what) {
    throw Error("measured prior '" + name + "': " + what);
  };
  if (mean.size() != cells) fail("the mean has " + std::to_string(mean.size()) + " values");
  if (components.rows() != cells || k < 1) fail("the components do not match the grid");
  if (variances.size() != k) fail("the variances do not match the components");
  if (training_coefficients.cols() != k ||
      training_coefficients.rows() != 3 * static_cast<Eigen::Index>(training.size())) {
    fail("the training coefficients do not match the training list and the components");
  }
  for (int i = 0; i < k; ++i) {
    if (!(variances[i] > 0) || !std::isfinite(variances[i])) fail("a variance is not positive");
  }
  if (!(noise_sigma > 0) || !std::isfinite(noise_sigma)) fail("noise_sigma must be positive");
  if (!(correction_weight > 0) || !std::isfinite(correction_weight)) {
    fail("correction_weight must be positive");
  }
}

void WritePrior(const MeasuredPrior& prior, const std::filesystem::path& path) {
  prior.Validate();
  nlohmann::json header = {
      {"format", "brdfrig-prior"},
      {"version", prior.version},
      {"name", prior.name},
      {"grid",
       {{"theta_h", prior.grid.theta_h},
        {"theta_d", prior.grid.theta_d},
        {"phi_d", prior.grid.phi_d},
        {"epsilon", prior.grid.epsilon},
        {"cos_floor", prior.grid.cos_floor}}},
      {"components", prior.Components()},
      {"noise_sigma", prior.noise_sigma},
      {"correction_weight", prior.correction_weight},
      {"built_with", prior.built_with},
      {"payload",
       "float32 little-endian: mean[cells], components[K][cells], variances[K], "
       "training_coefficients[3 x materials][K]"},
  };
  header["training"] = nlohmann::json::array();
  for (const TrainingMaterial& m : prior.training) {
    header["training"].push_back(
        {{"name", m.name}, {"database", m.database}, {"licence", m.licence}, {"sha256", m.sha256}});
  }
  std::string bytes = kMagic;
  bytes += header.dump(1) + '\n';
  bytes += '\0';  // end of the header: the payload follows
  AppendFloats(prior.mean.data(), prior.mean.size(), &bytes);
  for (int k = 0; k < prior.Components(); ++k) {
    AppendFloats(prior.components.col(k).data(), prior.components.rows(), &bytes);
  }
  AppendFloats(prior.variances.data(), prior.variances.size(), &bytes);
  const Eigen::MatrixXd rows = prior.training_coefficients;  // row-major copy below
  for (Eigen::Index r = 0; r < rows.rows(); ++r) {
    const Eigen::VectorXd row = rows.row(r).transpose();
    AppendFloats(row.data(), row.size(), &bytes);
  }
  WriteFileAtomically(path, bytes);
}

MeasuredPrior ReadPrior(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string bytes = ReadFileToString(path, kMaxPriorBytes);
  if (bytes.compare(0, std::strlen(kMagic), kMagic) != 0) {
    throw FileError(source, "not a brdfrig prior (the first line must be 'brdfrig-prior')");
  }
  const std::size_t end = bytes.find('\0', std::strlen(kMagic));
  if (end == std::string::npos) throw FileError(source, "the header does not end");
  const nlohmann::json header =
      ParseJson(bytes.substr(std::strlen(kMagic), end - std::strlen(kMagic)), source);
  const brdf::JsonReader reader(source);
  MeasuredPrior p;
  if (reader.String(header, "", "format") != "brdfrig-prior") {
    reader.Fail("format", "expected \"brdfrig-prior\"");
  }
  p.version = static_cast<int>(reader.Number(header, "", "version"));
  if (p.version != 1) reader.Fail("version", "this build reads version 1");
  p.name = reader.String(header, "", "name");
  const auto& grid = reader.Field(header, "", "grid");
  const auto count = [&](const nlohmann::json& object, const std::string& at, const char* key,
                         int hi) {
    const double x = reader.Number(object, at, key);
    if (x != std::floor(x) || x < 1 || x > hi) {
      reader.Fail(brdf::JsonReader::Join(at, key),
                  "expected a whole number in [1, " + std::to_string(hi) + "]");
    }
    return static_cast<int>(x);
  };
  p.grid.theta_h = count(grid, "grid", "theta_h", 512);
  p.grid.theta_d = count(grid, "grid", "theta_d", 512);
  p.grid.phi_d = count(grid, "grid", "phi_d", 512);
  p.grid.epsilon = reader.Number(grid, "grid", "epsilon");
  p.grid.cos_floor = reader.Number(grid, "grid", "cos_floor");
  try {
    p.grid.Validate();
  } catch (const Error& e) {
    reader.Fail("grid", e.what());
  }
  const int k = count(header, "", "components", 4096);
  p.noise_sigma = reader.Number(header, "", "noise_sigma");
  p.correction_weight = reader.Number(header, "", "correction_weight");
  p.built_with = reader.String(header, "", "built_with");
  const auto& training = reader.Field(header, "", "training");
  if (!training.is_array() || training.empty()) reader.Fail("training", "expected a list");
  for (std::size_t i = 0; i < training.size(); ++i) {
    const std::string at = "training[" + std::to_string(i) + "]";
    p.training.push_back(
        {reader.String(training[i], at, "name"), reader.String(training[i], at, "database"),
         reader.String(training[i], at, "licence"), reader.String(training[i], at, "sha256")});
  }
  const int cells = p.grid.Cells();
  const auto rows = static_cast<Eigen::Index>(3 * p.training.size());
  std::size_t offset = end + 1;
  const auto take = [&](std::size_t n, double* out, const char* what) {
    if (!TakeFloats(bytes, &offset, n, out)) {
      throw FileError(
          source, std::string("payload: the ") + what + " are missing, cut short or not finite");
    }
  };
  p.mean.resize(cells);
  take(cells, p.mean.data(), "mean values");
  p.components.resize(cells, k);
  take(static_cast<std::size_t>(cells) * k, p.components.data(), "components");
  p.variances.resize(k);
  take(k, p.variances.data(), "variances");
  Eigen::VectorXd row(k);
  p.training_coefficients.resize(rows, k);
  for (Eigen::Index r = 0; r < rows; ++r) {
    take(k, row.data(), "training coefficients");
    p.training_coefficients.row(r) = row.transpose();
  }
  if (offset != bytes.size()) throw FileError(source, "payload: bytes after the last array");
  try {
    p.Validate();
  } catch (const FileError&) {
    throw;
  } catch (const Error& e) {
    throw FileError(source, e.what());
  }
  return p;
}

std::filesystem::path DefaultPriorPath() {
  return std::filesystem::path(BRDFRIG_SOURCE_DIR) / "data" / "priors" / "measured.prior";
}

const MeasuredPrior& DefaultPrior() {
  static std::once_flag once;
  static MeasuredPrior prior;
  std::call_once(once, [] { prior = ReadPrior(DefaultPriorPath()); });
  return prior;
}

}  // namespace brdfrig::prior
