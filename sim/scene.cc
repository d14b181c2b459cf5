#include "sim/scene.h"

#include <cmath>
#include <sstream>

#include "common/angles.h"
#include "coverage/design_request.h"
#include "sim/sample_brdf.h"
#include "sim/yaml_values.h"

namespace brdfrig::sim {
namespace {

SampleDescription ParseSample(const YamlNode& node, const std::filesystem::path& base_dir,
                              const geometry::TargetGeometry& target) {
  SampleDescription s;
  s.brdf = ParseSampleBrdf(node.Required("brdf"), base_dir);
  // By default the sample fills the whole cut-out and then some (it lies under the paper).
  s.width = target.paper_width;
  s.height = target.paper_height;
  if (auto size = node.Optional("size")) {
    std::tie(s.width, s.height) = ReadPair(*size);
    size->Positive(std::min(s.width, s.height));
  }
  node.Finish();
  return s;
}

SensorDescription ParseSensor(const YamlNode& node) {
  SensorDescription s;
  const std::string format = node.Get("format", "png16");
  if (const auto named = PhotoFormatNamed(format)) {
    s.format = *named;
  } else {
    node.Required("format").Fail("expected png16, tiff16 or jpeg8, got '" + format + "'");
  }
  if (auto gain = node.Optional("gain")) s.gain = gain->Positive(gain->AsDouble());
  if (auto q = node.Optional("jpeg_quality")) s.jpeg_quality = q->InRange(q->AsInt(), 1, 100);
  if (auto range = node.Optional("exposure_range_s")) {
    std::tie(s.min_exposure_s, s.max_exposure_s) = ReadPair(*range);
    range->Positive(s.min_exposure_s);
    if (!(s.min_exposure_s < s.max_exposure_s)) range->Fail("expected [min, max] with min < max");
  }
  if (auto speeds = node.Optional("shutter_speeds")) {
    s.shutter_speeds = speeds->AsDoubles();
    if (s.shutter_speeds.empty()) speeds->Fail("expected at least one shutter speed");
    for (double t : s.shutter_speeds) speeds->Positive(t);
  }
  s.model = node.Get("model", s.model);
  node.Finish();
  return s;
}

RenderSettings ParseRender(const YamlNode& node) {
  RenderSettings r;
  if (auto ss = node.Optional("supersampling")) r.supersampling = ss->InRange(ss->AsInt(), 1, 16);
  if (auto seed = node.Optional("seed")) {
    r.seed = static_cast<std::uint64_t>(seed->InRange(seed->AsDouble(), 0, 9.0e15));
  }
  node.Finish();
  return r;
}

AxisTiming ParseAxisTiming(const YamlNode& node, AxisTiming t) {
  if (auto v = node.Optional("speed_deg_s")) t.speed = Radians(v->Positive(v->AsDouble()));
  if (auto a = node.Optional("acceleration_deg_s2")) {
    t.acceleration = Radians(a->Positive(a->AsDouble()));
  }
  node.Finish();
  return t;
}

TimingDescription ParseTiming(const YamlNode& node, const geometry::RigGeometry& rig) {
  TimingDescription t;
  if (auto axes = node.Optional("axes")) {
    t.default_axis = ParseAxisTiming(*axes, t.default_axis);
  }
  if (auto per_axis = node.Optional("per_axis")) {
    for (const std::string& name : per_axis->Keys()) {
      const YamlNode entry = per_axis->Required(name);
      if (!rig.FindAxis(name)) entry.Fail("no axis named '" + name + "' in rig.axes");
      t.axes[name] = ParseAxisTiming(entry, t.default_axis);
    }
  }
  auto non_negative = [&](const char* key, double fallback) {
    auto v = node.Optional(key);
    return v ? v->InRange(v->AsDouble(), 0, 3600) : fallback;
  };
  t.shot_overhead_s = non_negative("shot_overhead_s", t.shot_overhead_s);
  t.download_s = non_negative("download_s", t.download_s);
  t.reopen_s = non_negative("reopen_s", t.reopen_s);
  t.real_time_factor = non_negative("real_time_factor", t.real_time_factor);
  node.Finish();
  return t;
}

geometry::AxisPositions ParsePositionDegrees(const YamlNode& node,
                                             const geometry::RigGeometry& rig) {
  geometry::AxisPositions positions;
  for (const std::string& name : node.Keys()) {
    if (name == "validation") continue;  // the position's role, read by ParseCapture
    const YamlNode value = node.Required(name);
    const geometry::RotationAxis* axis = rig.FindAxis(name);
    if (!axis) value.Fail("no axis named '" + name + "' in rig.axes");
    const double angle = Radians(value.AsDouble());
    if (angle < axis->min - 1e-9 || angle > axis->max + 1e-9) {
      value.InRange(Degrees(angle), Degrees(axis->min), Degrees(axis->max));
    }
    positions[name] = angle;
  }
  return positions;
}

CapturePlan ParseCapture(const YamlNode& node, const geometry::RigGeometry& rig) {
  CapturePlan c;
  if (auto exposures = node.Optional("exposures")) {
    c.exposures = exposures->AsDoubles();
    for (double t : c.exposures) exposures->Positive(t);
  }
  if (auto positions = node.Optional("positions")) {
    if (positions->IsMap()) {
      const YamlNode request = positions->Required("design");
      positions->Finish();
      const coverage::DesignOptions options = coverage::ParseDesignRequest(request);
      coverage::PlanDesign design;
      try {
        design = coverage::DesignPlan(rig, options);
      } catch (const Error& e) {
        request.Fail(e.what());
      }
      c.positions = design.Positions();
      c.validation = design.Validation();
      c.design = design.ToString();
    } else {
      for (const YamlNode& item : positions->Elements()) {
        bool validation = false;
        if (auto v = item.Optional("validation")) validation = v->AsBool();
        c.positions.push_back(ParsePositionDegrees(item, rig));
        c.validation.push_back(validation);
      }
    }
  }
  node.Finish();
  return c;
}

SimFault ParseFault(const YamlNode& node, const geometry::RigGeometry& rig) {
  SimFault f{};
  const YamlNode type = node.Required("type");
  const std::string name = type.AsString();
  auto count = [&](const char* key, int lo, int fallback) {
    auto v = node.Optional(key);
    return v ? static_cast<int>(v->InRange(v->AsInt(), lo, 1e9)) : fallback;
  };
  if (name == "camera_disconnect") {
    f.type = SimFault::Type::kCameraDisconnect;
    const YamlNode after = node.Required("after_shots");
    f.at = static_cast<int>(after.InRange(after.AsInt(), 0, 1e9));
    f.count = count("reopen_failures", 0, 0);
  } else if (name == "camera_busy") {
    f.type = SimFault::Type::kCameraBusy;
    f.at = count("at_shot", 1, 1);
    f.count = count("count", 1, 1);
  } else if (name == "slow_download") {
    f.type = SimFault::Type::kSlowDownload;
    f.at = count("at_shot", 1, 1);
    f.count = count("count", 1, 1);
    const YamlNode d = node.Required("duration_s");
    f.duration_s = d.InRange(d.AsDouble(), 0, 3600);
  } else if (name == "axis_alarm") {
    f.type = SimFault::Type::kAxisAlarm;
    const YamlNode axis = node.Required("axis");
    f.axis = axis.AsString();
    if (!rig.FindAxis(f.axis)) axis.Fail("no axis named '" + f.axis + "' in rig.axes");
    f.at = count("at_move", 1, 1);
    f.alarm_code = count("alarm_code", 1, f.alarm_code);
  } else {
    type.Fail("unknown fault '" + name +
              "' (known: camera_disconnect, camera_busy, slow_download, axis_alarm)");
  }
  node.Finish();
  return f;
}

}  // namespace

std::optional<PhotoFormat> PhotoFormatNamed(const std::string& name) {
  if (name == "png16") return PhotoFormat::kPng16;
  if (name == "tiff16") return PhotoFormat::kTiff16;
  if (name == "jpeg8") return PhotoFormat::kJpeg8;
  return std::nullopt;
}

std::string SensorDescription::Extension() const {
  switch (format) {
    case PhotoFormat::kPng16:
      return ".png";
    case PhotoFormat::kTiff16:
      return ".tif";
    case PhotoFormat::kJpeg8:
      return ".jpg";
  }
  return ".png";
}

const AxisTiming& TimingDescription::For(const std::string& axis) const {
  const auto it = axes.find(axis);
  return it == axes.end() ? default_axis : it->second;
}

Scene Scene::Ideal() const {
  Scene ideal = *this;
  ideal.effects = Effects{};
  ideal.faults.clear();
  return ideal;
}

std::string Scene::Summary() const {
  std::ostringstream out;
  out << rig.intrinsics.width << "x" << rig.intrinsics.height << ", sample " << sample.brdf->Name()
      << ", effects: " << effects.Describe();
  if (board) out << ", a ChArUco board at " << board->world_from_page.size() << " poses";
  return out.str();
}

Scene ParseScene(const YamlNode& root, const std::filesystem::path& base_dir) {
  Scene scene;
  const YamlNode rig_node = root.Required("rig");
  scene.rig = geometry::ParseRigGeometry(rig_node);
  if (scene.rig.intrinsics.k1 != 0 || scene.rig.intrinsics.k2 != 0) {
    rig_node.Required("camera")
        .Required("distortion")
        .Fail("a scene's camera is ideal; list the radial_distortion effect instead");
  }
  scene.sample = ParseSample(root.Required("sample"), base_dir, scene.rig.target);
  if (auto background = root.Optional("background")) {
    scene.background_albedo = ReadRgb(background->Required("albedo"), 0, 1);
    background->Finish();
  }
  if (auto sensor = root.Optional("sensor")) scene.sensor = ParseSensor(*sensor);
  if (auto render = root.Optional("render")) scene.render = ParseRender(*render);
  if (auto timing = root.Optional("timing")) scene.timing = ParseTiming(*timing, scene.rig);
  if (auto capture = root.Optional("capture")) scene.capture = ParseCapture(*capture, scene.rig);
  if (auto effects = root.Optional("effects")) scene.effects = ParseEffects(*effects);
  if (auto board = root.Optional("board")) scene.board = ParseSceneBoard(*board);
  if (auto faults = root.Optional("faults")) {
    for (const YamlNode& item : faults->Elements()) {
      scene.faults.push_back(ParseFault(item, scene.rig));
    }
  }
  root.Finish();
  return scene;
}

Scene LoadScene(const std::filesystem::path& path) {
  Scene scene = ParseScene(LoadYamlFile(path.string()), path.parent_path());
  scene.source = path;
  return scene;
}

Scene LoadSceneString(const std::string& yaml, const std::string& source_name,
                      const std::filesystem::path& base_dir) {
  Scene scene = ParseScene(LoadYamlString(yaml, source_name), base_dir);
  scene.source = source_name;
  return scene;
}

geometry::AxisPositions ParsePositionsDegrees(const std::string& text) {
  geometry::AxisPositions positions;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw Error("positions '" + text + "': expected axis=degrees[,axis=degrees...]");
    }
    const std::string name = item.substr(0, eq);
    const std::string value = item.substr(eq + 1);
    std::size_t used = 0;
    double degrees = 0;
    try {
      degrees = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != value.size() || !std::isfinite(degrees)) {
      throw Error("positions '" + text + "': '" + value + "' is not a number of degrees");
    }
    if (!positions.emplace(name, Radians(degrees)).second) {
      throw Error("positions '" + text + "': axis '" + name + "' given twice");
    }
  }
  if (positions.empty()) throw Error("positions: empty; expected axis=degrees[,...]");
  return positions;
}

}  // namespace brdfrig::sim
