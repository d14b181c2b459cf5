#include "batch/task.h"

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "batch/manifest.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::batch {

namespace fs = std::filesystem;
using nlohmann::json;
using reconstruct::BatchItem;

namespace {

std::string Environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

std::string HostName() {
  std::array<char, 256> name{};
  return ::gethostname(name.data(), name.size() - 1) == 0 ? name.data() : "";
}

BatchItem::Status StatusFromName(const std::string& name) {
  if (name == "done" || name == "partial") return BatchItem::Status::kDone;
  if (name.starts_with("up to date")) return BatchItem::Status::kUpToDate;
  return BatchItem::Status::kFailed;
}

}  // namespace

int TaskIndexFromEnvironment() {
  const std::string id = Environment("SLURM_ARRAY_TASK_ID");
  if (id.empty()) {
    throw Error(
        "SLURM_ARRAY_TASK_ID is not set: not inside a Slurm job array (give --index to run "
        "one item by hand)");
  }
  // Digits only: strtol alone would take " 3" and "+3", which Slurm never sets.
  const bool digits = id.size() <= 10 && id.find_first_not_of("0123456789") == std::string::npos;
  const long index = digits ? std::strtol(id.c_str(), nullptr, 10) : -1;
  if (index < 0 || index > 1'000'000'000) {
    throw Error("SLURM_ARRAY_TASK_ID = \"" + id + "\" is not an item index");
  }
  return static_cast<int>(index);
}

TaskResult RunTask(const JobDir& dir, int index, const reconstruct::ProgressCallback& progress) {
  const Manifest manifest = ReadManifest(dir.manifest());
  const std::string software = std::string("brdfrig ") + BRDFRIG_VERSION;
  if (manifest.software != software) {
    throw FileError(dir.manifest().string(),
                    "written by " + manifest.software + ", but this is " + software +
                        ": its up-to-date decisions are not this version's; prepare the job "
                        "again with this brdfrig");
  }
  TaskResult result;
  result.index = index;
  result.item = manifest.Item(index);
  const std::string array_job = Environment("SLURM_ARRAY_JOB_ID");
  if (!array_job.empty()) result.job = array_job + "_" + Environment("SLURM_ARRAY_TASK_ID");
  result.host = HostName();
  if (fs::is_symlink(dir.results())) {  // followed, the task would write anywhere
    throw FileError(dir.results().string(), "a symbolic link: a task writes only in its job dir");
  }
  CreateDirectories(dir.results());
  // An earlier attempt's result would speak for this one if this one were killed.
  fs::remove(dir.result(index));
  reconstruct::BatchOptions options = manifest.options;
  options.inputs = {result.item.input};
  reconstruct::ProcessBatchItem(options, result.item, progress);
  result.exit_status = reconstruct::BatchExitStatus({result.item});
  WriteFileAtomically(dir.result(index), SerializeTaskResult(result));
  return result;
}

std::string SerializeTaskResult(const TaskResult& result) {
  json dropped = json::array(), degraded = json::array();
  for (const std::string& d : result.item.dropped) dropped.push_back(d);
  for (const std::string& d : result.item.degraded) degraded.push_back(d);
  return json{{"index", result.index},
              {"capture", result.item.input.string()},
              {"material", result.item.material_file.string()},
              {"status", result.item.StatusName()},
              {"exit_status", result.exit_status},
              {"message", result.item.message},
              {"dropped", dropped},
              {"degraded", degraded},
              {"seconds", result.item.seconds},
              {"job", result.job},
              {"host", result.host}}
             .dump(2) +
         "\n";
}

TaskResult ReadTaskResult(const fs::path& file) {
  try {
    const json root = ParseJson(ReadFileToString(file), file.string());
    TaskResult result;
    result.index = root.at("index").get<int>();
    result.item.input = root.at("capture").get<std::string>();
    result.item.material_file = root.at("material").get<std::string>();
    result.item.status = StatusFromName(root.at("status").get<std::string>());
    result.exit_status = root.at("exit_status").get<int>();
    result.item.message = root.at("message").get<std::string>();
    for (const json& d : root.at("dropped")) result.item.dropped.push_back(d.get<std::string>());
    for (const json& d : root.value("degraded", json::array())) {
      result.item.degraded.push_back(d.get<std::string>());
    }
    result.item.seconds = root.at("seconds").get<double>();
    result.job = root.value("job", "");
    result.host = root.value("host", "");
    return result;
  } catch (const json::exception& e) {
    throw FileError(file.string(), std::string("malformed task result: ") + e.what());
  }
}

}  // namespace brdfrig::batch
