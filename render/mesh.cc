#include "render/mesh.h"

#include <tiny_obj_loader.h>

#include <Eigen/Geometry>
#include <cmath>

#include "common/error.h"

namespace brdfrig::render {
namespace {

void AddQuad(Mesh& m, const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
             const Eigen::Vector3f& d) {
  const auto base = static_cast<unsigned>(m.positions.size());
  for (const auto& p : {a, b, c, d}) {
    m.positions.push_back(p);
    m.normals.emplace_back(0, 0, 1);
  }
  for (unsigned i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

void ComputeSmoothNormals(Mesh& m) {
  m.normals.assign(m.positions.size(), Eigen::Vector3f::Zero());
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const auto& a = m.positions[m.indices[t]];
    const Eigen::Vector3f n =
        (m.positions[m.indices[t + 1]] - a).cross(m.positions[m.indices[t + 2]] - a);
    for (int k = 0; k < 3; ++k) m.normals[m.indices[t + k]] += n;
  }
  for (auto& n : m.normals) n = n.norm() > 0 ? n.normalized() : Eigen::Vector3f::UnitZ();
}

// A tube of `rings` × `segments` quads around a closed curve.
Mesh Tube(int rings, int segments, float tube_radius,
          const std::function<Eigen::Vector3f(float)>& curve) {
  Mesh m;
  for (int i = 0; i < rings; ++i) {
    const float t = 2 * float(M_PI) * i / rings;
    const Eigen::Vector3f c = curve(t);
    const Eigen::Vector3f tangent = (curve(t + 1e-3f) - curve(t - 1e-3f)).normalized();
    Eigen::Vector3f side = tangent.cross(Eigen::Vector3f::UnitZ());
    if (side.norm() < 1e-3f) side = tangent.cross(Eigen::Vector3f::UnitX());
    side.normalize();
    const Eigen::Vector3f up = side.cross(tangent);
    for (int j = 0; j < segments; ++j) {
      const float a = 2 * float(M_PI) * j / segments;
      const Eigen::Vector3f n = std::cos(a) * side + std::sin(a) * up;
      m.positions.push_back(c + tube_radius * n);
      m.normals.push_back(n);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const unsigned a = i * segments + j, b = ((i + 1) % rings) * segments + j;
      const unsigned c = ((i + 1) % rings) * segments + (j + 1) % segments;
      const unsigned d = i * segments + (j + 1) % segments;
      for (unsigned k : {a, b, c, a, c, d}) m.indices.push_back(k);
    }
  }
  return m;
}

}  // namespace

Mesh MakeRectangle(float x0, float x1, float y0, float y1, float z0) {
  Mesh m;
  AddQuad(m, {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0});
  return m;
}

Mesh MakeFrame(float inner_w, float inner_h, float outer_w, float outer_h) {
  Mesh m;
  const float iw = inner_w / 2, ih = inner_h / 2, ow = outer_w / 2, oh = outer_h / 2;
  AddQuad(m, {-ow, -oh, 0}, {ow, -oh, 0}, {ow, -ih, 0}, {-ow, -ih, 0});  // bottom band
  AddQuad(m, {-ow, ih, 0}, {ow, ih, 0}, {ow, oh, 0}, {-ow, oh, 0});      // top band
  AddQuad(m, {-ow, -ih, 0}, {-iw, -ih, 0}, {-iw, ih, 0}, {-ow, ih, 0});  // left band
  AddQuad(m, {iw, -ih, 0}, {ow, -ih, 0}, {ow, ih, 0}, {iw, ih, 0});      // right band
  return m;
}

Mesh MakeSphere(float radius, int rings, int segments) {
  Mesh m;
  for (int i = 0; i <= rings; ++i) {
    const float theta = float(M_PI) * i / rings;
    for (int j = 0; j <= segments; ++j) {
      const float phi = 2 * float(M_PI) * j / segments;
      const Eigen::Vector3f n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const unsigned a = i * (segments + 1) + j, b = a + segments + 1;
      for (unsigned k : {a, b, b + 1, a, b + 1, a + 1}) m.indices.push_back(k);
    }
  }
  return m;
}

Mesh MakeTestObject(int triangles) {
  const int segments = 40;
  const int rings = std::max(3, triangles / (2 * segments));
  return Tube(rings, segments, 0.012f, [](float t) {
    // A (2, 3) torus knot, about 0.1 m across.
    const float r = 0.04f + 0.015f * std::cos(3 * t);
    return Eigen::Vector3f(r * std::cos(2 * t), r * std::sin(2 * t), 0.015f * std::sin(3 * t));
  });
}

Mesh LoadObj(const std::filesystem::path& path) {
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string())) {
    throw FileError(path.string(), "cannot load OBJ: " + reader.Error());
  }
  const auto& attrib = reader.GetAttrib();
  Mesh m;
  bool has_normals = !attrib.normals.empty();
  for (const auto& shape : reader.GetShapes()) {
    for (const auto& index : shape.mesh.indices) {
      m.positions.emplace_back(attrib.vertices[3 * index.vertex_index],
                               attrib.vertices[3 * index.vertex_index + 1],
                               attrib.vertices[3 * index.vertex_index + 2]);
      if (has_normals && index.normal_index >= 0) {
        m.normals.emplace_back(Eigen::Vector3f(attrib.normals[3 * index.normal_index],
                                               attrib.normals[3 * index.normal_index + 1],
                                               attrib.normals[3 * index.normal_index + 2])
                                   .normalized());
      } else {
        has_normals = false;
      }
      m.indices.push_back(static_cast<unsigned>(m.indices.size()));
    }
  }
  if (m.indices.empty()) throw FileError(path.string(), "OBJ has no triangles");
  if (!has_normals) ComputeSmoothNormals(m);
  return m;
}

GpuMesh::GpuMesh(const Mesh& mesh) : count_(static_cast<GLsizei>(mesh.indices.size())) {
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(3, buffers_);
  glNamedBufferData(buffers_[0], mesh.positions.size() * sizeof(Eigen::Vector3f),
                    mesh.positions.data(), GL_STATIC_DRAW);
  glNamedBufferData(buffers_[1], mesh.normals.size() * sizeof(Eigen::Vector3f), mesh.normals.data(),
                    GL_STATIC_DRAW);
  glNamedBufferData(buffers_[2], mesh.indices.size() * sizeof(unsigned), mesh.indices.data(),
                    GL_STATIC_DRAW);
  for (GLuint attrib = 0; attrib < 2; ++attrib) {
    glVertexArrayVertexBuffer(vao_, attrib, buffers_[attrib], 0, sizeof(Eigen::Vector3f));
    glVertexArrayAttribFormat(vao_, attrib, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, attrib, attrib);
    glEnableVertexArrayAttrib(vao_, attrib);
  }
  glVertexArrayElementBuffer(vao_, buffers_[2]);
}

GpuMesh::~GpuMesh() {
  glDeleteBuffers(3, buffers_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::Draw() const {
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace brdfrig::render
