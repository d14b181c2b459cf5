// `brdfrig render`: a material rendered headless, either as a capture position of a scene (the
// sample under the paper mask, seen by the scene's camera, lit by its light) or on a mesh seen
// from an orbit camera.
#pragma once

#include <filesystem>
#include <string>

namespace brdfrig::jobs {

struct RenderJobOptions {
  std::filesystem::path material;  // material.json or MERL .binary
  std::filesystem::path scene;     // optional: render a capture position of this scene
  int position = 0;                // index into the scene's capture positions
  std::string mesh = "object";     // without a scene: sphere | object | plane | path/to.obj
  int width = 1280, height = 720;  // without a scene (a scene fixes its camera)
  std::filesystem::path output;    // .exr (radiance) or .png/.jpg (picture)
  void Validate() const;           // throws OptionsError
};

struct RenderJobSummary {
  std::string gl;  // renderer / version
  int width = 0, height = 0;
  double milliseconds = 0;  // draw time, read-back excluded
  std::string ToString() const;
};

RenderJobSummary RunRenderJob(const RenderJobOptions& options);

}  // namespace brdfrig::jobs
