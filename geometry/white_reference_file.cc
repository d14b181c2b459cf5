#include "geometry/white_reference_file.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::geometry {
namespace {

constexpr const char* kWhiteReferenceFormat = "brdfrig-white-reference";

double Albedo(const nlohmann::json& j, const char* key) {
  const double v = j.at(key).get<double>();
  if (!(v > 0 && v <= 1)) throw Error(std::string(key) + " must be in (0, 1]");
  return v;
}

}  // namespace

void WriteWhiteReference(const std::filesystem::path& path, const WhiteReference& r) {
  const nlohmann::json j = {{"format", kWhiteReferenceFormat},
                            {"version", 1},
                            {"created", r.created},
                            {"software", r.software},
                            {"paper_albedo", r.paper_albedo},
                            {"reference_albedo", r.reference_albedo},
                            {"tile_spread", r.tile_spread},
                            {"per_photo", r.per_photo},
                            {"flat_field", r.flat_field},
                            {"photos", r.photos}};
  WriteFileAtomically(path, j.dump(2) + "\n");
}

WhiteReference ReadWhiteReference(const std::filesystem::path& path) {
  const nlohmann::json j = ParseJson(ReadFileToString(path), path.string());
  WhiteReference r;
  try {
    if (j.at("format").get<std::string>() != kWhiteReferenceFormat) {
      throw Error(std::string("not a white reference (format is not \"") + kWhiteReferenceFormat +
                  "\")");
    }
    if (j.at("version").get<double>() != 1) throw Error("version: only version 1 is known");
    r.created = j.at("created").get<std::string>();
    r.software = j.value("software", "");
    r.paper_albedo = Albedo(j, "paper_albedo");
    r.reference_albedo = Albedo(j, "reference_albedo");
    r.tile_spread = j.at("tile_spread").get<double>();
    if (!std::isfinite(r.tile_spread)) throw Error("tile_spread is not a finite number");
    r.per_photo = j.value("per_photo", std::vector<double>{});
    r.flat_field = j.value("flat_field", "");
    r.photos = j.value("photos", std::vector<std::string>{});
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path.string(), std::string("white reference: ") + e.what());
  } catch (const Error& e) {
    throw FileError(path.string(), std::string("white reference: ") + e.what());
  }
  return r;
}

}  // namespace brdfrig::geometry
