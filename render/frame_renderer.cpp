// FrameRenderer: buffers, programs and the three views (see frame_renderer.h).
#include "render/frame_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/gl_program.h"
#include "render/lens_pass.h"
#include "render/materials.h"
#include "render/shaders.h"
#include "render/tissue_pattern.h"
#include "render/vertex_normals.h"

namespace serosa::render {
namespace {

// One vertex attribute of a VAO: the buffer it reads, its component count and type, whether
// bytes are normalised, and its divisor (1: one value per instance).
struct VertexAttribute {
  GLuint buffer = 0;
  GLint size = 3;
  GLenum type = GL_FLOAT;
  GLboolean normalized = GL_FALSE;
  GLuint divisor = 0;
};

// Wires attribute k of `vao` to attrs[k], tightly packed, and the element buffer when given.
void wire_attributes(GLuint vao, std::initializer_list<VertexAttribute> attrs,
                     GLuint elements = 0) {
  glBindVertexArray(vao);
  GLuint k = 0;
  for (const VertexAttribute& a : attrs) {
    glBindBuffer(GL_ARRAY_BUFFER, a.buffer);
    glVertexAttribPointer(k, a.size, a.type, a.normalized, 0, nullptr);
    glEnableVertexAttribArray(k);
    if (a.divisor != 0) glVertexAttribDivisor(k, a.divisor);
    ++k;
  }
  if (elements != 0) glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, elements);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// Unique undirected edges of the triangles, (e x 2) vertex ids: the mechanical view's fallback.
std::vector<std::uint32_t> triangle_edges(const std::vector<std::uint32_t>& tri) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> e;
  e.reserve(tri.size());
  for (std::size_t f = 0; f + 2 < tri.size(); f += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[f + k];
      const std::uint32_t b = tri[f + (k + 1) % 3];
      e.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  std::vector<std::uint32_t> out;
  out.reserve(2 * e.size());
  for (const auto& [a, b] : e) {
    out.push_back(a);
    out.push_back(b);
  }
  return out;
}

GLsizeiptr bytes(std::size_t count, std::size_t size) {
  return static_cast<GLsizeiptr>(count * size);
}

constexpr GLuint kPatternUnit = 5;   // texture unit of the tissue's pattern
constexpr float kReliefM = 0.0002f;  // the height of the tissue's fine relief, m

}  // namespace

FrameRenderer::FrameRenderer()
    : visual_(std::make_unique<GlProgram>(std::vector<ShaderSource>{
          {GL_VERTEX_SHADER, shaders::kVisualVertex, "visual vertex"},
          {GL_TESS_CONTROL_SHADER, shaders::kVisualTessControl, "visual tess control"},
          {GL_TESS_EVALUATION_SHADER, shaders::kVisualTessEval, "visual tess evaluation"},
          {GL_FRAGMENT_SHADER, shaders::kVisualFragment, "visual fragment"}})),
      flat_(std::make_unique<GlProgram>(std::vector<ShaderSource>{
          {GL_VERTEX_SHADER, shaders::kFlatVertex, "flat vertex"},
          {GL_FRAGMENT_SHADER, shaders::kFlatFragment, "flat fragment"}})),
      tool_(std::make_unique<GlProgram>(std::vector<ShaderSource>{
          {GL_VERTEX_SHADER, shaders::kToolVertex, "tool vertex"},
          {GL_FRAGMENT_SHADER, shaders::kToolFragment, "tool fragment"}})),
      scenery_(std::make_unique<GlProgram>(std::vector<ShaderSource>{
          {GL_VERTEX_SHADER, shaders::kSceneryVertex, "scenery vertex"},
          {GL_FRAGMENT_SHADER, shaders::kVisualFragment, "visual fragment"}})),
      lens_(std::make_unique<LensPass>()),
      smoke_(std::make_unique<GlProgram>(std::vector<ShaderSource>{
          {GL_VERTEX_SHADER, shaders::kSmokeVertex, "smoke vertex"},
          {GL_FRAGMENT_SHADER, shaders::kSmokeFragment, "smoke fragment"}})) {
  glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &max_tess_level_);
  // Mesa's software tessellator (llvmpipe, softpipe) grows its output with a realloc per patch,
  // so one draw costs time quadratic in its patch count wherever realloc copies (a sanitizer's
  // allocator: 15 frames in 27 s against 100 in 20 s with 64 patches a draw). A GPU takes them
  // in one draw.
  const auto* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string renderer_name = gl_renderer != nullptr ? gl_renderer : "";
  if (renderer_name.find("llvmpipe") != std::string::npos ||
      renderer_name.find("softpipe") != std::string::npos)
    patches_per_draw_ = kSoftwarePatchesPerDraw;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texture_buffer_);
  glGenVertexArrays(1, &vao_);
  glGenVertexArrays(1, &pull_vao_);
  std::array<GLuint, 6> bufs{};
  glGenBuffers(static_cast<GLsizei>(bufs.size()), bufs.data());
  pos_buf_ = bufs[0];
  nrm_buf_ = bufs[1];
  tri_buf_ = bufs[2];
  line_buf_ = bufs[3];
  material_buf_ = bufs[4];
  rest_buf_ = bufs[5];
  std::array<GLuint, 6> texs{};
  glGenTextures(static_cast<GLsizei>(texs.size()), texs.data());
  pos_tex_ = texs[0];
  nrm_tex_ = texs[1];
  tri_tex_ = texs[2];
  material_tex_ = texs[3];
  rest_tex_ = texs[4];
  pattern_tex_ = texs[5];
  make_pattern_texture();

  // Attribute 0: position, attribute 1: normal, both (n x 3) floats.
  wire_attributes(vao_, {{pos_buf_}, {nrm_buf_}});

  // Instruments: attribute 0 position, 1 normal (3 floats each), 2 material (4 floats).
  std::array<GLuint, 4> tbufs{};
  glGenBuffers(static_cast<GLsizei>(tbufs.size()), tbufs.data());
  tool_pos_buf_ = tbufs[0];
  tool_nrm_buf_ = tbufs[1];
  tool_mat_buf_ = tbufs[2];
  tool_idx_buf_ = tbufs[3];
  glGenVertexArrays(1, &tool_vao_);
  wire_attributes(tool_vao_, {{tool_pos_buf_}, {tool_nrm_buf_}, {tool_mat_buf_, 4}}, tool_idx_buf_);

  // Scenery: attribute 0 position, 1 normal (3 floats each), 2 material and 3 look (4
  // normalised bytes each).
  std::array<GLuint, 4> sbufs{};
  glGenBuffers(static_cast<GLsizei>(sbufs.size()), sbufs.data());
  scenery_pos_buf_ = sbufs[0];
  scenery_nrm_buf_ = sbufs[1];
  scenery_mat_buf_ = sbufs[2];
  scenery_look_buf_ = sbufs[3];
  glGenVertexArrays(1, &scenery_vao_);
  wire_attributes(scenery_vao_, {{scenery_pos_buf_},
                                 {scenery_nrm_buf_},
                                 {scenery_mat_buf_, 4, GL_UNSIGNED_BYTE, GL_TRUE},
                                 {scenery_look_buf_, 4, GL_UNSIGNED_BYTE, GL_TRUE}});

  // Smoke: attribute 0 a puff's centre and radius (4 floats), 1 its density, one per instance.
  std::array<GLuint, 2> pbufs{};
  glGenBuffers(static_cast<GLsizei>(pbufs.size()), pbufs.data());
  smoke_puff_buf_ = pbufs[0];
  smoke_density_buf_ = pbufs[1];
  glGenVertexArrays(1, &smoke_vao_);
  wire_attributes(smoke_vao_, {{smoke_puff_buf_, 4, GL_FLOAT, GL_FALSE, 1},
                               {smoke_density_buf_, 1, GL_FLOAT, GL_FALSE, 1}});
}

FrameRenderer::~FrameRenderer() {
  const std::array<GLuint, 14> bufs{
      pos_buf_,         nrm_buf_,         tri_buf_,         line_buf_,        material_buf_,
      rest_buf_,        tool_pos_buf_,    tool_nrm_buf_,    tool_mat_buf_,    tool_idx_buf_,
      scenery_pos_buf_, scenery_nrm_buf_, scenery_mat_buf_, scenery_look_buf_};
  const std::array<GLuint, 6> texs{pos_tex_,      nrm_tex_,  tri_tex_,
                                   material_tex_, rest_tex_, pattern_tex_};
  const std::array<GLuint, 4> vaos{vao_, pull_vao_, tool_vao_, scenery_vao_};
  glDeleteTextures(static_cast<GLsizei>(texs.size()), texs.data());
  glDeleteBuffers(static_cast<GLsizei>(bufs.size()), bufs.data());
  glDeleteVertexArrays(static_cast<GLsizei>(vaos.size()), vaos.data());
  const std::array<GLuint, 2> smoke_bufs{smoke_puff_buf_, smoke_density_buf_};
  glDeleteBuffers(static_cast<GLsizei>(smoke_bufs.size()), smoke_bufs.data());
  glDeleteVertexArrays(1, &smoke_vao_);
}

// Per-triangle material (t x 2 RGBA8, render/materials.h pack_material). Wound faces take the
// wound material whatever their group, coagulated ones the coagulated material.
void FrameRenderer::upload_materials(const RenderFrame& frame) {
  const std::size_t t = frame.num_triangles();
  std::vector<std::uint8_t> mat(8 * std::max<std::size_t>(t, 1), 0);
  const Material wound = wound_material();
  const Material coagulated = coagulated_material();
  for (std::size_t f = 0; f < t; ++f) {
    const std::uint8_t mark = frame.tri_cut.empty() ? 0 : frame.tri_cut[f];
    const std::uint16_t g = frame.tri_group.empty() ? 0 : frame.tri_group[f];
    const Material m = mark == 1 ? wound : mark == 2 ? coagulated : group_material(frame, g);
    const std::array<std::uint8_t, 8> packed = pack_material(m);
    std::copy(packed.begin(), packed.end(), mat.begin() + static_cast<std::ptrdiff_t>(8 * f));
  }
  glBindBuffer(GL_TEXTURE_BUFFER, material_buf_);
  glBufferData(GL_TEXTURE_BUFFER, bytes(mat.size(), 1), mat.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  material_version_ = frame.material_version;
}

// The tissue's pattern as a repeating, mipmapped 3D texture (trilinear within a level).
void FrameRenderer::make_pattern_texture() {
  const TissuePattern& pattern = tissue_pattern();
  glBindTexture(GL_TEXTURE_3D, pattern_tex_);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, pattern.size, pattern.size, pattern.size, 0, GL_RGBA,
               GL_UNSIGNED_BYTE, pattern.rgba.data());
  glGenerateMipmap(GL_TEXTURE_3D);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_REPEAT);
  glBindTexture(GL_TEXTURE_3D, 0);
}

// The pattern on texture unit kPatternUnit, its period and the relief's height.
void FrameRenderer::set_pattern_uniforms(const GlProgram& program, bool detail) const {
  glActiveTexture(GL_TEXTURE0 + kPatternUnit);
  glBindTexture(GL_TEXTURE_3D, pattern_tex_);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(program.uniform("u_pattern"), static_cast<GLint>(kPatternUnit));
  glUniform1f(program.uniform("u_period"), kTissuePatternPeriodM);
  glUniform1f(program.uniform("u_relief"), kReliefM);
  glUniform1i(program.uniform("u_detail"), detail ? 1 : 0);
  glUniform1i(program.uniform("u_pools"), pools_);
  glUniform4fv(program.uniform("u_pool"), 4, pool_.data());
  glUniform3fv(program.uniform("u_pool_up"), 4, pool_up_.data());
  glUniform3fv(program.uniform("u_taenia_centre"), 1, taenia_centre_.data());
  glUniform3fv(program.uniform("u_taenia_axis"), 1, taenia_axis_.data());
}

// The first four pools of blood the frame's bleedings made (render_frame.h RenderBleed), and
// where the cecum's taeniae run.
void FrameRenderer::set_pools(const RenderFrame& frame) {
  pools_ = 0;
  for (const RenderBleed& b : frame.bleeds) {
    if (!(b.pool_radius > 0.0f) || pools_ == 4) continue;
    const auto k = static_cast<std::size_t>(pools_++);
    for (std::size_t c = 0; c < 3; ++c) {
      pool_[4 * k + c] = b.pool[c];
      pool_up_[3 * k + c] = b.pool_normal[c];
    }
    pool_[4 * k + 3] = b.pool_radius;
  }
  taenia_centre_ = frame.taenia_centre;
  taenia_axis_ = frame.taenia_axis;
}

// Per vertex two RGBA32F texels: the rest position (the pattern's coordinates; the current one
// when the frame has none) and the wound's rim; then the blood's stain.
void FrameRenderer::upload_rest(const RenderFrame& frame) {
  const std::size_t n = frame.num_vertices();
  const std::vector<float>& rest = frame.rest.empty() ? frame.pos : frame.rest;
  rest_scratch_.assign(8 * n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 3; ++k) rest_scratch_[8 * i + k] = rest[3 * i + k];
    rest_scratch_[8 * i + 3] = frame.rim.empty() ? 0.0f : frame.rim[i];
    rest_scratch_[8 * i + 4] = frame.stain.empty() ? 0.0f : frame.stain[i];
  }
  glBindBuffer(GL_TEXTURE_BUFFER, rest_buf_);
  glBufferData(GL_TEXTURE_BUFFER, bytes(rest_scratch_.size(), sizeof(float)), rest_scratch_.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

void FrameRenderer::upload_topology(const RenderFrame& frame) {
  const std::size_t t = frame.num_triangles();
  // The visual view reads 3t indices and n vertices through buffer textures.
  const auto limit = static_cast<std::size_t>(max_texture_buffer_);
  if (frame.tri.size() > limit || 2 * frame.num_vertices() > limit || 2 * t > limit) {
    throw std::runtime_error("FrameRenderer: " + std::to_string(frame.tri.size()) +
                             " triangle corners or " + std::to_string(frame.num_vertices()) +
                             " vertices exceed GL_MAX_TEXTURE_BUFFER_SIZE (" +
                             std::to_string(limit) + ")");
  }
  // Index buffers are bound through the vertex array (core profile has no default one).
  glBindVertexArray(vao_);
  // Triangle indices (t x 3).
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, tri_buf_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytes(frame.tri.size(), sizeof(std::uint32_t)),
               frame.tri.data(), GL_STATIC_DRAW);
  // Line indices (e x 2): the tet edges, or the triangles' edges when the frame has none.
  const std::vector<std::uint32_t> lines =
      frame.edges.empty() ? triangle_edges(frame.tri) : frame.edges;
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, line_buf_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytes(lines.size(), sizeof(std::uint32_t)), lines.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);

  upload_materials(frame);

  uploaded_ = true;
  ++topology_uploads_;
  topology_version_ = frame.topology_version;
  tri_count_ = t;
  line_count_ = lines.size() / 2;
  edge_source_ = frame.edges.size();
}

void FrameRenderer::draw_tools(const RenderFrame& frame, const float* view_proj, const float* eye,
                               float ref_dist, bool depth_cue) {
  if (frame.tools.empty() && frame.guide.empty() && frame.clips.empty() && frame.bleeds.empty())
    return;
  tool_mesh_.clear();
  for (const RenderTool& t : frame.tools) append_tool_mesh(t, tool_mesh_);
  if (depth_cue)
    for (const RenderTool& t : frame.tools) append_depth_cue(t, tool_mesh_);
  for (const RenderClip& c : frame.clips) append_clip_mesh(c, tool_mesh_);
  for (const RenderBleed& b : frame.bleeds) append_bleed_mesh(b, tool_mesh_);
  append_guide_mesh(frame.guide, tool_mesh_);
  glBindBuffer(GL_ARRAY_BUFFER, tool_pos_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(tool_mesh_.pos.size(), sizeof(float)), tool_mesh_.pos.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, tool_nrm_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(tool_mesh_.nrm.size(), sizeof(float)), tool_mesh_.nrm.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, tool_mat_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(tool_mesh_.material.size(), sizeof(float)),
               tool_mesh_.material.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(tool_vao_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytes(tool_mesh_.tri.size(), sizeof(std::uint32_t)),
               tool_mesh_.tri.data(), GL_STREAM_DRAW);
  glUseProgram(tool_->id());
  glUniformMatrix4fv(tool_->uniform("u_view_proj"), 1, GL_FALSE, view_proj);
  glUniform3f(tool_->uniform("u_eye"), eye[0], eye[1], eye[2]);
  glUniform1f(tool_->uniform("u_ref_dist"), ref_dist);
  glEnable(GL_DEPTH_TEST);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(tool_mesh_.tri.size()), GL_UNSIGNED_INT,
                 nullptr);
  glBindVertexArray(0);
}

// The scenery, once per version: every triangle's three corners with their own position, normal
// and the triangle's material (RGBA8: sRGB colour, specular strength), drawn as plain triangles.
void FrameRenderer::upload_scenery(const Scenery& scenery) {
  const std::size_t corners = scenery.tri.size();
  std::vector<float> pos(3 * corners), nrm(3 * corners);
  std::vector<std::uint8_t> mat(4 * corners), look(4 * corners);
  scenery_lo_ = Eigen::Vector3f::Constant(1.0f);
  scenery_hi_ = Eigen::Vector3f::Zero();
  for (std::size_t c = 0; c < corners; ++c) {
    const std::size_t v = scenery.tri[c];
    for (std::size_t k = 0; k < 3; ++k) {
      pos[3 * c + k] = scenery.pos[3 * v + k];
      nrm[3 * c + k] = scenery.nrm[3 * v + k];
    }
    const std::array<std::uint8_t, 8> m = pack_material(scenery_material(scenery.material[c / 3]));
    std::copy(m.begin(), m.begin() + 4, mat.begin() + static_cast<std::ptrdiff_t>(4 * c));
    std::copy(m.begin() + 4, m.end(), look.begin() + static_cast<std::ptrdiff_t>(4 * c));
    const Eigen::Vector3f p(pos[3 * c], pos[3 * c + 1], pos[3 * c + 2]);
    const bool first = c == 0;
    scenery_lo_ = first ? p : Eigen::Vector3f(scenery_lo_.cwiseMin(p));
    scenery_hi_ = first ? p : Eigen::Vector3f(scenery_hi_.cwiseMax(p));
  }
  const std::array<std::pair<GLuint, std::pair<const void*, std::size_t>>, 4> data{{
      {scenery_pos_buf_, {pos.data(), pos.size() * sizeof(float)}},
      {scenery_nrm_buf_, {nrm.data(), nrm.size() * sizeof(float)}},
      {scenery_mat_buf_, {mat.data(), mat.size()}},
      {scenery_look_buf_, {look.data(), look.size()}},
  }};
  for (const auto& [buf, d] : data) {
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBufferData(GL_ARRAY_BUFFER, bytes(d.second, 1), d.first, GL_STATIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  scenery_version_ = scenery.version;
  scenery_corners_ = corners;
  ++scenery_uploads_;
}

// Vertex data, every frame: positions, and normals (computed when the frame has none).
void FrameRenderer::upload_vertices(const RenderFrame& frame) {
  const std::vector<float> computed =
      frame.nrm.empty() ? compute_vertex_normals(frame.pos, frame.tri) : std::vector<float>{};
  const std::vector<float>& nrm = frame.nrm.empty() ? computed : frame.nrm;
  glBindBuffer(GL_ARRAY_BUFFER, pos_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(frame.pos.size(), sizeof(float)), frame.pos.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, nrm_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(nrm.size(), sizeof(float)), nrm.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  // Buffer-texture views of the same buffers for the visual view's vertex pulling (re-attached
  // every draw: glBufferData above gave the buffers new storage).
  upload_rest(frame);
  const std::array<std::pair<GLuint, std::pair<GLenum, GLuint>>, 5> views{{
      {pos_tex_, {GL_RGB32F, pos_buf_}},
      {nrm_tex_, {GL_RGB32F, nrm_buf_}},
      {tri_tex_, {GL_R32UI, tri_buf_}},
      {material_tex_, {GL_RGBA8, material_buf_}},
      {rest_tex_, {GL_RGBA32F, rest_buf_}},
  }};
  for (const auto& [tex, fmt] : views) {
    glBindTexture(GL_TEXTURE_BUFFER, tex);
    glTexBuffer(GL_TEXTURE_BUFFER, fmt.first, fmt.second);
  }
  glBindTexture(GL_TEXTURE_BUFFER, 0);
}

// The camera: view-projection, eye (the light), and the light's reference distance.
FrameRenderer::View FrameRenderer::view_of(const RenderFrame& frame, const SnapshotOptions& options,
                                           int width, int height) const {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const Camera cam = options.fit_camera ? auto_camera(frame, aspect) : frame.camera;
  Bounds bounds = drawn_bounds(frame);
  // The instruments' working ends are part of the scene's depth range (their shafts may reach
  // behind the camera and are left to the near plane).
  for (const RenderTool& t : frame.tools) {
    const ToolFrame tf = tool_frame(t);
    for (const auto& p : {t.tip, tf.hinge}) {
      const Eigen::Vector3f v(p[0], p[1], p[2]);
      if (bounds.empty) {
        bounds.lo = bounds.hi = v;
        bounds.empty = false;
      }
      bounds.lo = bounds.lo.cwiseMin(v);
      bounds.hi = bounds.hi.cwiseMax(v);
    }
  }
  // The scenery reaches far beyond the organs: without it in the depth range the far plane
  // would cut the wall off around them.
  if (options.view == SnapshotOptions::View::kVisual && scenery_corners_ > 0) {
    bounds.lo = bounds.empty ? scenery_lo_ : Eigen::Vector3f(bounds.lo.cwiseMin(scenery_lo_));
    bounds.hi = bounds.empty ? scenery_hi_ : Eigen::Vector3f(bounds.hi.cwiseMax(scenery_hi_));
    bounds.empty = false;
  }
  const CameraMatrices m = camera_matrices(cam, aspect, bounds);
  const Eigen::Matrix4f view_proj = m.projection * m.view;
  const Eigen::Vector3f eye(cam.eye[0], cam.eye[1], cam.eye[2]);
  const Eigen::Vector3f target(cam.target[0], cam.target[1], cam.target[2]);
  const float ref_dist = std::max((target - eye).norm(), 1e-6f);
  const Eigen::Vector3f right = m.view.block<1, 3>(0, 0).transpose().normalized();
  const Eigen::Vector3f up = m.view.block<1, 3>(1, 0).transpose().normalized();
  return {view_proj, eye, ref_dist, right, up};
}

namespace {

// The six planes (a, b, c, d; a x + b y + c z + d >= 0 inside, (a, b, c) unit) of the frustum of
// view_proj (column-major, OpenGL clip space): each is the last row plus or minus another
// (Gribb and Hartmann).
std::array<float, 24> frustum_planes(const Eigen::Matrix4f& view_proj) {
  std::array<float, 24> out{};
  for (int k = 0; k < 6; ++k) {
    const float sign = k % 2 == 0 ? 1.0f : -1.0f;
    Eigen::Vector4f p = (view_proj.row(3) + sign * view_proj.row(k / 2)).transpose();
    const float n = p.head<3>().norm();
    if (n > 0.0f) p /= n;
    for (int c = 0; c < 4; ++c) out[static_cast<std::size_t>(4 * k + c)] = p[c];
  }
  return out;
}

}  // namespace

void FrameRenderer::draw_visual(const View& v, const SnapshotOptions& options) {
  const Eigen::Matrix4f& view_proj = v.view_proj;
  const Eigen::Vector3f& eye = v.eye;
  const float ref_dist = v.ref_dist;
  if (tri_count_ == 0) return;
  const GLuint p = visual_->id();
  glUseProgram(p);
  const int level = std::clamp(options.tessellation, 1, max_tess_level_);
  glUniform1f(visual_->uniform("u_level"), static_cast<float>(level));
  glUniform1f(visual_->uniform("u_alpha"), std::clamp(options.shape_factor, 0.0f, 1.0f));
  glUniformMatrix4fv(visual_->uniform("u_view_proj"), 1, GL_FALSE, view_proj.data());
  glUniform3f(visual_->uniform("u_eye"), eye.x(), eye.y(), eye.z());
  glUniform1f(visual_->uniform("u_ref_dist"), ref_dist);
  const std::array<float, 24> planes = frustum_planes(view_proj);
  glUniform4fv(visual_->uniform("u_planes"), 6, planes.data());
  // Texture units 0..4: positions, normals, indices, materials, rest positions; the pattern's
  // on kPatternUnit.
  const std::array<std::pair<GLuint, const char*>, 5> units{{{pos_tex_, "u_pos"},
                                                             {nrm_tex_, "u_nrm"},
                                                             {tri_tex_, "u_tri"},
                                                             {material_tex_, "u_tri_material"},
                                                             {rest_tex_, "u_rest"}}};
  for (std::size_t u = 0; u < units.size(); ++u) {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(u));
    glBindTexture(GL_TEXTURE_BUFFER, units[u].first);
    glUniform1i(visual_->uniform(units[u].second), static_cast<GLint>(u));
  }
  set_pattern_uniforms(*visual_, options.detail);
  glBindVertexArray(pull_vao_);
  glPatchParameteri(GL_PATCH_VERTICES, 3);
  const std::size_t batch = patches_per_draw_ > 0 ? patches_per_draw_ : tri_count_;
  for (std::size_t first = 0; first < tri_count_; first += batch)
    glDrawArrays(GL_PATCHES, static_cast<GLint>(3 * first),
                 static_cast<GLsizei>(3 * std::min(batch, tri_count_ - first)));
  for (std::size_t u = 0; u < units.size(); ++u) {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(u));
    glBindTexture(GL_TEXTURE_BUFFER, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

// Surgical smoke, over what is drawn: blended (its alpha over the colour; the coverage in alpha
// left as it is), depth-tested against the surfaces but not written.
void FrameRenderer::draw_smoke(const RenderFrame& frame, const View& v) {
  if (frame.smoke.empty()) return;
  smoke_puffs_.clear();
  smoke_densities_.clear();
  for (const RenderPuff& p : frame.smoke) {
    smoke_puffs_.insert(smoke_puffs_.end(), {p.at[0], p.at[1], p.at[2], p.radius});
    smoke_densities_.push_back(std::clamp(p.density, 0.0f, 1.0f));
  }
  glBindBuffer(GL_ARRAY_BUFFER, smoke_puff_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(smoke_puffs_.size(), sizeof(float)), smoke_puffs_.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, smoke_density_buf_);
  glBufferData(GL_ARRAY_BUFFER, bytes(smoke_densities_.size(), sizeof(float)),
               smoke_densities_.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(smoke_->id());
  glUniformMatrix4fv(smoke_->uniform("u_view_proj"), 1, GL_FALSE, v.view_proj.data());
  glUniform3f(smoke_->uniform("u_right"), v.right.x(), v.right.y(), v.right.z());
  glUniform3f(smoke_->uniform("u_up"), v.up.x(), v.up.y(), v.up.z());
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glDepthMask(GL_FALSE);
  glBindVertexArray(smoke_vao_);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(frame.smoke.size()));
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

// The scenery with the visual view's lighting (kVisualFragment), untessellated.
void FrameRenderer::draw_scenery(const View& v, bool detail) {
  if (scenery_corners_ == 0) return;
  glUseProgram(scenery_->id());
  glUniformMatrix4fv(scenery_->uniform("u_view_proj"), 1, GL_FALSE, v.view_proj.data());
  glUniform3f(scenery_->uniform("u_eye"), v.eye.x(), v.eye.y(), v.eye.z());
  glUniform1f(scenery_->uniform("u_ref_dist"), v.ref_dist);
  set_pattern_uniforms(*scenery_, detail);
  glBindVertexArray(scenery_vao_);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(scenery_corners_));
  glBindVertexArray(0);
}

void FrameRenderer::draw_collision(const View& v) {
  const Eigen::Matrix4f& view_proj = v.view_proj;
  const Eigen::Vector3f& eye = v.eye;
  if (tri_count_ == 0) return;
  glUseProgram(flat_->id());
  glUniformMatrix4fv(flat_->uniform("u_view_proj"), 1, GL_FALSE, view_proj.data());
  glUniform3f(flat_->uniform("u_eye"), eye.x(), eye.y(), eye.z());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, tri_buf_);
  // Faceted fill, pushed back so that the wireframe on top wins the depth test.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glUniform1i(flat_->uniform("u_shaded"), 1);
  glUniform4f(flat_->uniform("u_color"), 0.55f, 0.70f, 0.75f, 1.0f);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * tri_count_), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
  // The triangles' edges.
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glUniform1i(flat_->uniform("u_shaded"), 0);
  glUniform4f(flat_->uniform("u_color"), 0.05f, 0.25f, 0.10f, 1.0f);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * tri_count_), GL_UNSIGNED_INT, nullptr);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void FrameRenderer::draw_mechanical(const View& v) {
  const Eigen::Matrix4f& view_proj = v.view_proj;
  if (line_count_ == 0) return;
  // See-through: every tet edge is drawn, inner ones included.
  glDisable(GL_DEPTH_TEST);
  glUseProgram(flat_->id());
  glUniformMatrix4fv(flat_->uniform("u_view_proj"), 1, GL_FALSE, view_proj.data());
  glUniform1i(flat_->uniform("u_shaded"), 0);
  glUniform4f(flat_->uniform("u_color"), 0.55f, 0.95f, 1.0f, 1.0f);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, line_buf_);
  glDrawElements(GL_LINES, static_cast<GLsizei>(2 * line_count_), GL_UNSIGNED_INT, nullptr);
  glEnable(GL_DEPTH_TEST);
}

void FrameRenderer::draw(const RenderFrame& frame, const SnapshotOptions& options, int width,
                         int height) {
  if (const auto errors = validate(frame); !errors.empty()) {
    std::string msg = "FrameRenderer::draw: invalid frame:";
    for (const std::string& e : errors) msg += " " + e + ";";
    throw std::invalid_argument(msg);
  }
  if (!uploaded_ || frame.topology_version != topology_version_ ||
      frame.num_triangles() != tri_count_ || frame.edges.size() != edge_source_) {
    upload_topology(frame);
  } else if (frame.material_version != material_version_) {
    upload_materials(frame);
  }
  if (frame.scenery.version != scenery_version_ || frame.scenery.tri.size() != scenery_corners_) {
    upload_scenery(frame.scenery);
  }
  upload_vertices(frame);
  set_pools(frame);
  const bool lens = options.lens && options.view == SnapshotOptions::View::kVisual;
  if (lens) lens_->begin(width, height);
  const View v = view_of(frame, options, width, height);
  const auto& bg = options.background;
  glClearColor(bg[0], bg[1], bg[2], 0.0f);  // alpha 0: coverage is read back in alpha
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glEnable(GL_MULTISAMPLE);
  // Instruments first, depth-tested; the views' lines and surfaces then meet them in depth.
  draw_tools(frame, v.view_proj.data(), v.eye.data(), v.ref_dist, options.depth_cue);
  glBindVertexArray(vao_);
  switch (options.view) {
    case SnapshotOptions::View::kVisual:
      draw_visual(v, options);
      draw_scenery(v, options.detail);
      draw_smoke(frame, v);
      break;
    case SnapshotOptions::View::kCollision:
      draw_collision(v);
      break;
    case SnapshotOptions::View::kMechanical:
      draw_mechanical(v);
      break;
  }
  glBindVertexArray(0);
  glUseProgram(0);
  if (lens) lens_->end(options.optic);
}

}  // namespace serosa::render
