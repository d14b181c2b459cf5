// The "Model ladder" section of a report (the demo's; any job that reconstructs): every rung
// the reconstruction fitted, with its kind, held-out scores (leave-one-position-out folds and
// the capture's validation photos), size, fit time and whether it was chosen, then the chosen
// rung's fit diagnostics (its slices, or its microfacet parameters and fit summary). Built from
// the LadderResult, stored in report.json as a job section (evaluate::SectionJson).
#pragma once

#include "evaluate/report.h"
#include "reconstruct/fit_ladder.h"

namespace brdfrig::jobs {

evaluate::ReportSection LadderSection(const reconstruct::LadderResult& ladder);

// One sentence naming the model that was written, e.g. "the ggx rung (analytic microfacet),
// chosen by validation among 5 rungs": what the demo's overview says it reconstructed.
std::string ChosenModelPhrase(const reconstruct::LadderResult& ladder);

}  // namespace brdfrig::jobs
