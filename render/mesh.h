// Triangle meshes: generated test objects and user OBJ files, and their GPU buffers.
#pragma once

#include <epoxy/gl.h>

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace brdfrig::render {

struct Mesh {
  std::vector<Eigen::Vector3f> positions;  // world metres
  std::vector<Eigen::Vector3f> normals;    // unit, per vertex
  std::vector<unsigned> indices;           // triangles
  std::size_t TriangleCount() const { return indices.size() / 3; }
};

// A rectangle in the plane z = z0 (normal +z) spanning [x0, x1] × [y0, y1].
Mesh MakeRectangle(float x0, float x1, float y0, float y1, float z0 = 0);
// The paper mask around a cut-out: the frame between the cut-out and the paper's outer edge.
Mesh MakeFrame(float inner_w, float inner_h, float outer_w, float outer_h);
Mesh MakeSphere(float radius, int rings, int segments);
// A torus knot tube with about `triangles` triangles: curved everywhere, many normals,
// self-occluding — a stand-in for a real object (the seed's 50K-triangle test).
Mesh MakeTestObject(int triangles = 50000);
// Loads an OBJ with tinyobjloader; computes smooth normals if the file has none.
// Throws FileError naming the file and the loader's message.
Mesh LoadObj(const std::filesystem::path& path);

class GpuMesh {
 public:
  explicit GpuMesh(const Mesh& mesh);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  void Draw() const;

 private:
  GLuint vao_ = 0, buffers_[3] = {0, 0, 0};
  GLsizei count_ = 0;
};

}  // namespace brdfrig::render
