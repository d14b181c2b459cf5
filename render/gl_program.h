// A linked GLSL program built from shader files plus #defines; compile and link errors
// become brdfrig::Error with the driver's log and the file names.
#pragma once

#include <epoxy/gl.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace brdfrig::render {

class GlProgram {
 public:
  // Each stage is the concatenation of `#version 450 core`, the defines, then the files.
  GlProgram(const std::vector<std::string>& vertex_files,
            const std::vector<std::string>& fragment_files,
            const std::vector<std::string>& defines);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void Use() const { glUseProgram(program_); }
  GLint Location(const char* name) const { return glGetUniformLocation(program_, name); }
  void Set(const char* name, int value) const { glUniform1i(Location(name), value); }
  void Set(const char* name, float value) const { glUniform1f(Location(name), value); }
  void Set(const char* name, const Eigen::Vector3f& v) const {
    glUniform3f(Location(name), v.x(), v.y(), v.z());
  }
  void Set(const char* name, const Eigen::Matrix4f& m) const {
    glUniformMatrix4fv(Location(name), 1, GL_FALSE, m.data());
  }

 private:
  GLuint program_ = 0;
};

}  // namespace brdfrig::render
