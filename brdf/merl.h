// MERL BRDF tables (Matusik et al. 2003): 90 theta_h × 90 theta_d × 180 phi_d bins per
// channel in Rusinkiewicz half/difference coordinates. Layout and scales: docs/design.md (formats).
#pragma once

#include <filesystem>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

inline constexpr int kMerlThetaH = 90;
inline constexpr int kMerlThetaD = 90;
inline constexpr int kMerlPhiD = 180;
inline constexpr int kMerlBins = kMerlThetaH * kMerlThetaD * kMerlPhiD;

class MerlTable : public Brdf {
 public:
  // Reads a .binary file; throws FileError on a wrong size, wrong dimensions or a short read.
  static MerlTable Read(const std::filesystem::path& path);
  // Samples `source` at the centre of every bin.
  static MerlTable Tabulate(const Brdf& source);

  // Writes the .binary format (atomically). Throws FileError, writing nothing, when a value is
  // infinite or NaN (a table no reader accepts).
  void Write(const std::filesystem::path& path) const;
  // How many stored values are infinite or NaN.
  std::size_t NonFiniteCount() const;

  // Nearest-bin lookup with the reference indexing. Bins holding negative values ("no data")
  // evaluate to 0.
  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  std::string Name() const override { return "merl"; }

  // Unscaled stored values, channel-major: value(c, i) = data[c * kMerlBins + i].
  const std::vector<double>& data() const { return data_; }

 private:
  std::vector<double> data_;  // 3 * kMerlBins, raw (before scale)
};

}  // namespace brdfrig::brdf
