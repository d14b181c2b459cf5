// Which part of the isotropic BRDF domain a capture position observes, from the rig's nominal
// geometry alone. An isotropic BRDF is mostly a function of the half-vector angle θh and the
// difference angle θd (Rusinkiewicz); a photo sees, across the cut-out, a small patch of that
// square. Points spread over the cut-out give l and v from the nominal light and camera, hence
// (θh, θd) per point, hence the occupied cells of a grid over [0, π/2]².
//
// The θh axis is sqrt-warped like MERL's tables (bin = floor(sqrt(θh / (π/2)) · N)): the
// specular peak lives in the first few degrees of θh and needs the finer cells there; a linear
// axis would lump the whole peak of a glossy sample into one or two cells.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::coverage {

struct GridOptions {
  // 32 × 32 cells: a θd cell is 2.8°, about half the spread one photo of a 100 mm cut-out at
  // 0.5 m gives (±w/2d ≈ ±5.7°), so a photo's patch is a few cells wide and the covered
  // fraction resolves it; the first θh cell ends at 0.09°, the eighth at 5.5° (the edge of a
  // mirror photo's patch), so the peak is resolved too. Finer grids would measure the sampling
  // density of the cut-out points rather than the patch.
  int theta_h_bins = 32;
  int theta_d_bins = 32;
  // Points per side of the cut-out; enough that neighbouring points land in neighbouring cells
  // (a 100 mm cut-out: 41 points are 2.5 mm ≈ 0.3° apart).
  int samples_per_side = 41;
  void Validate() const;  // throws OptionsError naming field, value and rule
};

// The Rusinkiewicz angles of one (l, v) pair about the normal +z (unit vectors).
struct HalfDiff {
  double theta_h = 0, theta_d = 0;
};
HalfDiff ToHalfDiff(const geometry::Vec3& l, const geometry::Vec3& v);

// Cell indices (0-based; the cell id is h_bin * theta_d_bins + d_bin).
int ThetaHBin(double theta_h, int bins);
int ThetaDBin(double theta_d, int bins);
// Lower edge (radians) of θh bin i (i = bins gives π/2).
double ThetaHEdge(int i, int bins);
double ThetaDEdge(int i, int bins);

struct PositionCoverage {
  geometry::AxisPositions axes;  // radians
  bool validation = false;       // a validation position: captured, not fitted
  // False when nothing of the cut-out is seen lit: camera or light below the sample plane, or
  // no cut-out point projecting into the image. `problem` says which.
  bool observed = false;
  std::string problem;
  double theta_h_min = 0, theta_h_max = 0;  // over the cut-out points seen (radians)
  double theta_d_min = 0, theta_d_max = 0;
  double theta_in = 0, theta_out = 0;  // at the cut-out centre (radians)
  std::vector<int> cells;              // occupied cell ids, ascending
  // Of this position's cells and θh bins, how many another fitted position also sees (set by
  // ComputeCoverage). Leave-one-position-out validation predicts a held-out photo from the
  // others: only in the shared part does it judge how a model interpolates; elsewhere it judges
  // extrapolation to a region no remaining photo sees, which the model fitted to every photo
  // never has to do.
  int shared_cells = 0;
  int theta_h_bins = 0, shared_theta_h_bins = 0;
};

// Coverage of one position (whatever its role).
PositionCoverage PositionCoverageAt(const geometry::RigGeometry& rig,
                                    const geometry::AxisPositions& axes, const GridOptions& grid);

struct CoverageMap {
  GridOptions grid;
  std::vector<PositionCoverage> positions;
  // Fraction of the grid's cells seen by at least one fitted (non-validation) position, and by
  // any position (fit and validation together).
  double covered_fraction = 0;
  double covered_fraction_with_validation = 0;
  // Fractions of the θh bins and of the θd bins seen at all by the fitted positions: how much of
  // a shared D(θh) and F(θd) the plan constrains.
  double theta_h_fraction = 0, theta_d_fraction = 0;
  // Over the fitted positions: the fraction of their cells, and of their θh bins, that another
  // fitted position also sees (PositionCoverage::shared_cells).
  double shared_cell_fraction = 0, shared_theta_h_fraction = 0;
  // A table: per position the θh and θd ranges, cells, then the fractions.
  std::string ToString() const;
};

CoverageMap ComputeCoverage(const geometry::RigGeometry& rig,
                            const std::vector<geometry::AxisPositions>& positions,
                            const std::vector<bool>& validation, const GridOptions& grid = {});

// An SVG map: θh (sqrt-warped axis, ticks in degrees) across, θd up, one colour per position
// (validation positions drawn hatched), with a legend and the covered fraction in the title.
std::string CoverageSvg(const CoverageMap& map, const std::string& title);

}  // namespace brdfrig::coverage
