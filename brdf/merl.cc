#include "brdf/merl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "brdf/orthonormal_frame.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/parallel.h"

namespace brdfrig::brdf {
namespace {

constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
constexpr std::size_t kFileBytes = 3 * sizeof(std::int32_t) + 3 * sizeof(double) * kMerlBins;

Vec3 RotateZ(const Vec3& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}
Vec3 RotateY(const Vec3& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() + s * v.z(), v.y(), -s * v.x() + c * v.z()};
}

// Table index of local-frame directions, with the reference's quantization.
int BinIndex(const Vec3& l, const Vec3& v) {
  const Vec3 h = (l + v).normalized();
  const double theta_h = std::acos(std::clamp(h.z(), -1.0, 1.0));
  const double phi_h = std::atan2(h.y(), h.x());
  const Vec3 d = RotateY(RotateZ(l, -phi_h), -theta_h);
  const double theta_d = std::acos(std::clamp(d.z(), -1.0, 1.0));
  double phi_d = std::atan2(d.y(), d.x());
  if (phi_d < 0) phi_d += M_PI;
  const int ih = std::clamp(static_cast<int>(std::sqrt(theta_h / (M_PI / 2)) * kMerlThetaH), 0,
                            kMerlThetaH - 1);
  const int id =
      std::clamp(static_cast<int>(theta_d / (M_PI / 2) * kMerlThetaD), 0, kMerlThetaD - 1);
  const int ip = std::clamp(static_cast<int>(phi_d / M_PI * kMerlPhiD), 0, kMerlPhiD - 1);
  return ip + kMerlPhiD * (id + kMerlThetaD * ih);
}

}  // namespace

MerlTable MerlTable::Read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), "cannot open MERL table");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  in.seekg(0);
  if (size != kFileBytes) {
    throw FileError(path.string(), "not a MERL table: expected " + std::to_string(kFileBytes) +
                                       " bytes, file has " + std::to_string(size));
  }
  std::int32_t dims[3];
  in.read(reinterpret_cast<char*>(dims), sizeof(dims));
  if (dims[0] != kMerlThetaH || dims[1] != kMerlThetaD || dims[2] != kMerlPhiD) {
    throw FileError(path.string(), "MERL dimensions must be 90 90 180, got " +
                                       std::to_string(dims[0]) + " " + std::to_string(dims[1]) +
                                       " " + std::to_string(dims[2]));
  }
  MerlTable table;
  table.data_.resize(3 * static_cast<std::size_t>(kMerlBins));
  in.read(reinterpret_cast<char*>(table.data_.data()),
          static_cast<std::streamsize>(table.data_.size() * sizeof(double)));
  if (!in) throw FileError(path.string(), "short read in MERL table");
  for (double x : table.data_) {
    if (std::isnan(x) || std::isinf(x)) throw FileError(path.string(), "MERL table holds NaN/Inf");
  }
  return table;
}

MerlTable MerlTable::Tabulate(const Brdf& source) {
  MerlTable table;
  table.data_.assign(3 * static_cast<std::size_t>(kMerlBins), -1.0);
  const Vec3 n = Vec3::UnitZ();
  ParallelFor(kMerlThetaH, [&](std::size_t begin, std::size_t end) {
    for (std::size_t ih = begin; ih < end; ++ih) {
      const double u = (static_cast<double>(ih) + 0.5) / kMerlThetaH;
      const double theta_h = u * u * (M_PI / 2);
      for (int id = 0; id < kMerlThetaD; ++id) {
        const double theta_d = (id + 0.5) / kMerlThetaD * (M_PI / 2);
        for (int ip = 0; ip < kMerlPhiD; ++ip) {
          const double phi_d = (ip + 0.5) / kMerlPhiD * M_PI;
          const Vec3 d(std::sin(theta_d) * std::cos(phi_d), std::sin(theta_d) * std::sin(phi_d),
                       std::cos(theta_d));
          const Vec3 l = RotateY(d, theta_h);
          const Vec3 v = RotateY(Vec3(-d.x(), -d.y(), d.z()), theta_h);
          if (l.z() <= 0 || v.z() <= 0) continue;  // below the horizon: "no data"
          const Rgb f = source.Eval(l, v, n);
          const std::size_t index = ip + kMerlPhiD * (id + kMerlThetaD * ih);
          for (int c = 0; c < 3; ++c) table.data_[c * kMerlBins + index] = f[c] / kScale[c];
        }
      }
    }
  });
  return table;
}

std::size_t MerlTable::NonFiniteCount() const {
  return std::count_if(data_.begin(), data_.end(), [](double v) { return !std::isfinite(v); });
}

void MerlTable::Write(const std::filesystem::path& path) const {
  if (const std::size_t bad = NonFiniteCount(); bad > 0) {
    throw FileError(path.string(), "not written: " + std::to_string(bad) +
                                       " of the table's values are infinite or NaN");
  }
  std::vector<std::byte> bytes(kFileBytes);
  const std::int32_t dims[3] = {kMerlThetaH, kMerlThetaD, kMerlPhiD};
  std::memcpy(bytes.data(), dims, sizeof(dims));
  std::memcpy(bytes.data() + sizeof(dims), data_.data(), data_.size() * sizeof(double));
  WriteFileAtomically(path, bytes);
}

Rgb MerlTable::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  if (n.dot(l) <= 0 || n.dot(v) <= 0) return Rgb::Zero();
  Vec3 t, b;
  OrthonormalFrame(n, &t, &b);
  const Vec3 l_local(l.dot(t), l.dot(b), l.dot(n));
  const Vec3 v_local(v.dot(t), v.dot(b), v.dot(n));
  const int index = BinIndex(l_local, v_local);
  Rgb out;
  for (int c = 0; c < 3; ++c) out[c] = std::max(0.0, data_[c * kMerlBins + index] * kScale[c]);
  return out;
}

}  // namespace brdfrig::brdf
