#include "cutting/smoke_stage.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/state_codec.h"

namespace serosa::cutting {
namespace {

// A repeatable number in [-1, 1] from a puff's serial number.
double spread(std::uint64_t n, std::uint64_t salt) {
  std::uint64_t h = n * 0x9e3779b97f4a7c15ULL + salt;
  h ^= h >> 31;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) / static_cast<double>(1ULL << 52) - 1.0;
}

}  // namespace

SmokeStage::SmokeStage(const Scene& scene) : m_puffs(kMaxPuffs) {
  const Vec3 g = scene.settings.gravity_mps2;
  m_up = g.norm() > 0.0 ? Vec3(-g.normalized()) : Vec3::UnitY();
  m_side1 = m_up.unitOrthogonal();
  m_side2 = m_up.cross(m_side1);
}

void SmokeStage::emit(const Vec3& at, double t) {
  Puff& p = m_puffs[static_cast<std::size_t>(m_next % kMaxPuffs)];
  p.at = {at.x(), at.y(), at.z()};
  p.drift = {kDriftMps * spread(m_next, 1), kDriftMps * spread(m_next, 2)};
  p.born_s = t;
  ++m_next;
}

void SmokeStage::step(const StepContext& ctx, SimState& state) {
  const double t = ctx.time_s + ctx.dt_s;
  const auto& coag = state.handoff.coagulated;
  // Nodes a cut adds take their parents' marks: born coagulated, they raise no smoke. (The marks
  // appear all at once when the first hook coagulates: those do.)
  const bool grown = !m_seen.empty();
  for (std::size_t i = m_seen.size(); i < coag.size(); ++i)
    m_seen.push_back(grown ? coag[i] : std::uint8_t{0});
  int raised = 0;
  for (std::size_t i = 0; i < coag.size() && i < state.mesh.x.size(); ++i) {
    if (coag[i] == 0 || m_seen[i] != 0) continue;
    m_seen[i] = 1;
    if (raised < kPuffsPerStep) {
      emit(state.mesh.x[i], t);
      ++raised;
    }
  }
  for (Puff& p : m_puffs) {
    if (p.born_s < 0.0) continue;
    if (t - p.born_s > kLifeS) {
      p.born_s = -1.0;
      continue;
    }
    const Vec3 v = kRiseMps * m_up + p.drift[0] * m_side1 + p.drift[1] * m_side2;
    for (int k = 0; k < 3; ++k) p.at[static_cast<std::size_t>(k)] += ctx.dt_s * v[k];
  }
  publish(t, state);
}

void SmokeStage::publish(double t, SimState& state) const {
  auto& out = state.handoff.smoke;
  if (out.capacity() < kMaxPuffs) out.reserve(kMaxPuffs);
  out.clear();
  for (const Puff& p : m_puffs) {
    if (p.born_s < 0.0) continue;
    const double age = std::clamp((t - p.born_s) / kLifeS, 0.0, 1.0);
    SmokePuff s;
    s.at_m = Vec3(p.at[0], p.at[1], p.at[2]);
    s.radius_m = kStartRadiusM + kGrowMps * (t - p.born_s);
    s.density = kStartDensity * (1.0 - age) * (1.0 - age);
    out.push_back(s);
  }
}

void SmokeStage::save(StateWriter& out) const {
  out.array(m_puffs);
  out.u64(m_next);
  out.array(m_seen);
}

void SmokeStage::restore(StateReader& in, SimState& state) {
  in.array(m_puffs);
  m_next = in.u64();
  in.array(m_seen);
  if (m_puffs.size() != kMaxPuffs)
    in.fail("smoke of " + std::to_string(m_puffs.size()) + " puffs, not " +
            std::to_string(kMaxPuffs));
  if (m_seen.size() > state.mesh.x.size())
    in.fail("smoke marks for " + std::to_string(m_seen.size()) + " nodes of " +
            std::to_string(state.mesh.x.size()));
  publish(state.time_s, state);
}

}  // namespace serosa::cutting
