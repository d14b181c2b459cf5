#include "batch/manifest.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::batch {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "brdfrig-batch-manifest";
constexpr int kVersion = 1;

std::string Software() { return std::string("brdfrig ") + BRDFRIG_VERSION; }

fs::path Absolute(const fs::path& p) { return fs::absolute(p).lexically_normal(); }

bool IsAbsoluteAndNormal(const fs::path& p) { return p.is_absolute() && p == p.lexically_normal(); }

// `path` is `dir` or below it (both absolute and normal), component by component.
bool IsWithin(const fs::path& path, const fs::path& dir) {
  return std::mismatch(dir.begin(), dir.end(), path.begin(), path.end()).first == dir.end();
}

}  // namespace

reconstruct::BatchItem Manifest::Item(int index) const {
  if (index < 0 || index >= static_cast<int>(items.size())) {
    throw Error("item " + std::to_string(index) + " is not in the manifest (it has " +
                std::to_string(items.size()) + " items, 0.." +
                std::to_string(static_cast<int>(items.size()) - 1) + ")");
  }
  reconstruct::BatchItem item;
  item.input = items[index].capture;
  item.material_file = items[index].material;
  return item;
}

Manifest MakeManifest(const reconstruct::BatchOptions& options,
                      const reconstruct::ProgressCallback& progress) {
  reconstruct::BatchOptions absolute = options;
  for (fs::path& input : absolute.inputs) input = Absolute(input);
  absolute.output = Absolute(options.output);
  Manifest manifest;
  manifest.software = Software();
  manifest.output = absolute.output;
  manifest.options = absolute;
  manifest.options.inputs.clear();
  for (reconstruct::BatchItem item : reconstruct::ListBatchItems(absolute)) {
    // Always <output>/<capture name>/, also for one capture (where `brdfrig reconstruct`
    // writes into <output> itself): jobs prepared one session at a time (the daemon's
    // hand-off) share one fits directory.
    item.material_file = absolute.output / item.input.filename() / "material.json";
    const bool needed = reconstruct::NeedsReconstruct(item, absolute);
    if (progress) {
      progress(item.input.filename().string() + (needed ? ": to do" : ": up to date, skipped"));
    }
    if (!needed) {
      manifest.up_to_date.push_back(item.input);
      continue;
    }
    manifest.items.push_back(
        {static_cast<int>(manifest.items.size()), item.input, item.material_file});
  }
  return manifest;
}

std::string SerializeManifest(const Manifest& manifest) {
  const reconstruct::ReconstructOptions& r = manifest.options.reconstruct;
  json root{{"format", kFormat},
            {"version", kVersion},
            {"software", manifest.software},
            {"output", manifest.output.string()},
            {"reconstruct",
             {{"model", r.model},
              {"bin_width", r.samples.bin_width},
              {"light_refine", r.light_refine.enabled},
              {"strict", r.strict},
              {"force", manifest.options.force}}},
            {"up_to_date", json::array()},
            {"items", json::array()}};
  for (const fs::path& p : manifest.up_to_date) root["up_to_date"].push_back(p.string());
  for (const ManifestItem& item : manifest.items) {
    root["items"].push_back({{"index", item.index},
                             {"capture", item.capture.string()},
                             {"material", item.material.string()}});
  }
  return root.dump(2) + "\n";
}

Manifest ReadManifest(const fs::path& file) {
  const std::string where = file.string();
  try {
    const json root = ParseJson(ReadFileToString(file), where);
    if (root.value("format", "") != kFormat || root.value("version", 0) != kVersion) {
      throw FileError(where, std::string("not a ") + kFormat + " version " +
                                 std::to_string(kVersion) + " file");
    }
    Manifest manifest;
    manifest.software = root.at("software").get<std::string>();
    manifest.output = root.at("output").get<std::string>();
    manifest.options.output = manifest.output;
    const json& r = root.at("reconstruct");
    manifest.options.reconstruct.model = r.at("model").get<std::string>();
    manifest.options.reconstruct.samples.bin_width = r.at("bin_width").get<double>();
    manifest.options.reconstruct.light_refine.enabled = r.at("light_refine").get<bool>();
    manifest.options.reconstruct.strict = r.at("strict").get<bool>();
    manifest.options.force = r.at("force").get<bool>();
    manifest.options.jobs = 1;
    for (const json& p : root.at("up_to_date"))
      manifest.up_to_date.emplace_back(p.get<std::string>());
    for (const json& item : root.at("items")) {
      ManifestItem m{item.at("index").get<int>(), item.at("capture").get<std::string>(),
                     item.at("material").get<std::string>()};
      if (m.index != static_cast<int>(manifest.items.size())) {
        throw FileError(where, "items must be numbered 0, 1, 2, ... in order; item " +
                                   std::to_string(manifest.items.size()) + " has index " +
                                   std::to_string(m.index));
      }
      // A task writes only where MakeManifest put it: <output>/<capture name>/, never into a
      // capture (a tampered path would make it overwrite any file).
      const std::string item_name = "item " + std::to_string(m.index);
      if (!IsAbsoluteAndNormal(m.capture) || !IsAbsoluteAndNormal(manifest.output)) {
        throw FileError(where, item_name +
                                   ": capture and output paths must be absolute, "
                                   "without '.' or '..'");
      }
      const fs::path expected = manifest.output / m.capture.filename() / "material.json";
      if (m.material != expected) {
        throw FileError(where, item_name + ": material " + m.material.string() + " is not " +
                                   expected.string() + " (<output>/<capture name>/material.json)");
      }
      if (IsWithin(manifest.output, m.capture)) {
        throw FileError(where, item_name + ": the output " + manifest.output.string() +
                                   " lies inside the capture " + m.capture.string());
      }
      manifest.items.push_back(m);
    }
    manifest.options.reconstruct.Validate();
    return manifest;
  } catch (const json::exception& e) {
    throw FileError(where, std::string("malformed manifest: ") + e.what());
  } catch (const OptionsError& e) {
    throw FileError(where, std::string("reconstruct settings: ") + e.what());
  }
}

void WriteManifest(const fs::path& file, const Manifest& manifest) {
  WriteFileAtomically(file, SerializeManifest(manifest));
}

}  // namespace brdfrig::batch
