// The manifest of a sharded reconstruction: the captures of an archive that need a
// reconstruction (those whose material is up to date are left out, by the same rule as
// `brdfrig reconstruct`), each with its index in the job array, and the reconstruction
// settings every task uses, so that a task's material is byte for byte the one a local batch
// run writes.
//
//   {"format": "brdfrig-batch-manifest", "version": 1, "software": "brdfrig 0.1.0",
//    "output": "/srv/fits",
//    "reconstruct": {"model": "", "bin_width": 0.000349, "light_refine": true,
//                    "strict": false, "force": false},
//    "up_to_date": ["/srv/archive/s1"],
//    "items": [{"index": 0, "capture": "/srv/archive/s2",
//               "material": "/srv/fits/s2/material.json"}]}
//
// Paths are absolute: a task runs on any node, from any working directory.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "reconstruct/batch.h"

namespace brdfrig::batch {

struct ManifestItem {
  int index = 0;
  std::filesystem::path capture, material;
};

struct Manifest {
  std::string software;  // the brdfrig that wrote it; a task of another version refuses
  std::filesystem::path output;
  // Only the fields a user sets on the command line are kept (model, bin width, light
  // refinement, strict, force); everything else is the default of the running version.
  reconstruct::BatchOptions options;
  std::vector<std::filesystem::path> up_to_date;  // skipped captures, for the report
  std::vector<ManifestItem> items;

  // The batch options a task runs item `index` with (inputs = that capture), and the item.
  reconstruct::BatchItem Item(int index) const;
};

// Lists the captures `options.inputs` name and keeps those NeedsReconstruct says need it, each
// fitted into <output>/<capture name>/ (also when there is only one). Paths are made absolute.
// `progress` hears one line per capture checked.
Manifest MakeManifest(const reconstruct::BatchOptions& options,
                      const reconstruct::ProgressCallback& progress = {});

std::string SerializeManifest(const Manifest& manifest);
// Throws FileError naming the file for anything malformed or missing.
Manifest ReadManifest(const std::filesystem::path& file);
void WriteManifest(const std::filesystem::path& file, const Manifest& manifest);

}  // namespace brdfrig::batch
