// GlProgram: compile, link, report the driver's log (see gl_program.h).
#include "render/gl_program.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace serosa::render {
namespace {

std::string shader_log(GLuint shader) {
  GLint len = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
  glGetShaderInfoLog(shader, len, nullptr, log.data());
  return log;
}

std::string program_log(GLuint program) {
  GLint len = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
  glGetProgramInfoLog(program, len, nullptr, log.data());
  return log;
}

}  // namespace

GlProgram::GlProgram(const std::vector<ShaderSource>& stages) : id_(glCreateProgram()) {
  std::vector<GLuint> shaders;
  const auto cleanup = [&] {
    for (const GLuint s : shaders) glDeleteShader(s);
  };
  for (const ShaderSource& src : stages) {
    const GLuint s = glCreateShader(src.stage);
    shaders.push_back(s);
    glShaderSource(s, 1, &src.text, nullptr);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
      const std::string log = shader_log(s);
      cleanup();
      glDeleteProgram(id_);
      throw std::runtime_error(std::string("GLSL compile error in ") + src.name + ": " + log);
    }
    glAttachShader(id_, s);
  }
  glLinkProgram(id_);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  cleanup();  // shaders stay alive while attached; deleting here frees them with the program
  if (ok != GL_TRUE) {
    const std::string log = program_log(id_);
    glDeleteProgram(id_);
    throw std::runtime_error("GLSL link error: " + log);
  }
}

GlProgram::~GlProgram() { glDeleteProgram(id_); }

int GlProgram::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

}  // namespace serosa::render
