// Camera placement and matrices (see camera.h).
#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace serosa::render {
namespace {

Eigen::Vector3f vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

float deg_to_rad(float deg) { return deg * std::numbers::pi_v<float> / 180.0f; }

// Extends `b` by vertex `id` of `pos` (n x 3).
void extend(Bounds& b, const std::vector<float>& pos, std::uint32_t id) {
  if (3 * static_cast<std::size_t>(id) + 2 >= pos.size()) return;
  const Eigen::Vector3f p(pos[3 * id], pos[3 * id + 1], pos[3 * id + 2]);
  if (b.empty) {
    b.lo = b.hi = p;
    b.empty = false;
  } else {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
}

}  // namespace

Bounds drawn_bounds(const RenderFrame& frame) {
  Bounds b;
  const auto& ids = frame.tri.empty() ? frame.edges : frame.tri;
  for (const std::uint32_t id : ids) extend(b, frame.pos, id);
  return b;
}

Camera auto_camera(const RenderFrame& frame, float aspect) {
  Camera cam = frame.camera;
  const Bounds b = drawn_bounds(frame);
  const Eigen::Vector3f center = b.empty ? Eigen::Vector3f::Zero() : b.center();
  const float radius = b.empty ? 1.0f : std::max(b.radius(), 1e-6f);
  // The sphere fits when its angular radius is within the narrower half field of view.
  const float half_y = 0.5f * deg_to_rad(std::clamp(cam.fov_y_deg, 1.0f, 170.0f));
  const float half_x = std::atan(std::tan(half_y) * std::max(aspect, 1e-3f));
  const float half = std::min(half_x, half_y);
  const float distance = 1.1f * radius / std::sin(half);
  const Eigen::Vector3f dir = Eigen::Vector3f(0.25f, 0.45f, 1.0f).normalized();
  const Eigen::Vector3f eye = center + distance * dir;
  cam.eye = {eye.x(), eye.y(), eye.z()};
  cam.target = {center.x(), center.y(), center.z()};
  cam.up = {0.0f, 1.0f, 0.0f};
  return cam;
}

Camera endoscope_camera(const std::array<float, 3>& tip_m, const std::array<float, 4>& quat_wxyz,
                        float scope_angle_deg, float fov_y_deg, float working_distance_m) {
  Eigen::Quaternionf q(quat_wxyz[0], quat_wxyz[1], quat_wxyz[2], quat_wxyz[3]);
  if (!(q.norm() > 1e-6f)) q = Eigen::Quaternionf::Identity();
  q.normalize();
  const Eigen::Matrix3f r = q.toRotationMatrix();
  const float a = deg_to_rad(scope_angle_deg);
  // Tilt about the scope's local x axis: +z towards -y.
  const Eigen::Vector3f dir = std::cos(a) * r.col(2) - std::sin(a) * r.col(1);
  const Eigen::Vector3f up = std::sin(a) * r.col(2) + std::cos(a) * r.col(1);
  const Eigen::Vector3f eye = vec(tip_m);
  const Eigen::Vector3f target = eye + std::max(working_distance_m, 1e-4f) * dir;
  Camera cam;
  cam.eye = tip_m;
  cam.target = {target.x(), target.y(), target.z()};
  cam.up = {up.x(), up.y(), up.z()};
  cam.fov_y_deg = fov_y_deg;
  return cam;
}

CameraMatrices camera_matrices(const Camera& camera, float aspect, const Bounds& bounds) {
  CameraMatrices m;
  const Eigen::Vector3f eye = vec(camera.eye);
  Eigen::Vector3f f = vec(camera.target) - eye;  // forward
  if (f.norm() < 1e-12f) f = -Eigen::Vector3f::UnitZ();
  f.normalize();
  Eigen::Vector3f s = f.cross(vec(camera.up));  // side (right)
  if (s.norm() < 1e-6f) s = f.unitOrthogonal();
  s.normalize();
  const Eigen::Vector3f u = s.cross(f);
  m.view.setIdentity();
  m.view.block<1, 3>(0, 0) = s.transpose();
  m.view.block<1, 3>(1, 0) = u.transpose();
  m.view.block<1, 3>(2, 0) = -f.transpose();
  m.view(0, 3) = -s.dot(eye);
  m.view(1, 3) = -u.dot(eye);
  m.view(2, 3) = f.dot(eye);

  // Near and far around the bounding sphere; the near plane stays a fraction of the distance.
  const Eigen::Vector3f center = bounds.empty ? Eigen::Vector3f::Zero() : bounds.center();
  const float dist = (center - eye).norm();
  const float r = bounds.empty ? 1.0f : std::max(bounds.radius(), 1e-6f);
  const float far_plane = std::max(dist + 1.5f * r, 1e-3f);
  const float near_plane = std::max(dist - 1.5f * r, far_plane * 1e-3f);
  const float t = 1.0f / std::tan(0.5f * deg_to_rad(std::clamp(camera.fov_y_deg, 1.0f, 170.0f)));
  m.projection.setZero();
  m.projection(0, 0) = t / std::max(aspect, 1e-3f);
  m.projection(1, 1) = t;
  m.projection(2, 2) = -(far_plane + near_plane) / (far_plane - near_plane);
  m.projection(2, 3) = -2.0f * far_plane * near_plane / (far_plane - near_plane);
  m.projection(3, 2) = -1.0f;
  return m;
}

}  // namespace serosa::render
