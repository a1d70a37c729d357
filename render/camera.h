// Camera placement and matrices (no GL): fit a frame in view, build view and projection.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "render/render_frame.h"

namespace serosa::render {

/// Axis-aligned bounds of the vertices the triangles (or, without triangles, the edges) use, m.
struct Bounds {
  Eigen::Vector3f lo{0.0f, 0.0f, 0.0f};
  Eigen::Vector3f hi{0.0f, 0.0f, 0.0f};
  bool empty = true;  ///< true when nothing is drawn

  [[nodiscard]] Eigen::Vector3f center() const { return 0.5f * (lo + hi); }
  [[nodiscard]] float radius() const { return 0.5f * (hi - lo).norm(); }  ///< bounding sphere, m
};

/// Bounds of what `frame` draws (vertices used by tri, else by edges).
[[nodiscard]] Bounds drawn_bounds(const RenderFrame& frame);

/// A camera that fits the bounding sphere of what `frame` draws in view, with a small margin,
/// looking at its centre from the +z side and somewhat above (+y up, a typical endoscope view of a
/// mesh modelled y-up). The frame's own camera is ignored; fov_y_deg is kept from it.
/// @param aspect  width / height of the image the camera is for
[[nodiscard]] Camera auto_camera(const RenderFrame& frame, float aspect = 4.0f / 3.0f);

/// The view of an endoscope whose tip (the lens, and the light) is at `tip_m` with orientation
/// `quat_wxyz` (tool frame as in docs/scene-format.md: +z along the shaft towards the tip, +y
/// the image's up). A 0 degree scope looks along +z; an angled scope (30 degrees is common)
/// looks `scope_angle_deg` away from the shaft, towards the image's down side (-y), so that
/// rotating the scope about its shaft sweeps the view around. The target lies
/// `working_distance_m` ahead (the light's intensity is 1 there; see the visual shader).
[[nodiscard]] Camera endoscope_camera(const std::array<float, 3>& tip_m,
                                      const std::array<float, 4>& quat_wxyz,
                                      float scope_angle_deg = 0.0f, float fov_y_deg = 70.0f,
                                      float working_distance_m = 0.08f);

/// View and projection matrices (column-major, OpenGL clip conventions) for a camera. Near and far
/// planes enclose `bounds` (with a margin) so that depth precision follows the scene's size.
struct CameraMatrices {
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();        ///< world -> eye
  Eigen::Matrix4f projection = Eigen::Matrix4f::Identity();  ///< eye -> clip
};
[[nodiscard]] CameraMatrices camera_matrices(const Camera& camera, float aspect,
                                             const Bounds& bounds);

}  // namespace serosa::render
