// The interactive viewer: a GLFW window showing a material on a mesh, with the reference (or a
// second material) side by side.
//   drag (left button)   orbit the camera          scroll      zoom
//   arrow keys           move the light             M          next mesh (sphere, object, plane)
//   I                    spline / linear interpolation across theta_in (see the seams)
//   + / -                display exposure           S          save a screenshot
//   Esc, Q               quit
// The window title shows frames per second, the mesh and the interpolation.
#pragma once

#include <string>

#include "brdf/brdf.h"

namespace brdfrig::render {

struct ViewerOptions {
  int width = 1280, height = 720;
  std::string screenshot_path = "brdfrig_view.png";  // where S (or --frames) saves the window
  int frames = 0;  // > 0: render this many frames, save a screenshot, close (for tests/docs)
  void Validate() const;
};

// `compare` may be null (one material fills the window).
void RunViewer(const brdf::Brdf& material, const brdf::Brdf* compare, const std::string& label,
               const std::string& compare_label, const ViewerOptions& options);

}  // namespace brdfrig::render
