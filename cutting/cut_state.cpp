// The helpers of cut_state.h that several steps of the cut share.
#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

std::vector<double> outline_crossings(const CutState& cs, const V2& u, const V2& w) {
  std::vector<double> out;
  const V2 d = w - u;
  const double len = d.norm();
  if (!(len > 2.0 * cs.tol)) return out;
  const std::size_t k = cs.blade2.size();
  for (std::size_t i = 0; i < k; ++i) {
    const V2& b0 = cs.blade2[i];
    const V2 e = cs.blade2[(i + 1) % k] - b0;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (std::abs(den) <= 1e-14 * len * e.norm()) continue;  // parallel
    const V2 r0 = b0 - u;
    const double s = (r0.x() * e.y() - r0.y() * e.x()) / den;
    const double r = (r0.x() * d.y() - r0.y() * d.x()) / den;
    if (r < -1e-12 || r > 1.0 + 1e-12) continue;
    if (s * len <= cs.tol || (1.0 - s) * len <= cs.tol) continue;
    out.push_back(s);
  }
  std::sort(out.begin(), out.end());
  // Crossings closer than tol (at a blade corner on the segment) are one.
  std::vector<double> merged;
  for (double s : out)
    if (merged.empty() || (s - merged.back()) * len > cs.tol) merged.push_back(s);
  return merged;
}

}  // namespace serosa::cutting::detail
