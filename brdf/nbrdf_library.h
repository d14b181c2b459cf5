// The measured materials shipped with the repository (data/materials/nbrdf/), by name, so that
// scenes and tools can say `gold-metallic-paint` instead of a path.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "brdf/nbrdf.h"

namespace brdfrig::brdf {

// data/materials/nbrdf/ of the source tree this program was built from.
std::filesystem::path NbrdfDirectory();

// Names of the shipped materials (file names without ".json"), sorted.
std::vector<std::string> NbrdfMaterialNames();

// The study set (data/materials/nbrdf/study_set.txt): the 27 materials the tests and the
// pre-prior studies iterate over; the other shipped materials train the prior.
std::vector<std::string> NbrdfStudyMaterialNames();

// The file of a shipped material. Throws brdfrig::Error listing the known names when `name` is
// not one of them (a name is never a path: "../x" is refused).
std::filesystem::path NbrdfMaterialPath(const std::string& name);

// Reads a shipped material by name.
NeuralBrdf ReadNbrdfMaterial(const std::string& name);

}  // namespace brdfrig::brdf
