// `serosa bench polar`: the rotation extraction of corotational FEM (fem/rotation.h)
// on random deformation gradients of four kinds, accuracy against time. For Müller et al.'s
// iteration (extract_rotation) and the Newton variant (newton_rotation), each from a cold start
// (q = identity, a tet's first step), the iteration cap is the knob: the mean error against the
// SVD polar factor |R - R_svd|_F and the orthogonality error |R^T R - I|_F, against ns per call.
// The SVD itself (polar_rotation_svd) is the reference: its time and orthogonality are noted.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "bench/suite/bench_parts.h"
#include "fem/rotation.h"

namespace serosa::bench {

namespace {

struct Kind {
  const char* name;   // table suffix
  const char* title;  // what the gradients are
};

constexpr Kind kKinds[] = {
    {"mild", "mild: R (I + 0.1 S), S symmetric in [-1, 1]"},
    {"large", "large: U diag(s) V^T, s in [0.3, 3]"},
    {"flat", "near-flat: U diag(s1, s2, 1e-3 s3) V^T"},
    {"inverted", "inverted: U diag(s1, s2, -s3) V^T, s in [0.3, 2]"},
};

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Quat q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// `count` deformation gradients of kind k (index into kKinds), reproducible.
std::vector<Mat3> gradients(std::size_t k, int count) {
  std::mt19937 rng(1234U + static_cast<unsigned>(k));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Mat3> out;
  out.reserve(static_cast<std::size_t>(count));
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * 0.5 * (u(rng) + 1.0); };
  for (int i = 0; i < count; ++i) {
    Mat3 f;
    if (k == 0) {
      Mat3 s;
      for (int r = 0; r < 3; ++r)
        for (int c = r; c < 3; ++c) s(r, c) = s(c, r) = u(rng);
      f = random_rotation(rng) * (Mat3::Identity() + 0.1 * s);
    } else {
      const double lo = k == 1 ? 0.3 : k == 2 ? 0.5 : 0.3, hi = k == 1 ? 3.0 : 2.0;
      Vec3 sv(in(lo, hi), in(lo, hi), in(lo, hi));
      if (k == 2) sv.z() *= 1e-3;
      if (k == 3) sv.z() = -sv.z();
      f = random_rotation(rng) * sv.asDiagonal() * random_rotation(rng).transpose();
    }
    out.push_back(f);
  }
  return out;
}

struct Measured {
  double mean_error = 0.0;  // mean |R - R_svd|_F
  double max_ortho = 0.0;   // max |R^T R - I|_F
  double ns_per_call = 0.0;
};

// Times `method(F) -> R` over all gradients, then measures its answers against the SVD's.
template <class Method>
Measured measure(const std::vector<Mat3>& fs, const std::vector<Mat3>& ref, Method method) {
  std::vector<Mat3> rs(fs.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < fs.size(); ++i) rs[i] = method(fs[i]);
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  Measured m;
  m.ns_per_call = ns / static_cast<double>(fs.size());
  for (std::size_t i = 0; i < fs.size(); ++i) {
    m.mean_error += (rs[i] - ref[i]).norm();
    m.max_ortho = std::max(m.max_ortho, (rs[i].transpose() * rs[i] - Mat3::Identity()).norm());
  }
  m.mean_error /= static_cast<double>(fs.size());
  return m;
}

}  // namespace

PartResult run_polar_part(const BenchOptions& options) {
  const int samples = options.quick ? 4000 : 100000;
  const std::vector<int> caps = options.quick
                                    ? std::vector<int>{1, 2, 4, 8, 16, 32, 64}
                                    : std::vector<int>{1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
  PartResult result;
  Table svd{"polar_svd", {"kind", "ns_per_call", "max_orthogonality_error"}, {}, {}};
  for (std::size_t k = 0; k < std::size(kKinds); ++k) {
    const std::vector<Mat3> fs = gradients(k, samples);
    std::vector<Mat3> ref(fs.size());
    const Measured s = measure(fs, ref, [](const Mat3& f) { return fem::polar_rotation_svd(f); });
    for (std::size_t i = 0; i < fs.size(); ++i) ref[i] = fem::polar_rotation_svd(fs[i]);
    svd.add(kKinds[k].name, {static_cast<double>(k), s.ns_per_call, s.max_ortho});

    Table t{std::string("polar_") + kKinds[k].name,
            {"iterations", "muller_error", "muller_ns_per_call", "muller_orthogonality_error",
             "newton_error", "newton_ns_per_call", "newton_orthogonality_error"},
            {},
            {}};
    for (int cap : caps) {
      const Measured mu = measure(fs, ref, [cap](const Mat3& f) {
        Quat q = Quat::Identity();
        fem::extract_rotation(f, q, cap);
        return Mat3(q.toRotationMatrix());
      });
      const Measured nw = measure(fs, ref, [cap](const Mat3& f) {
        Quat q = Quat::Identity();
        fem::newton_rotation(f, q, cap, 0.0);
        return Mat3(q.toRotationMatrix());
      });
      t.add("cap " + std::to_string(cap),
            {static_cast<double>(cap), mu.mean_error, mu.ns_per_call, mu.max_ortho, nw.mean_error,
             nw.ns_per_call, nw.max_ortho});
    }
    Plot p;
    p.name = t.name;
    p.title = std::string("rotation extraction, cold start, ") + kKinds[k].title;
    p.x_label = "ns per call";
    p.y_label = "mean |R - R_svd|_F";
    p.log_x = p.log_y = true;
    p.series.push_back({t.name, "muller_ns_per_call", "muller_error",
                        "Müller et al. 2016, iteration cap 1..64", false, true});
    p.series.push_back({t.name, "newton_ns_per_call", "newton_error",
                        "Newton (Müller step when indefinite), cap 1..64", false, false});
    result.plots.push_back(p);
    for (const char* method : {"muller", "newton"}) {
      MonotoneCheck c;
      c.table = t.name;
      c.knob = "iterations";
      c.value = std::string(method) + "_error";
      c.direction = Direction::decreasing;
      c.rel_tol = 1e-3;
      c.abs_tol = 1e-12;  // round-off floor once converged
      c.why = std::string(method) + " on " + kKinds[k].name +
              " gradients: the error falls as the iteration cap rises";
      result.checks.push_back(c);
    }
    char buf[200];
    const auto& last = t.rows.back();
    std::snprintf(buf, sizeof buf,
                  "%s: SVD %.0f ns/call; at cap 64 Müller %.1e (%.0f ns), Newton %.1e (%.0f ns)",
                  kKinds[k].name, s.ns_per_call, last[1], last[2], last[4], last[5]);
    result.notes.emplace_back(buf);
    result.tables.push_back(std::move(t));
  }
  result.tables.push_back(std::move(svd));
  return result;
}

}  // namespace serosa::bench
