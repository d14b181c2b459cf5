#include "render/mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"

namespace brdfrig::render {
namespace {

TEST(MeshTest, TestObjectHasAboutFiftyThousandTrianglesWithUnitNormals) {
  const Mesh m = MakeTestObject(50000);
  EXPECT_NEAR(static_cast<double>(m.TriangleCount()), 50000, 100);
  for (const auto& n : m.normals) ASSERT_NEAR(n.norm(), 1.0, 1e-5);
}

TEST(MeshTest, SphereNormalsPointOutwards) {
  const Mesh m = MakeSphere(2.0f, 16, 32);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    ASSERT_NEAR((m.positions[i] / 2.0f - m.normals[i]).norm(), 0, 1e-5);
  }
}

TEST(MeshTest, ObjWithoutNormalsGetsSmoothNormals) {
  const auto path = std::filesystem::temp_directory_path() / "brdfrig_mesh_test.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Mesh m = LoadObj(path);
  ASSERT_EQ(m.TriangleCount(), 1u);
  EXPECT_NEAR(m.normals[0].z(), 1.0, 1e-6);
  std::filesystem::remove(path);
}

TEST(MeshTest, MissingObjNamesTheFile) {
  try {
    LoadObj("/nonexistent/model.obj");
    FAIL();
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("/nonexistent/model.obj"));
  }
}

}  // namespace
}  // namespace brdfrig::render
