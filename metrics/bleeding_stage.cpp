#include "metrics/bleeding_stage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace serosa::metrics {
namespace {

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> arr(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The distance from p to the segment [a, b], m.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// The mean of pulse() over a heartbeat: 0.3 + 0.7 x (the mean of sin^2 over its positive half).
constexpr double kMeanPulse = 0.3 + 0.7 * 0.25;

double pool_radius(double shed_m3) {
  return std::min(std::sqrt(shed_m3 / (std::numbers::pi * BleedingStage::kPoolDepthM)),
                  BleedingStage::kMaxPoolRadiusM);
}

}  // namespace

BleedingStage::BleedingStage(const Scene& scene) {
  const Vec3 g = scene.settings.gravity_mps2;
  m_down = g.norm() > 0.0 ? Vec3(g.normalized()) : Vec3(0.0, -1.0, 0.0);
  if (!scene.supports.empty()) m_floor = scene.supports.front();
}

double BleedingStage::pulse(double t, double since) {
  const double phase = std::sin(2.0 * std::numbers::pi * kHeartRateHz * (t - since));
  const double systole = std::max(phase, 0.0);
  return 0.3 + 0.7 * systole * systole;
}

// A new bleeding: the node nearest the cut carries its end; the pool lies where a drop from it
// falls onto the floor.
void BleedingStage::begin(const Vec3& where, double since, SimState& state) const {
  Source s;
  s.since_s = since;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < state.mesh.x.size(); ++i) {
    const double d = (state.mesh.x[i] - where).squaredNorm();
    if (d < best) {
      best = d;
      s.node = static_cast<std::int64_t>(i);
    }
  }
  Vec3 pool = where, normal = -m_down;
  if (m_floor) {
    const double fall = m_down.dot(m_floor->normal);
    if (fall < -1e-9) {
      pool = where + ((m_floor->point_m - where).dot(m_floor->normal) / fall) * m_down;
      normal = m_floor->normal;
    }
  }
  s.pool = arr(pool);
  s.pool_normal = arr(normal);
  s.coagulated_near = coagulated_near(state.mesh.x[static_cast<std::size_t>(s.node)], state);
  state.blocks.bleeding.sources.push_back(s);
}

// The coagulated nodes within kClosedByM of the cut end.
std::int64_t BleedingStage::coagulated_near(const Vec3& end, const SimState& state) {
  const auto& coag = state.blocks.cutting.coagulated;
  std::int64_t n = 0;
  for (std::size_t i = 0; i < coag.size() && i < state.mesh.x.size(); ++i)
    n += coag[i] != 0 && (state.mesh.x[i] - end).norm() < kClosedByM ? 1 : 0;
  return n;
}

// A ligature placed since the bleeding began reaching within kClosedByM of the cut end, or more
// coagulated nodes that near than when it began.
bool BleedingStage::closed(const Source& s, const SimState& state) const {
  const Vec3& end = state.mesh.x[static_cast<std::size_t>(s.node)];
  for (const Clip& c : state.shared.clips)
    if (c.placed_s >= s.since_s &&
        segment_distance(end, c.end(0), c.end(1)) < c.reach_m() + kClosedByM)
      return true;
  return coagulated_near(end, state) > s.coagulated_near;
}

// Every node within the pool's reach takes its stain (kept: blood stains for good).
void BleedingStage::stain(const Source& s, double radius, SimState& state) {
  if (radius <= 0.0) return;
  const Vec3 centre = vec(s.pool);
  for (std::size_t i = 0; i < state.mesh.x.size(); ++i) {
    const double d = (state.mesh.x[i] - centre).norm();
    if (d >= radius) continue;
    const double w = std::clamp((radius - d) / (0.3 * radius), 0.0, 1.0);
    float& st = state.blocks.bleeding.stain[i];
    st = std::max(st, static_cast<float>(w));
  }
}

void BleedingStage::step(const StepContext& ctx, SimState& state) {
  const auto& bleeds = state.shared.bleeds;
  BleedingBlock& b = state.blocks.bleeding;
  for (std::size_t k = b.sources.size(); k < bleeds.size(); ++k)
    begin(bleeds[k].first, bleeds[k].second, state);
  if (b.sources.empty()) return;  // nothing bleeds: nothing is stained, nothing published
  b.stain.resize(state.mesh.x.size(), 0.0f);  // cuts add nodes (unstained)
  const double t = ctx.time_s + ctx.dt_s;
  for (Source& s : b.sources) {
    // The stroke that cut it coagulates on for a moment: only coagulation after that closes it.
    if (s.closed_s < 0.0 && t - s.since_s < kOwnStrokeS)
      s.coagulated_near =
          std::max(s.coagulated_near,
                   coagulated_near(state.mesh.x[static_cast<std::size_t>(s.node)], state));
    else if (s.closed_s < 0.0 && closed(s, state))
      s.closed_s = t;
    if (s.closed_s < 0.0) {
      s.shed_m3 += kFlowM3PerS / kMeanPulse * pulse(t, s.since_s) * ctx.dt_s;
      stain(s, pool_radius(s.shed_m3), state);
    }
  }
  publish(t, state);
}

void BleedingStage::publish(double time_s, SimState& state) {
  const std::vector<Source>& sources = state.blocks.bleeding.sources;
  state.shared.blood.resize(sources.size());
  for (std::size_t k = 0; k < sources.size(); ++k) {
    const Source& s = sources[k];
    Blood& b = state.shared.blood[k];
    const auto node = static_cast<std::size_t>(s.node);
    b.source_m = node < state.mesh.x.size() ? state.mesh.x[node] : vec(s.pool);
    b.pool_m = vec(s.pool);
    b.pool_normal = vec(s.pool_normal);
    b.pool_radius_m = pool_radius(s.shed_m3);
    b.pulse = s.closed_s < 0.0 ? pulse(time_s, s.since_s) : 0.0;
    b.since_s = s.since_s;
    b.shed_m3 = s.shed_m3;
  }
}

void BleedingStage::adopt(SimState& state) {
  const BleedingBlock& b = state.blocks.bleeding;
  const std::size_t n = state.mesh.x.size();
  for (const Source& s : b.sources)
    if (s.node < 0 || static_cast<std::size_t>(s.node) >= n)
      throw BlockMismatch("bleeding from node " + std::to_string(s.node) + " of " +
                          std::to_string(n));
  if (b.stain.size() > n)
    throw BlockMismatch("stain for " + std::to_string(b.stain.size()) + " nodes of " +
                        std::to_string(n));
  state.shared.blood.clear();
  if (!b.sources.empty()) publish(state.time_s, state);
}

}  // namespace serosa::metrics
