#include "contact/support_stage.h"

#include <algorithm>

#include "engine/sim_state.h"

namespace serosa::contact {

SupportStage::SupportStage(const Scene& scene, bool owns_forces)
    : m_supports(scene.supports), m_owns_forces(owns_forces) {}

void SupportStage::step(const StepContext& ctx, SimState& state) {
  const TetMesh& mesh = state.mesh;
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  std::vector<Vec3>& force = state.events.external_force_n;
  if (m_owns_forces) force.clear();
  m_contacts = 0;
  const double inv_dt = 1.0 / ctx.dt_s;
  for (std::size_t i = 0; i < n; ++i) {
    if (mesh.fixed[i] != 0 || !(mesh.mass[i] > 0.0)) continue;
    for (const Support& s : m_supports) {
      const double depth = -(mesh.x[i] - s.point_m).dot(s.normal);
      if (depth <= 0.0) continue;
      const double m = mesh.mass[i];
      const double k = std::min(kSupportStiffness, kSupportBeta * m * inv_dt * inv_dt);
      const double vn = mesh.v[i].dot(s.normal);
      // Empty forces mean none so far this step (FEM reads one per node or none).
      if (force.size() != n) force.assign(n, Vec3::Zero());
      force[i] += (k * depth - kSupportDamping * m * inv_dt * vn) * s.normal;
      ++m_contacts;
    }
  }
}

}  // namespace serosa::contact
