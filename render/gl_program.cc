#include "render/gl_program.h"

#include "common/error.h"
#include "render/shader_sources.h"

namespace brdfrig::render {
namespace {

GLuint Compile(GLenum stage, const std::vector<std::string>& files,
               const std::vector<std::string>& defines) {
  std::string source = "#version 450 core\n";
  for (const std::string& d : defines) source += "#define " + d + "\n";
  std::string names;
  for (const std::string& f : files) {
    source += LoadShaderSource(f) + "\n";
    names += (names.empty() ? "" : " + ") + f;
  }
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    glDeleteShader(shader);
    throw Error("GLSL compile error in " + names + ":\n" + log);
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const std::vector<std::string>& vertex_files,
                     const std::vector<std::string>& fragment_files,
                     const std::vector<std::string>& defines) {
  const GLuint vs = Compile(GL_VERTEX_SHADER, vertex_files, defines);
  const GLuint fs = Compile(GL_FRAGMENT_SHADER, fragment_files, defines);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetProgramInfoLog(program_, sizeof(log), nullptr, log);
    glDeleteProgram(program_);
    throw Error(std::string("GLSL link error:\n") + log);
  }
}

GlProgram::~GlProgram() { glDeleteProgram(program_); }

}  // namespace brdfrig::render
