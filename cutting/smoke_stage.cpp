#include "cutting/smoke_stage.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/stage.h"

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

SmokeStage::SmokeStage(const Scene& scene) {
  const Vec3 g = scene.settings.gravity_mps2;
  m_up = g.norm() > 0.0 ? Vec3(-g.normalized()) : Vec3::UnitY();
  m_side1 = m_up.unitOrthogonal();
  m_side2 = m_up.cross(m_side1);
}

void SmokeStage::emit(SmokeBlock& b, const Vec3& at, double t) {
  Puff& p = b.puffs[static_cast<std::size_t>(b.next % kMaxPuffs)];
  p.at = {at.x(), at.y(), at.z()};
  p.drift = {kDriftMps * spread(b.next, 1), kDriftMps * spread(b.next, 2)};
  p.born_s = t;
  ++b.next;
}

void SmokeStage::step(const StepContext& ctx, SimState& state) {
  const double t = ctx.time_s + ctx.dt_s;
  SmokeBlock& b = state.blocks.smoke;
  if (b.puffs.empty()) b.puffs.resize(kMaxPuffs);  // the ring, sized once
  const auto& coag = state.blocks.cutting.coagulated;
  // Nodes a cut adds take their parents' marks: born coagulated, they raise no smoke. (The marks
  // appear all at once when the first hook coagulates: those do.)
  const bool grown = !b.seen.empty();
  for (std::size_t i = b.seen.size(); i < coag.size(); ++i)
    b.seen.push_back(grown ? coag[i] : std::uint8_t{0});
  int raised = 0;
  for (std::size_t i = 0; i < coag.size() && i < state.mesh.x.size(); ++i) {
    if (coag[i] == 0 || b.seen[i] != 0) continue;
    b.seen[i] = 1;
    if (raised < kPuffsPerStep) {
      emit(b, state.mesh.x[i], t);
      ++raised;
    }
  }
  for (Puff& p : b.puffs) {
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

void SmokeStage::publish(double t, SimState& state) {
  auto& out = state.shared.smoke;
  if (out.capacity() < kMaxPuffs) out.reserve(kMaxPuffs);
  out.clear();
  for (const Puff& p : state.blocks.smoke.puffs) {
    if (p.born_s < 0.0) continue;
    const double age = std::clamp((t - p.born_s) / kLifeS, 0.0, 1.0);
    SmokePuff s;
    s.at_m = Vec3(p.at[0], p.at[1], p.at[2]);
    s.radius_m = kStartRadiusM + kGrowMps * (t - p.born_s);
    s.density = kStartDensity * (1.0 - age) * (1.0 - age);
    out.push_back(s);
  }
}

void SmokeStage::adopt(SimState& state) {
  const SmokeBlock& b = state.blocks.smoke;
  if ((state.step > 0 || !b.puffs.empty()) && b.puffs.size() != kMaxPuffs)
    throw BlockMismatch("smoke of " + std::to_string(b.puffs.size()) + " puffs, not " +
                        std::to_string(kMaxPuffs));
  if (b.seen.size() > state.mesh.x.size())
    throw BlockMismatch("smoke marks for " + std::to_string(b.seen.size()) + " nodes of " +
                        std::to_string(state.mesh.x.size()));
  publish(state.time_s, state);
}

}  // namespace serosa::cutting
