#include "render/scaled_target.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/gl_program.h"

namespace serosa::render {
namespace {

// A full-screen triangle from gl_VertexID, sampling the drawn picture.
constexpr const char* kVertex = R"(#version 410 core
out vec2 v_uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  v_uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
})";

constexpr const char* kFragment = R"(#version 410 core
in vec2 v_uv;
uniform sampler2D u_picture;
out vec4 o_color;
void main() { o_color = texture(u_picture, v_uv); })";

}  // namespace

ScaledTarget::ScaledTarget()
    : program_(std::make_unique<GlProgram>(
          std::vector<ShaderSource>{{GL_VERTEX_SHADER, kVertex, "scaled target vertex"},
                                    {GL_FRAGMENT_SHADER, kFragment, "scaled target fragment"}})) {
  glGenVertexArrays(1, &vao_);
}

ScaledTarget::~ScaledTarget() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &color_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteVertexArrays(1, &vao_);
}

void ScaledTarget::ensure_size(int width, int height) {
  if (fbo_ != 0 && width == width_ && height == height_) return;
  if (fbo_ == 0) {
    glGenFramebuffers(1, &fbo_);
    glGenTextures(1, &color_);
    glGenRenderbuffers(1, &depth_);
  }
  width_ = width;
  height_ = height;
  glBindTexture(GL_TEXTURE_2D, color_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
}

void scaled_size(int width, int height, float scale, int& draw_width, int& draw_height) {
  const float s = std::clamp(std::isfinite(scale) ? scale : 1.0f, 0.1f, 1.0f);
  draw_width = std::max(1, static_cast<int>(std::lround(s * static_cast<float>(width))));
  draw_height = std::max(1, static_cast<int>(std::lround(s * static_cast<float>(height))));
}

void ScaledTarget::begin(int width, int height, float scale, int& draw_width, int& draw_height) {
  scale_ = std::clamp(std::isfinite(scale) ? scale : 1.0f, 0.1f, 1.0f);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_);
  draw_width = width;
  draw_height = height;
  if (scale_ >= 1.0f) return;
  scaled_size(width, height, scale_, draw_width, draw_height);
  ensure_size(draw_width, draw_height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, draw_width, draw_height);
}

void ScaledTarget::present(int width, int height) {
  if (scale_ >= 1.0f) return;
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_));
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_->id());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, color_);
  glUniform1i(program_->uniform("u_picture"), 0);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace serosa::render
