#include "calibrate/charuco_spec.h"

#include <algorithm>
#include <array>
#include <opencv2/aruco/charuco.hpp>
#include <utility>

#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::calibrate {
namespace {

struct NamedDictionary {
  const char* name;
  cv::aruco::PREDEFINED_DICTIONARY_NAME id;
  int size;
};

constexpr std::array<NamedDictionary, 17> kDictionaries = {{
    {"DICT_4X4_50", cv::aruco::DICT_4X4_50, 50},
    {"DICT_4X4_100", cv::aruco::DICT_4X4_100, 100},
    {"DICT_4X4_250", cv::aruco::DICT_4X4_250, 250},
    {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000, 1000},
    {"DICT_5X5_50", cv::aruco::DICT_5X5_50, 50},
    {"DICT_5X5_100", cv::aruco::DICT_5X5_100, 100},
    {"DICT_5X5_250", cv::aruco::DICT_5X5_250, 250},
    {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000, 1000},
    {"DICT_6X6_50", cv::aruco::DICT_6X6_50, 50},
    {"DICT_6X6_100", cv::aruco::DICT_6X6_100, 100},
    {"DICT_6X6_250", cv::aruco::DICT_6X6_250, 250},
    {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000, 1000},
    {"DICT_7X7_50", cv::aruco::DICT_7X7_50, 50},
    {"DICT_7X7_100", cv::aruco::DICT_7X7_100, 100},
    {"DICT_7X7_250", cv::aruco::DICT_7X7_250, 250},
    {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000, 1000},
    {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL, 1024},
}};

const NamedDictionary& Find(const std::string& name) {
  for (const NamedDictionary& d : kDictionaries) {
    if (name == d.name) return d;
  }
  std::string known;
  for (const NamedDictionary& d : kDictionaries)
    known += std::string(known.empty() ? "" : ", ") + d.name;
  throw Error("unknown ArUco dictionary '" + name + "' (known: " + known + ")");
}

}  // namespace

cv::Ptr<cv::aruco::Dictionary> DictionaryNamed(const std::string& name) {
  return cv::aruco::getPredefinedDictionary(Find(name).id);
}

int DictionarySize(const std::string& name) { return Find(name).size; }

void CharucoSpec::Validate() const {
  CheckOption(squares_x >= 3 && squares_x <= 64, "CharucoSpec.squares_x", squares_x, "in 3..64");
  CheckOption(squares_y >= 3 && squares_y <= 64, "CharucoSpec.squares_y", squares_y, "in 3..64");
  CheckOption(square_m > 0.001 && square_m < 1, "CharucoSpec.square_m", square_m,
              "in (0.001, 1) metres");
  CheckOption(marker_m > 0.2 * square_m && marker_m < square_m, "CharucoSpec.marker_m", marker_m,
              "between 0.2 and 1 times square_m (the marker sits inside a square)");
  int size = 0;
  try {
    size = DictionarySize(dictionary);
  } catch (const Error& e) {
    throw OptionsError(std::string("CharucoSpec.dictionary: ") + e.what());
  }
  CheckOption(Markers() <= size, "CharucoSpec.squares_x * squares_y / 2", Markers(),
              "at most the " + std::to_string(size) + " markers of " + dictionary);
  CheckOption(page_width_m >= BoardWidth(), "CharucoSpec.page_width_m", page_width_m,
              "at least the board's width, squares_x * square_m = " + std::to_string(BoardWidth()));
  CheckOption(page_height_m >= BoardHeight() + 2 * kScaleStripM, "CharucoSpec.page_height_m",
              page_height_m,
              "at least the board's height plus room for the title and the scale bar (" +
                  std::to_string(BoardHeight() + 2 * kScaleStripM) + ")");
}

Eigen::Vector2d CharucoSpec::OriginOnPage() const {
  // Centred across; down the page, centred in what the scale strip leaves.
  return {0.5 * (page_width_m - BoardWidth()),
          0.5 * (page_height_m - kScaleStripM - BoardHeight())};
}

cv::Ptr<cv::aruco::CharucoBoard> CharucoSpec::MakeBoard() const {
  Validate();
  return cv::aruco::CharucoBoard::create(squares_x, squares_y, static_cast<float>(square_m),
                                         static_cast<float>(marker_m), DictionaryNamed(dictionary));
}

nlohmann::json CharucoSpec::ToJson() const {
  return {{"type", "charuco"},        {"squares", {squares_x, squares_y}},
          {"square_m", square_m},     {"marker_m", marker_m},
          {"dictionary", dictionary}, {"page_m", {page_width_m, page_height_m}}};
}

CharucoSpec CharucoSpec::FromJson(const nlohmann::json& j, const std::string& source) {
  CharucoSpec spec;
  try {
    if (j.at("type").get<std::string>() != "charuco") throw Error("board type is not charuco");
    // Read as numbers and range-checked before the cast (1e300 would overflow an int).
    const double x = j.at("squares").at(0).get<double>(), y = j.at("squares").at(1).get<double>();
    if (!(x >= 3 && x <= 64 && y >= 3 && y <= 64)) throw Error("squares: each in 3..64");
    spec.squares_x = static_cast<int>(x);
    spec.squares_y = static_cast<int>(y);
    spec.square_m = j.at("square_m").get<double>();
    spec.marker_m = j.at("marker_m").get<double>();
    spec.dictionary = j.at("dictionary").get<std::string>();
    spec.page_width_m = j.at("page_m").at(0).get<double>();
    spec.page_height_m = j.at("page_m").at(1).get<double>();
    spec.Validate();
  } catch (const nlohmann::json::exception& e) {
    throw FileError(source, std::string("board: ") + e.what());
  } catch (const Error& e) {
    throw FileError(source, std::string("board: ") + e.what());
  }
  return spec;
}

CharucoSpec CharucoSpec::FromYaml(const YamlNode& node) {
  CharucoSpec spec;
  if (auto squares = node.Optional("squares")) {
    const std::vector<double> v = squares->AsDoubles();
    if (v.size() != 2) squares->Fail("expected [across, down]");
    spec.squares_x = static_cast<int>(squares->InRange(v[0], 3, 64));
    spec.squares_y = static_cast<int>(squares->InRange(v[1], 3, 64));
  }
  if (auto s = node.Optional("square_mm")) spec.square_m = 1e-3 * s->Positive(s->AsDouble());
  if (auto m = node.Optional("marker_mm")) spec.marker_m = 1e-3 * m->Positive(m->AsDouble());
  if (auto d = node.Optional("dictionary")) {
    spec.dictionary = d->AsString();
    try {
      DictionarySize(spec.dictionary);
    } catch (const Error& e) {
      d->Fail(e.what());
    }
  }
  if (auto page = node.Optional("page_mm")) {
    const std::vector<double> v = page->AsDoubles();
    if (v.size() != 2) page->Fail("expected [width, height]");
    spec.page_width_m = 1e-3 * page->Positive(v[0]);
    spec.page_height_m = 1e-3 * page->Positive(v[1]);
  }
  try {
    spec.Validate();
  } catch (const OptionsError& e) {
    node.Fail(e.what());
  }
  node.Finish();
  return spec;
}

}  // namespace brdfrig::calibrate
