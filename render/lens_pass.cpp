#include "render/lens_pass.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "render/gl_program.h"
#include "render/picture_target.h"

namespace serosa::render {
namespace {

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
          std::vector<ShaderSource>{{GL_VERTEX_SHADER, kFullScreenVertex, "lens vertex"},
                                    {GL_FRAGMENT_SHADER, kFragment, "lens fragment"}})) {}

LensPass::~LensPass() = default;

void LensPass::begin(int width, int height) {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  picture_.bind(std::max(width, 1), std::max(height, 1));
}

void LensPass::end(const LensSettings& lens) {
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);  // every pixel is replaced, coverage (alpha) included
  glUseProgram(program_->id());
  glUniform1i(program_->uniform("u_picture"), 0);
  glUniform2f(program_->uniform("u_size"), static_cast<float>(picture_.width()),
              static_cast<float>(picture_.height()));
  glUniform1f(program_->uniform("u_k"), std::max(lens.distortion, 0.0f));
  glUniform1f(program_->uniform("u_vignette"), std::clamp(lens.vignette, 0.0f, 0.99f));
  glUniform1i(program_->uniform("u_antialias"), lens.antialias ? 1 : 0);
  picture_.draw_full_screen();
  glUseProgram(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace serosa::render
