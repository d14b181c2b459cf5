// The Khronos glTF-Validator (npm gltf-validator, pinned in tests/consumers/package.json and
// installed by scripts/setup.sh with npm ci) on what the real `brdfrig export` writes for every
// model kind, as .glb and as .gltf + .bin: 0 errors and 0 warnings; infos and hints are printed.
// Skipped only where Node.js is not installed.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "brdf/material_file.h"
#include "tests/common/run_brdfrig.h"
#include "tests/export/example_materials.h"

namespace brdfrig {
namespace {

namespace fs = std::filesystem;

const fs::path kConsumers = fs::path(BRDFRIG_SOURCE_DIR) / "tests" / "consumers";

bool HaveNode() { return std::system("command -v node > /dev/null 2>&1") == 0; }

// stdout of a shell command and its exit status.
std::pair<int, std::string> RunCommand(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, ""};
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

TEST(GltfValidatorTest, EveryKindExportsWithoutErrorsOrWarnings) {
  if (!HaveNode()) GTEST_SKIP() << "node (Debian's nodejs) is not installed: nothing can validate";
  ASSERT_TRUE(fs::exists(kConsumers / "node_modules" / "gltf-validator"))
      << "tests/consumers/node_modules is missing: run `bash scripts/setup.sh` (npm ci)";
  const fs::path dir = fs::temp_directory_path() / "brdfrig_gltf_validator";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<fs::path> outputs;
  for (brdf::ModelKind kind : brdf::kAllModelKinds) {
    const std::string name = brdf::ModelKindName(kind);
    const fs::path material = dir / (name + ".json");
    brdf::Material m = testing::ExampleMaterial(kind);
    m.provenance["cutout_m"] = {0.1, 0.07};
    brdf::WriteMaterialFile(material, m);
    for (const char* ext : {".glb", ".gltf"}) {
      const fs::path output = dir / (name + ext);
      const auto result =
          testing::RunBrdfrig("export " + material.string() + " -o " + output.string());
      ASSERT_EQ(result.status, 0) << result.output;
      ASSERT_TRUE(fs::exists(output)) << result.output;
      outputs.push_back(output);
    }
  }
  std::string command = "node " + (kConsumers / "validate_gltf.mjs").string();
  for (const fs::path& output : outputs) command += " " + output.string();
  const auto [status, out] = RunCommand(command);
  ASSERT_EQ(status, 0) << out;
  std::istringstream lines(out);
  std::string line;
  std::size_t reports = 0;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    const nlohmann::json report = nlohmann::json::parse(line);
    ++reports;
    std::printf("%s: %d errors, %d warnings, %d infos, %d hints\n",
                fs::path(report["file"].get<std::string>()).filename().c_str(),
                report["errors"].get<int>(), report["warnings"].get<int>(),
                report["infos"].get<int>(), report["hints"].get<int>());
    for (const nlohmann::json& message : report["messages"]) {
      std::printf("  %s\n", message.dump().c_str());
    }
    EXPECT_EQ(report["errors"], 0) << report.dump(1);
    EXPECT_EQ(report["warnings"], 0) << report.dump(1);
    EXPECT_EQ(report["extensionsUsed"],
              nlohmann::json({"KHR_materials_ior", "KHR_materials_specular"}));
  }
  EXPECT_EQ(reports, outputs.size());
}

}  // namespace
}  // namespace brdfrig
