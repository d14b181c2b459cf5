// The report sections that judge a fitted material against a simulated truth, shared by
// `brdfrig demo` and `brdfrig evaluate`: held-out views (PSNR two ways, photo / rendering /
// difference images) and the BRDF-space error with a directional-albedo energy check.
#pragma once

#include <filesystem>
#include <vector>

#include "brdf/brdf.h"
#include "evaluate/held_out.h"
#include "evaluate/report.h"

namespace brdfrig::evaluate {

// Writes views/phiN_{photo,render,diff}.png under `report_dir` (the views must have been
// evaluated with keep_images) and returns the section that shows them.
ReportSection HeldOutSection(const std::vector<HeldOutResult>& views, double elevation_deg,
                             const std::filesystem::path& report_dir);

// Log-cosine error of `fitted` against `truth` and directional albedo of both.
ReportSection BrdfSection(const brdf::Brdf& truth, const brdf::Brdf& fitted);

}  // namespace brdfrig::evaluate
