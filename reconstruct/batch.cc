#include "reconstruct/batch.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/option_check.h"
#include "common/sha256.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> ExpandInputs(const std::vector<fs::path>& inputs) {
  std::vector<fs::path> captures;
  for (const fs::path& input : inputs) {
    if (!fs::is_directory(input)) throw FileError(input.string(), "not a directory");
    if (IsCaptureDirectory(input)) {
      captures.push_back(input);
      continue;
    }
    std::vector<fs::path> inside;
    for (const auto& entry : fs::directory_iterator(input)) {
      if (entry.is_directory() && IsCaptureDirectory(entry.path())) inside.push_back(entry.path());
    }
    if (inside.empty()) {
      throw FileError(input.string(),
                      "neither a capture (photos/capture.json or session.sqlite) nor a directory "
                      "of captures");
    }
    std::sort(inside.begin(), inside.end());
    captures.insert(captures.end(), inside.begin(), inside.end());
  }
  return captures;
}

// Whether `path` is `root` or below it, compared component by component after resolving
// links and "..", so "session2" is not inside "session".
bool IsInside(const fs::path& path, const fs::path& root) {
  const fs::path p = fs::weakly_canonical(path), r = fs::weakly_canonical(root);
  auto [r_end, p_end] = std::mismatch(r.begin(), r.end(), p.begin(), p.end());
  return r_end == r.end() || (std::next(r_end) == r.end() && r_end->empty());
}

struct Existing {
  std::string fingerprint;  // "" when there is no readable material
  std::vector<std::string> dropped;
  std::vector<std::string> degraded;
};

Existing ExistingMaterial(const fs::path& material_file) {
  if (!fs::exists(material_file)) return {};
  try {
    const brdf::Material m = brdf::ReadMaterialFile(material_file);
    Existing existing{m.provenance.value("input_sha256", "") + "/" +
                          m.provenance.value("software", "") + "/" +
                          m.provenance.value("options", nlohmann::json()).dump(),
                      {}};
    for (const auto& p : m.provenance.value("positions", nlohmann::json::array())) {
      const std::string name = "p" + std::to_string(p.value("index", -1)) + ": ";
      if (!p.value("used", true)) {
        existing.dropped.push_back(name + p.value("skipped", std::string("?")));
      } else if (p.contains("degraded")) {
        existing.degraded.push_back(name + p.value("degraded", std::string("?")));
      }
    }
    return existing;
  } catch (const std::exception&) {
    return {};  // unreadable: redo it
  }
}

}  // namespace

void BatchOptions::Validate() const {
  if (inputs.empty()) throw OptionsError("reconstruct: no input capture given");
  if (output.empty()) throw OptionsError("reconstruct: no output given (-o)");
  CheckOption(jobs >= 1, "BatchOptions.jobs", jobs, ">= 1");
  reconstruct.Validate();
}

std::string BatchItem::StatusName() const {
  switch (status) {
    case Status::kDone:
      return Partial() ? "partial" : "done";
    case Status::kUpToDate:
      return Partial() ? "up to date, partial" : "up to date";
    case Status::kFailed:
      return "FAILED";
  }
  return "?";
}

int BatchExitStatus(const std::vector<BatchItem>& items) {
  int status = 0;
  for (const BatchItem& item : items) {
    if (item.status == BatchItem::Status::kFailed) return 1;
    if (item.Partial()) status = 3;
  }
  return status;
}

bool IsCaptureDirectory(const fs::path& dir) {
  return fs::exists(dir / "session.sqlite") || fs::exists(dir / "photos" / "capture.json") ||
         fs::exists(dir / "capture.json");
}

CaptureSet LoadCapture(const fs::path& dir) {
  return fs::exists(dir / "session.sqlite") ? LoadSessionCapture(dir) : LoadSimulatedCapture(dir);
}

std::string CaptureFingerprint(const CaptureSet& capture) {
  Sha256 hash;
  for (const CapturePosition& position : capture.positions) {
    for (const BracketFrame& frame : position.frames) {
      hash.Update(frame.file.filename().string() + "@" + std::to_string(frame.exposure_s));
      // A missing photo hashes as empty, as before; the reconstruction reports it.
      if (fs::exists(frame.file)) hash.UpdateFile(frame.file);
    }
  }
  return hash.HexDigest();
}

std::vector<BatchItem> ListBatchItems(const BatchOptions& options) {
  options.Validate();
  const std::vector<fs::path> captures = ExpandInputs(options.inputs);
  const bool single = captures.size() == 1;
  const bool to_file = single && options.output.extension() == ".json";
  // Several captures each get output/<capture name>: two of one name (archX/tile, archY/tile)
  // would overwrite each other's material.
  std::map<fs::path, fs::path> by_name;
  for (const fs::path& capture : captures) {
    const auto [it, added] = by_name.emplace(capture.filename(), capture);
    if (!added) {
      throw Error("captures " + it->second.string() + " and " + capture.string() +
                  " have the same name, so both would be written to " +
                  (options.output / capture.filename()).string() +
                  ": reconstruct them into different outputs");
    }
  }
  std::vector<BatchItem> items(captures.size());
  for (std::size_t i = 0; i < captures.size(); ++i) {
    items[i].input = captures[i];
    const fs::path dir = to_file
                             ? options.output.parent_path()
                             : (single ? options.output : options.output / captures[i].filename());
    items[i].material_file = to_file ? options.output : dir / "material.json";
  }
  return items;
}

namespace {

std::string SoftwareName() { return std::string("brdfrig ") + BRDFRIG_VERSION; }

// What an up-to-date material's provenance says: the same photos, software and options.
std::string UpToDateKey(const std::string& fingerprint, const ReconstructOptions& options) {
  return fingerprint + "/" + SoftwareName() + "/" + options.ResultKey().dump();
}

}  // namespace

bool NeedsReconstruct(const BatchItem& item, const BatchOptions& options) {
  if (options.force) return true;
  try {
    const std::string fingerprint = CaptureFingerprint(LoadCapture(item.input));
    const Existing existing = ExistingMaterial(item.material_file);
    if (existing.fingerprint != UpToDateKey(fingerprint, options.reconstruct)) return true;
    // Under --strict an earlier partial material is a failure to report, not a skip.
    return options.reconstruct.strict && (!existing.dropped.empty() || !existing.degraded.empty());
  } catch (const Error&) {
    return true;  // unreadable capture: processing it reports why
  }
}

void ProcessBatchItem(const BatchOptions& options, BatchItem& item,
                      const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::string name = item.input.filename().string();
  try {
    const CaptureSet capture = LoadCapture(item.input);
    const std::string fingerprint = CaptureFingerprint(capture);
    const Existing existing = ExistingMaterial(item.material_file);
    if (!options.force && existing.fingerprint == UpToDateKey(fingerprint, options.reconstruct)) {
      if (options.reconstruct.strict && (!existing.dropped.empty() || !existing.degraded.empty())) {
        throw Error("the material of an earlier run lacks " +
                    std::to_string(existing.dropped.size()) + " position(s) and has " +
                    std::to_string(existing.degraded.size()) +
                    " degraded, refused under --strict (nothing written)");
      }
      item.status = BatchItem::Status::kUpToDate;
      item.message = "up to date";
      item.dropped = existing.dropped;
      item.degraded = existing.degraded;
    } else {
      const fs::path out_dir = item.material_file.parent_path();
      if (IsInside(out_dir, item.input)) {
        throw Error("the output " + item.material_file.string() +
                    " lies inside the capture: a capture's recorded data is never written to");
      }
      ReconstructOptions reconstruct = options.reconstruct;
      reconstruct.hdr_dir = out_dir / "hdr";
      CreateDirectories(out_dir);
      ReconstructionResult result = Reconstruct(capture, reconstruct, [&](const std::string& m) {
        if (progress) progress(name + ": " + m);
      });
      result.material.provenance["input_sha256"] = fingerprint;
      // The material last: its presence (written atomically) is what marks the item done.
      WriteFileAtomically(out_dir / "report.txt", result.Summary());
      brdf::WriteMaterialFile(item.material_file, result.material);
      item.status = BatchItem::Status::kDone;
      item.ladder = result.ladder.Summary();
      item.dropped = result.Dropped();
      item.degraded = result.Degraded();
      item.message = std::string(brdf::ModelKindName(result.material.kind)) +
                     (brdf::IsSliceKind(result.material.kind)
                          ? " (" + std::to_string(result.material.slices.size()) + " slices)"
                          : "");
    }
  } catch (const Error& e) {
    item.status = BatchItem::Status::kFailed;
    item.message = e.what();
  } catch (const fs::filesystem_error& e) {  // one capture's paths never stop the others
    item.status = BatchItem::Status::kFailed;
    item.message = e.what();
  }
  item.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<BatchItem> ReconstructBatch(const BatchOptions& options,
                                        const ProgressCallback& progress) {
  std::vector<BatchItem> items = ListBatchItems(options);
  std::mutex mutex;
  const auto say = [&](const std::string& message) {
    std::lock_guard lock(mutex);
    if (progress) progress(message);
  };
  std::atomic<std::size_t> next{0};
  std::atomic<int> finished{0};
  const auto worker = [&] {
    for (std::size_t i = next++; i < items.size(); i = next++) {
      BatchItem& item = items[i];
      ProcessBatchItem(options, item, say);
      say("[" + std::to_string(++finished) + "/" + std::to_string(items.size()) + "] " +
          item.input.filename().string() + ": " + item.message);
    }
  };
  std::vector<std::thread> threads;
  const int jobs = std::min<int>(options.jobs, static_cast<int>(items.size()));
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  return items;
}

}  // namespace brdfrig::reconstruct
