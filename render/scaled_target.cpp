#include "render/scaled_target.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/gl_program.h"
#include "render/picture_target.h"

namespace serosa::render {
namespace {

constexpr const char* kFragment = R"(#version 410 core
in vec2 v_uv;
uniform sampler2D u_picture;
out vec4 o_color;
void main() { o_color = texture(u_picture, v_uv); })";

}  // namespace

ScaledTarget::ScaledTarget()
    : program_(std::make_unique<GlProgram>(
          std::vector<ShaderSource>{{GL_VERTEX_SHADER, kFullScreenVertex, "scaled target vertex"},
                                    {GL_FRAGMENT_SHADER, kFragment, "scaled target fragment"}})) {}

ScaledTarget::~ScaledTarget() = default;

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
  target_picture_.bind(draw_width, draw_height);
}

void ScaledTarget::present(int width, int height) {
  if (scale_ >= 1.0f) return;
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_));
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_->id());
  glUniform1i(program_->uniform("u_picture"), 0);
  target_picture_.draw_full_screen();
  glUseProgram(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace serosa::render
