// FrameRenderer: draws a RenderFrame into the bound framebuffer (the GL half of rendering).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "render/render_frame.h"
#include "render/snapshot_options.h"
#include "render/tool_mesh.h"

namespace serosa::render {

class GlProgram;
class LensPass;

/// Owns the GL programs and buffers that draw RenderFrames. Construct and use it with a current
/// OpenGL 4.1+ core context (OffscreenContext or a window's), and destroy it before the context.
///
/// The frame's tools are drawn in every view (meshes from render/tool_mesh.h, regenerated every
/// draw). Vertex positions and normals are uploaded on every draw; triangle and edge indices and
/// the per-triangle materials only when the frame's topology_version (or its triangle or edge
/// count) differs from the last upload. The frame's scenery (the organs' surroundings) is drawn in
/// the visual view only, lit like the organs, and uploaded only when its version (or triangle
/// count) changes; while it is there, the depth range covers it too.
class FrameRenderer {
 public:
  /// Compiles the programs. @throws std::runtime_error with the driver's log on a GLSL error
  FrameRenderer();
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;
  FrameRenderer(FrameRenderer&&) = delete;
  FrameRenderer& operator=(FrameRenderer&&) = delete;

  /// Clears the bound framebuffer to the background and draws `frame` in `options.view` (the
  /// visual view through the endoscope's optic when options.lens: then the picture is drawn at
  /// width x height into the optic's target and stretched over the viewport bound at the call).
  /// Missing normals are computed (area-weighted); the camera is frame.camera, or auto_camera's
  /// when options.fit_camera. The viewport must already cover width x height pixels.
  /// @throws std::invalid_argument when validate(frame) reports a problem
  void draw(const RenderFrame& frame, const SnapshotOptions& options, int width, int height);

  /// How many patches (surface triangles) one tessellated draw call takes at most; 0: all in one.
  /// Mesa's software renderers get kSoftwarePatchesPerDraw, a GPU 0. The picture is the same.
  void set_patches_per_draw(std::size_t n) { patches_per_draw_ = n; }
  [[nodiscard]] std::size_t patches_per_draw() const { return patches_per_draw_; }
  static constexpr std::size_t kSoftwarePatchesPerDraw = 64;

  /// How many times indices and materials were uploaded so far (statistics and tests).
  [[nodiscard]] std::uint64_t topology_uploads() const { return topology_uploads_; }
  /// How many times the scenery was uploaded so far (statistics and tests).
  [[nodiscard]] std::uint64_t scenery_uploads() const { return scenery_uploads_; }

 private:
  /// The camera of a draw: view-projection, eye (the light), the light's reference distance.
  struct View {
    Eigen::Matrix4f view_proj;
    Eigen::Vector3f eye;
    float ref_dist = 1.0f;
    Eigen::Vector3f right = Eigen::Vector3f::UnitX();  // unit: the picture's right, world
    Eigen::Vector3f up = Eigen::Vector3f::UnitY();     // unit: the picture's up, world
  };
  void upload_topology(const RenderFrame& frame);
  void upload_materials(const RenderFrame& frame);
  void upload_vertices(const RenderFrame& frame);
  void upload_scenery(const Scenery& scenery);
  void upload_rest(const RenderFrame& frame);
  void make_pattern_texture();
  void set_pattern_uniforms(const GlProgram& program, bool detail) const;
  void set_pools(const RenderFrame& frame);
  [[nodiscard]] View view_of(const RenderFrame& frame, const SnapshotOptions& options, int width,
                             int height) const;
  void draw_visual(const View& v, const SnapshotOptions& options);
  void draw_collision(const View& v);
  void draw_mechanical(const View& v);
  void draw_scenery(const View& v, bool detail);
  void draw_smoke(const RenderFrame& frame, const View& v);
  void draw_tools(const RenderFrame& frame, const float* view_proj, const float* eye,
                  float ref_dist, bool depth_cue);

  std::unique_ptr<GlProgram> visual_;
  std::unique_ptr<GlProgram> flat_;
  std::unique_ptr<GlProgram> tool_;
  std::unique_ptr<GlProgram> scenery_;
  std::unique_ptr<LensPass> lens_;
  std::unique_ptr<GlProgram> smoke_;
  // Smoke: its vertex array and per-puff (instanced) buffers, and their scratch.
  unsigned int smoke_vao_ = 0;
  unsigned int smoke_puff_buf_ = 0;
  unsigned int smoke_density_buf_ = 0;
  std::vector<float> smoke_puffs_, smoke_densities_;
  // GL object names: vertex arrays (attributes for the flat views, none for the visual view's
  // vertex pulling), position and normal buffers, triangle and line index buffers, the
  // per-triangle material buffer, and the buffer textures the visual view reads them through.
  unsigned int vao_ = 0;
  unsigned int pull_vao_ = 0;
  unsigned int pos_tex_ = 0;
  unsigned int nrm_tex_ = 0;
  unsigned int tri_tex_ = 0;
  unsigned int pos_buf_ = 0;
  unsigned int nrm_buf_ = 0;
  unsigned int tri_buf_ = 0;
  unsigned int line_buf_ = 0;
  unsigned int material_buf_ = 0;
  unsigned int material_tex_ = 0;
  // The rest positions and the wound's rim ((n) RGBA32F) and their buffer texture; the tissue's
  // pattern (a repeating 3D texture, render/tissue_pattern.h).
  unsigned int rest_buf_ = 0;
  unsigned int rest_tex_ = 0;
  unsigned int pattern_tex_ = 0;
  std::vector<float> rest_scratch_;
  // The frame's pools of blood for the visual view's shader: count, (4) centre and radius, m,
  // (4) unit normals.
  int pools_ = 0;
  std::array<float, 16> pool_ = {};
  std::array<float, 12> pool_up_ = {};
  std::array<float, 3> taenia_centre_ = {};
  std::array<float, 3> taenia_axis_ = {};
  // Instruments: their vertex array, interleaved-free attribute buffers and index buffer.
  unsigned int tool_vao_ = 0;
  unsigned int tool_pos_buf_ = 0;
  unsigned int tool_nrm_buf_ = 0;
  unsigned int tool_mat_buf_ = 0;
  unsigned int tool_idx_buf_ = 0;
  ToolMesh tool_mesh_;  // scratch, regenerated every draw
  // Scenery: its vertex array and per-corner position, normal and material (RGBA8) buffers, what
  // they hold (the version, 3 x triangles corners) and its bounds (m; lo > hi: none).
  unsigned int scenery_vao_ = 0;
  unsigned int scenery_pos_buf_ = 0;
  unsigned int scenery_nrm_buf_ = 0;
  unsigned int scenery_mat_buf_ = 0;
  unsigned int scenery_look_buf_ = 0;
  std::uint64_t scenery_version_ = 0;
  std::size_t scenery_corners_ = 0;
  std::uint64_t scenery_uploads_ = 0;
  Eigen::Vector3f scenery_lo_{1.0f, 1.0f, 1.0f};
  Eigen::Vector3f scenery_hi_{0.0f, 0.0f, 0.0f};
  int max_tess_level_ = 64;
  std::size_t patches_per_draw_ = 0;  // see set_patches_per_draw
  int max_texture_buffer_ = 65536;    // texels
  // What the index buffers hold now.
  bool uploaded_ = false;
  std::uint64_t topology_uploads_ = 0;
  std::uint64_t topology_version_ = 0;
  std::uint64_t material_version_ = 0;
  std::size_t tri_count_ = 0;    // triangles
  std::size_t line_count_ = 0;   // line segments (tet edges, or triangle edges when none)
  std::size_t edge_source_ = 0;  // frame.edges.size() at upload
};

}  // namespace serosa::render
