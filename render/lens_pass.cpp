#include "render/lens_pass.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "render/gl_program.h"

namespace serosa::render {
namespace {

// A full-screen triangle from gl_VertexID.
constexpr const char* kVertex = R"(#version 410 core
out vec2 v_uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  v_uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
})";

// Radii are relative to the half diagonal, so the corner is at r = 1 whatever the aspect.
constexpr const char* kFragment = R"(#version 410 core
in vec2 v_uv;
uniform sampler2D u_picture;
uniform vec2 u_size;       // pixels
uniform float u_k;         // barrel distortion
uniform float u_vignette;  // light lost at the corners
uniform int u_antialias;
out vec4 o_color;
float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
void main() {
  vec2 half_size = 0.5 * u_size;
  vec2 c = (v_uv - 0.5) * u_size;      // pixels from the centre
  float r2 = dot(c, c) / dot(half_size, half_size);
  vec2 src = 0.5 + c * (1.0 + u_k * r2) / (1.0 + u_k) / u_size;
  vec4 m = texture(u_picture, src);
  vec3 rgb = m.rgb;
  if (u_antialias != 0) {
    // Two bilinear taps half a pixel off along the diagonals: each is the mean of a 2 x 2 block,
    // so together they see the 3 x 3 neighbourhood; where they differ much, an edge runs
    // through it and the pixel takes their mean.
    vec2 t = 0.5 / u_size;
    vec3 a = texture(u_picture, src + vec2(t.x, t.y)).rgb;
    vec3 b = texture(u_picture, src - vec2(t.x, t.y)).rgb;
    vec3 c = texture(u_picture, src + vec2(t.x, -t.y)).rgb;
    vec3 d = texture(u_picture, src - vec2(t.x, -t.y)).rgb;
    float contrast = max(abs(luma(a) - luma(b)), abs(luma(c) - luma(d)));
    float edge = smoothstep(0.06, 0.25, contrast);
    rgb = mix(rgb, 0.25 * (a + b + c + d), edge);
  }
  float fall = 1.0 - u_vignette * r2 * r2 * (3.0 - 2.0 * sqrt(r2));
  o_color = vec4(rgb * fall, m.a);
})";

}  // namespace

LensPass::LensPass()
    : program_(std::make_unique<GlProgram>(
          std::vector<ShaderSource>{{GL_VERTEX_SHADER, kVertex, "lens vertex"},
                                    {GL_FRAGMENT_SHADER, kFragment, "lens fragment"}})) {
  glGenVertexArrays(1, &vao_);
}

LensPass::~LensPass() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &color_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteVertexArrays(1, &vao_);
}

void LensPass::ensure_size(int width, int height) {
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

void LensPass::begin(int width, int height) {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  ensure_size(std::max(width, 1), std::max(height, 1));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

void LensPass::end(const LensSettings& lens) {
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);  // every pixel is replaced, coverage (alpha) included
  glUseProgram(program_->id());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, color_);
  glUniform1i(program_->uniform("u_picture"), 0);
  glUniform2f(program_->uniform("u_size"), static_cast<float>(width_), static_cast<float>(height_));
  glUniform1f(program_->uniform("u_k"), std::max(lens.distortion, 0.0f));
  glUniform1f(program_->uniform("u_vignette"), std::clamp(lens.vignette, 0.0f, 0.99f));
  glUniform1i(program_->uniform("u_antialias"), lens.antialias ? 1 : 0);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace serosa::render
