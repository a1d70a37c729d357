// Instrument meshes (no GL): a shaft cylinder through the trocar and two jaws that open and close,
// generated from a RenderTool's pose every frame (a few hundred triangles per tool).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/render_frame.h"

namespace serosa::render {

/// Sizes of the generated instruments, m (5 mm laparoscopic instruments).
struct ToolDimensions {
  float shaft_radius = 0.0025f;   ///< shaft cylinder radius
  float shaft_outside = 0.10f;    ///< shaft length drawn beyond the trocar, outside the body
  float shaft_no_trocar = 0.30f;  ///< shaft length behind the hinge when no trocar is given
  float scissors_blade = 0.016f;  ///< blade length, hinge to tip
  float grasper_jaw = 0.014f;     ///< jaw length, hinge to tip
  int shaft_segments = 16;        ///< facets around the shaft
};

/// Indexed triangles with per-vertex normals and materials, world coordinates.
struct ToolMesh {
  std::vector<float> pos;          ///< (n x 3) positions, m
  std::vector<float> nrm;          ///< (n x 3) unit normals
  std::vector<float> material;     ///< (n x 4) sRGB colour in [0, 1] and specular strength
  std::vector<std::uint32_t> tri;  ///< (t x 3) vertex ids, counter-clockwise seen from outside

  [[nodiscard]] std::size_t num_vertices() const { return pos.size() / 3; }
  [[nodiscard]] std::size_t num_triangles() const { return tri.size() / 3; }
  void clear();
};

/// The tool's frame in world coordinates: `axis` (local +z, handle -> tip), `up` (local +y) and
/// `side` (local +x), orthonormal and right-handed; `hinge` is where the jaws pivot, m. With a
/// trocar the axis is the line trocar -> tip (the shaft must pass through the port) and `up` the
/// pose's +y made orthogonal to it; without one the axis is the pose's +z.
struct ToolFrame {
  std::array<float, 3> axis{0.0f, 0.0f, 1.0f};
  std::array<float, 3> up{0.0f, 1.0f, 0.0f};
  std::array<float, 3> side{1.0f, 0.0f, 0.0f};
  std::array<float, 3> hinge{0.0f, 0.0f, 0.0f};
  std::array<float, 3> shaft_start{0.0f, 0.0f, 0.0f};  ///< the shaft's outer end, m
};
[[nodiscard]] ToolFrame tool_frame(const RenderTool& tool, const ToolDimensions& dims = {});

/// Appends the instrument to `out`: the shaft (a capped cylinder, dark) from shaft_start to the
/// hinge, and two jaws (steel) rotated by +-jaw_rad/2 about the hinge's `up` axis. Scissors
/// blades are thin, tapered, slightly curved and offset along `up` so that they shear past each
/// other; grasper jaws are wider and meet on the axis when closed; a stapler's cartridge and
/// anvil are kCartridgeLength long and wide enough to carry its staple lines.
void append_tool_mesh(const RenderTool& tool, ToolMesh& out, const ToolDimensions& dims = {});

/// The depth cue under a tip (RenderTool::has_tissue): a thin ring on the tissue round the surface
/// point nearest the tip, kDepthCueLift above it, of outer radius kDepthCueMinRadius +
/// kDepthCueSpread x the tip's distance, dark like a shadow, closing in as the tip comes near;
/// amber and wider once the tip is within kTouchDistance (touching). Nothing beyond
/// kDepthCueRange, m.
inline constexpr float kDepthCueRange = 0.05f;
inline constexpr float kDepthCueMinRadius = 3e-3f;
inline constexpr float kDepthCueSpread = 0.3f;
inline constexpr float kDepthCueLift = 2e-4f;
inline constexpr float kTouchDistance = 5e-4f;
void append_depth_cue(const RenderTool& tool, ToolMesh& out);

/// Thickness of a clip's legs across the clip, m.
inline constexpr float kClipLegThickness = 3e-4f;
/// A staple line's drawing, m: the wire's thickness, each staple's crown length and the pitch of
/// the staples along a row (three staggered rows across the line's width).
inline constexpr float kStapleWireThickness = 2.5e-4f;
inline constexpr float kStapleCrown = 3e-3f;
inline constexpr float kStaplePitch = 3.5e-3f;
/// Appends a placed clip: two titanium legs along its centre line, one each side of the pressed
/// tissue (kClipGap apart, engine/clip.h), joined at the far end; a staple line: its rows of
/// closed titanium staples, crowns and clinched legs either side of the tissue (kStapleGap
/// apart, engine/stapler.h).
void append_clip_mesh(const RenderClip& clip, ToolMesh& out);

/// Appends blood, glossy dark red: a drop of bleed.radius about bleed.at and the stream's
/// droplets (the pool is drawn over the surfaces it covers by the visual view's shader).
void append_bleed_mesh(const RenderBleed& bleed, ToolMesh& out);

/// Radius of the guide's marker tube, m.
inline constexpr float kGuideRadius = 4e-4f;
/// Appends the guide polyline (m) as a tube of kGuideRadius, violet like a surgical skin marker.
void append_guide_mesh(const std::vector<std::array<float, 3>>& line, ToolMesh& out);

}  // namespace serosa::render
