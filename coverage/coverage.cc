#include "coverage/coverage.h"
#include "common/angles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "common/error.h"

namespace brdfrig::coverage {
namespace {

constexpr double kHalfPi = M_PI / 2;

double AngleBetween(const geometry::Vec3& a, const geometry::Vec3& b) {
  return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
}

bool InImage(const geometry::Intrinsics& k, const geometry::CameraPose& pose,
             const geometry::Vec3& x) {
  Eigen::Vector2d pixel;
  return geometry::ProjectToPixel(k, pose, x, &pixel) && pixel.x() >= 0 && pixel.y() >= 0 &&
         pixel.x() < k.width && pixel.y() < k.height;
}

}  // namespace

void GridOptions::Validate() const {
  const auto check = [](const char* field, int value, int lo, int hi) {
    if (value < lo || value > hi) {
      throw OptionsError("coverage grid: " + std::string(field) + " = " + std::to_string(value) +
                         " must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    }
  };
  check("theta_h_bins", theta_h_bins, 4, 512);
  check("theta_d_bins", theta_d_bins, 4, 512);
  check("samples_per_side", samples_per_side, 2, 1001);
}

HalfDiff ToHalfDiff(const geometry::Vec3& l, const geometry::Vec3& v) {
  const geometry::Vec3 h = (l + v).normalized();
  return {AngleBetween(h, geometry::Vec3::UnitZ()), AngleBetween(l, h)};
}

int ThetaHBin(double theta_h, int bins) {
  const double u = std::sqrt(std::clamp(theta_h / kHalfPi, 0.0, 1.0));
  return std::min(bins - 1, static_cast<int>(u * bins));
}

int ThetaDBin(double theta_d, int bins) {
  return std::min(bins - 1, static_cast<int>(std::clamp(theta_d / kHalfPi, 0.0, 1.0) * bins));
}

double ThetaHEdge(int i, int bins) {
  const double u = static_cast<double>(i) / bins;
  return u * u * kHalfPi;
}

double ThetaDEdge(int i, int bins) { return static_cast<double>(i) / bins * kHalfPi; }

PositionCoverage PositionCoverageAt(const geometry::RigGeometry& rig,
                                    const geometry::AxisPositions& axes, const GridOptions& grid) {
  PositionCoverage c;
  c.axes = axes;
  const geometry::CameraPose pose = rig.CameraAt(axes);
  const geometry::Vec3 camera = pose.CenterInWorld();
  const geometry::Vec3 light = rig.LightAt(axes);
  if (camera.z() <= 0) {
    c.problem = "the camera is below the sample plane";
    return c;
  }
  if (light.z() <= 0) {
    c.problem = "the light is below the sample plane";
    return c;
  }
  c.theta_in = AngleBetween(light.normalized(), geometry::Vec3::UnitZ());
  c.theta_out = AngleBetween(camera.normalized(), geometry::Vec3::UnitZ());
  std::set<int> cells;
  c.theta_h_min = c.theta_d_min = M_PI;
  const int n = grid.samples_per_side;
  for (int iy = 0; iy < n; ++iy) {
    for (int ix = 0; ix < n; ++ix) {
      const geometry::Vec3 x((ix / (n - 1.0) - 0.5) * rig.target.cutout_width,
                             (iy / (n - 1.0) - 0.5) * rig.target.cutout_height, 0);
      if (!InImage(rig.intrinsics, pose, x)) continue;
      const HalfDiff hd = ToHalfDiff((light - x).normalized(), (camera - x).normalized());
      c.theta_h_min = std::min(c.theta_h_min, hd.theta_h);
      c.theta_h_max = std::max(c.theta_h_max, hd.theta_h);
      c.theta_d_min = std::min(c.theta_d_min, hd.theta_d);
      c.theta_d_max = std::max(c.theta_d_max, hd.theta_d);
      cells.insert(ThetaHBin(hd.theta_h, grid.theta_h_bins) * grid.theta_d_bins +
                   ThetaDBin(hd.theta_d, grid.theta_d_bins));
    }
  }
  if (cells.empty()) {
    c.problem = "no point of the cut-out is inside the image";
    c.theta_h_min = c.theta_d_min = 0;
    return c;
  }
  c.observed = true;
  c.cells.assign(cells.begin(), cells.end());
  return c;
}

namespace {

// PositionCoverage::shared_cells and the map's shared fractions, over the fitted positions.
void ShareCells(CoverageMap* map) {
  const int d_bins = map->grid.theta_d_bins;
  std::map<int, int> cell_seers, h_seers;  // how many fitted positions see each cell / θh bin
  std::vector<std::set<int>> h_of(map->positions.size());
  for (std::size_t i = 0; i < map->positions.size(); ++i) {
    const PositionCoverage& c = map->positions[i];
    for (int cell : c.cells) h_of[i].insert(cell / d_bins);
    if (c.validation) continue;
    for (int cell : c.cells) ++cell_seers[cell];
    for (int h : h_of[i]) ++h_seers[h];
  }
  long cells = 0, shared = 0, hs = 0, shared_h = 0;
  for (std::size_t i = 0; i < map->positions.size(); ++i) {
    PositionCoverage& c = map->positions[i];
    const int self = c.validation ? 0 : 1;  // a fitted position counts itself once
    c.shared_cells = 0;
    for (int cell : c.cells) c.shared_cells += cell_seers[cell] > self;
    c.theta_h_bins = static_cast<int>(h_of[i].size());
    c.shared_theta_h_bins = 0;
    for (int h : h_of[i]) c.shared_theta_h_bins += h_seers[h] > self;
    if (c.validation) continue;
    cells += static_cast<long>(c.cells.size());
    shared += c.shared_cells;
    hs += c.theta_h_bins;
    shared_h += c.shared_theta_h_bins;
  }
  map->shared_cell_fraction = cells ? static_cast<double>(shared) / cells : 0;
  map->shared_theta_h_fraction = hs ? static_cast<double>(shared_h) / hs : 0;
}

}  // namespace

CoverageMap ComputeCoverage(const geometry::RigGeometry& rig,
                            const std::vector<geometry::AxisPositions>& positions,
                            const std::vector<bool>& validation, const GridOptions& grid) {
  grid.Validate();
  CoverageMap map;
  map.grid = grid;
  std::set<int> fit, all;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    PositionCoverage c = PositionCoverageAt(rig, positions[i], grid);
    c.validation = i < validation.size() && validation[i];
    all.insert(c.cells.begin(), c.cells.end());
    if (!c.validation) fit.insert(c.cells.begin(), c.cells.end());
    map.positions.push_back(std::move(c));
  }
  const double total = static_cast<double>(grid.theta_h_bins) * grid.theta_d_bins;
  map.covered_fraction = fit.size() / total;
  std::set<int> h_bins, d_bins;
  for (const int cell : fit) {
    h_bins.insert(cell / grid.theta_d_bins);
    d_bins.insert(cell % grid.theta_d_bins);
  }
  map.theta_h_fraction = static_cast<double>(h_bins.size()) / grid.theta_h_bins;
  map.theta_d_fraction = static_cast<double>(d_bins.size()) / grid.theta_d_bins;
  map.covered_fraction_with_validation = all.size() / total;
  ShareCells(&map);
  return map;
}

std::string CoverageMap::ToString() const {
  std::ostringstream out;
  out << "coverage in (theta_h, theta_d), " << grid.theta_h_bins << " x " << grid.theta_d_bins
      << " cells (theta_h sqrt-warped), " << grid.samples_per_side << "^2 cut-out points\n";
  out << "position  role        theta_in  theta_out  theta_h range     theta_d range     cells  "
         "shared\n";
  char row[200];
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const PositionCoverage& c = positions[i];
    const char* role = c.validation ? "validation" : "fit";
    if (!c.observed) {
      std::snprintf(row, sizeof row, "%8zu  %-10s  not observed: %s\n", i, role, c.problem.c_str());
    } else {
      std::snprintf(row, sizeof row,
                    "%8zu  %-10s  %7.1f°  %8.1f°  %5.1f° .. %5.1f°  %5.1f° .. %5.1f°  %5zu  %6d\n",
                    i, role, Degrees(c.theta_in), Degrees(c.theta_out), Degrees(c.theta_h_min),
                    Degrees(c.theta_h_max), Degrees(c.theta_d_min), Degrees(c.theta_d_max),
                    c.cells.size(), c.shared_cells);
    }
    out << row;
  }
  std::snprintf(row, sizeof row, "covered fraction of the (theta_h, theta_d) domain: %.1f %%",
                100 * covered_fraction);
  out << row;
  if (covered_fraction_with_validation != covered_fraction) {
    std::snprintf(row, sizeof row, " (%.1f %% with the validation positions)",
                  100 * covered_fraction_with_validation);
    out << row;
  }
  std::snprintf(row, sizeof row, "; theta_h bins seen %.0f %%, theta_d bins seen %.0f %%\n",
                100 * theta_h_fraction, 100 * theta_d_fraction);
  out << row;
  std::snprintf(row, sizeof row,
                "seen by another fitted position too (\"shared\"): %.1f %% of the fitted "
                "positions' cells, %.0f %% of their theta_h bins\n",
                100 * shared_cell_fraction, 100 * shared_theta_h_fraction);
  out << row;
  return out.str();
}

}  // namespace brdfrig::coverage
