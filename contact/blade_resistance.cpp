#include "contact/blade_resistance.h"

#include <algorithm>
#include <cmath>

#include "engine/tool_geometry.h"

namespace serosa::contact {
namespace {

double young_pa(const Lame& l) {
  const double sum = l.lambda + l.mu;
  return sum > 0.0 ? l.mu * (3.0 * l.lambda + 2.0 * l.mu) / sum : 0.0;
}

double rest_volume(const TetMesh& mesh, const Tet& t) {
  const Vec3& a = mesh.rest[static_cast<std::size_t>(t[0])];
  return std::abs((mesh.rest[static_cast<std::size_t>(t[1])] - a)
                      .dot((mesh.rest[static_cast<std::size_t>(t[2])] - a)
                               .cross(mesh.rest[static_cast<std::size_t>(t[3])] - a))) /
         6.0;
}

}  // namespace

void BladeResistance::update(const TetMesh& mesh, const LameTable& table) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  m_volume_m3.assign(n, 0.0);
  m_strength_pa.assign(n, 0.0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const double v = 0.25 * rest_volume(mesh, mesh.tets[t]);
    const double s = kShearStrengthPerYoung * young_pa(table.of(mesh.group[t]));
    for (std::int32_t k : mesh.tets[t]) {
      m_volume_m3[static_cast<std::size_t>(k)] += v;
      m_strength_pa[static_cast<std::size_t>(k)] += v * s;  // volume-weighted, divided below
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (m_volume_m3[i] > 0.0) m_strength_pa[i] /= m_volume_m3[i];
  m_version = mesh.topology_version;
}

BladeLoad BladeResistance::load(const TetMesh& mesh, const ToolState& tool,
                                double stroke_open_rad) const {
  BladeLoad out;
  if (!(tool.jaw_rad < stroke_open_rad)) return out;
  const ToolFrame f = tool_frame(tool);
  const double from = 0.5 * std::max(tool.jaw_rad, 0.0);  // blade angles off the shaft axis
  const double to = 0.5 * stroke_open_rad;
  const std::size_t n = std::min(m_volume_m3.size(), mesh.x.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = mesh.x[i] - f.hinge;
    if (std::abs(d.dot(f.pin)) > 0.5 * kBladeSlab) continue;
    const double along = d.dot(f.forward);
    const double across = std::abs(d.dot(f.side));
    const double r = std::hypot(along, across);
    if (r > kJawLength || r <= 0.0) continue;
    const double angle = std::atan2(across, along);  // off the shaft axis, either side
    if (angle < from || angle > to) continue;
    const double force = m_strength_pa[i] * (m_volume_m3[i] / kBladeSlab);
    out.force_n += force;
    out.torque_nm += force * r;
  }
  return out;
}

}  // namespace serosa::contact
