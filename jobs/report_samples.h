// The measured BRDF samples a report draws beside the models' curves (evaluate/brdf_plots.h):
// the capture's fitted positions measured as the reconstruction measures them
// (reconstruct::MeasurePosition), their direction samples in the sample's frame. The
// reconstruction's result keeps the material, not its samples, so a report measures again
// (a few seconds per position).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "evaluate/brdf_plots.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/measure_position.h"

namespace brdfrig::jobs {

// Every position of `capture` that is not a validation position; one that cannot be measured
// is left out (and said through `say`), as the reconstruction drops it.
std::vector<evaluate::MeasuredSample> MeasureReportSamples(
    const reconstruct::CaptureSet& capture, const reconstruct::MeasureOptions& options = {},
    const std::function<void(const std::string&)>& say = {});

}  // namespace brdfrig::jobs
