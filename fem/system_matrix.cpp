#include "fem/system_matrix.h"
#include "fem/parallel.h"

#include <algorithm>

namespace serosa::fem {

void build_pattern(const TetMesh& mesh, SystemPattern& p, CsrMatrix& a) {
  const std::int32_t n = mesh.num_nodes();
  const std::int32_t m = mesh.num_tets();
  p.nodes = n;
  // Node -> (tet, corner) incidence, in ascending tet order (counting sort).
  p.incident_ptr.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const Tet& t : mesh.tets)
    for (std::int32_t i : t) ++p.incident_ptr[static_cast<std::size_t>(i) + 1];
  for (std::int32_t i = 0; i < n; ++i)
    p.incident_ptr[static_cast<std::size_t>(i) + 1] += p.incident_ptr[static_cast<std::size_t>(i)];
  p.incident.resize(static_cast<std::size_t>(4) * static_cast<std::size_t>(m));
  {
    std::vector<std::int32_t> fill(p.incident_ptr.begin(), p.incident_ptr.end() - 1);
    for (std::int32_t t = 0; t < m; ++t)
      for (int c = 0; c < 4; ++c) {
        const auto node = static_cast<std::size_t>(mesh.tets[static_cast<std::size_t>(t)][c]);
        p.incident[static_cast<std::size_t>(fill[node]++)] = 4 * t + c;
      }
  }
  // Sorted, unique neighbour list per node (itself included).
  std::vector<std::vector<std::int32_t>> nbr(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 256) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i) {
    auto& l = nbr[static_cast<std::size_t>(i)];
    l.push_back(i);
    for (std::int32_t k = p.incident_ptr[static_cast<std::size_t>(i)];
         k < p.incident_ptr[static_cast<std::size_t>(i) + 1]; ++k) {
      const Tet& t =
          mesh.tets[static_cast<std::size_t>(p.incident[static_cast<std::size_t>(k)] / 4)];
      l.insert(l.end(), t.begin(), t.end());
    }
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  // CSR structure: three identical rows per node.
  a.rows = 3 * n;
  a.row_ptr.assign(static_cast<std::size_t>(a.rows) + 1, 0);
  p.row_len.resize(static_cast<std::size_t>(n));
  p.diag_start.resize(static_cast<std::size_t>(n));
  std::int64_t nnz = 0;
  for (std::int32_t i = 0; i < n; ++i) {
    const auto len = static_cast<std::int32_t>(3 * nbr[static_cast<std::size_t>(i)].size());
    p.row_len[static_cast<std::size_t>(i)] = len;
    for (int r = 0; r < 3; ++r) {
      a.row_ptr[static_cast<std::size_t>(3 * i + r)] = static_cast<std::int32_t>(nnz);
      nnz += len;
    }
  }
  a.row_ptr[static_cast<std::size_t>(a.rows)] = static_cast<std::int32_t>(nnz);
  a.col.resize(static_cast<std::size_t>(nnz));
  a.val.assign(static_cast<std::size_t>(nnz), 0.0);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i) {
    const auto& l = nbr[static_cast<std::size_t>(i)];
    for (int r = 0; r < 3; ++r) {
      std::int32_t k = a.row_ptr[static_cast<std::size_t>(3 * i + r)];
      for (std::int32_t j : l)
        for (int c = 0; c < 3; ++c) a.col[static_cast<std::size_t>(k++)] = 3 * j + c;
    }
    const auto self = std::lower_bound(l.begin(), l.end(), i) - l.begin();
    p.diag_start[static_cast<std::size_t>(i)] =
        a.row_ptr[static_cast<std::size_t>(3 * i)] + 3 * static_cast<std::int32_t>(self);
  }
  // Block starts of every (tet, a, b).
  p.block.resize(static_cast<std::size_t>(m));
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::int32_t t = 0; t < m; ++t) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    for (int ca = 0; ca < 4; ++ca) {
      const auto& l = nbr[static_cast<std::size_t>(tet[ca])];
      for (int cb = 0; cb < 4; ++cb) {
        const auto k = std::lower_bound(l.begin(), l.end(), tet[cb]) - l.begin();
        p.block[static_cast<std::size_t>(t)][static_cast<std::size_t>(4 * ca + cb)] =
            a.row_ptr[static_cast<std::size_t>(3 * tet[ca])] + 3 * static_cast<std::int32_t>(k);
      }
    }
  }
  p.topology_version = mesh.topology_version;
}

void fill_system(const TetMesh& mesh, const FemElements& el, const SystemPattern& p,
                 std::span<const Mat3> rot, double dt_s, CsrMatrix& a) {
  const double dt2 = dt_s * dt_s;
#pragma omp parallel for schedule(static) if (p.nodes >= kParallelMin)
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const std::int32_t len = p.row_len[ui];
    double* row0 = a.val.data() + a.row_ptr[static_cast<std::size_t>(3 * i)];
    std::fill(row0, row0 + 3 * len, 0.0);
    const std::int32_t d = p.diag_start[ui];
    // Lumped mass and mass damping on the diagonal: (m_i + dt c_i) I.
    if (node_constrained(mesh, el, ui)) {
      const double diag = el.node_mass[ui] > 0.0 ? el.node_mass[ui] : 1.0;
      for (int r = 0; r < 3; ++r) a.val[static_cast<std::size_t>(d + r * len + r)] = diag;
      continue;
    }
    const double md = el.node_mass[ui] + dt_s * el.node_damping[ui];
    for (int r = 0; r < 3; ++r) a.val[static_cast<std::size_t>(d + r * len + r)] = md;
    // (dt^2 + dt beta) R K_ab R^T for every incident tet and every other corner b, with
    // R K_ab R^T = V (lambda Rb_a (Rb_b)^T + mu Rb_b (Rb_a)^T + mu (b_a . b_b) I).
    for (std::int32_t k = p.incident_ptr[ui]; k < p.incident_ptr[ui + 1]; ++k) {
      const std::int32_t t = p.incident[static_cast<std::size_t>(k)] / 4;
      const int ca = p.incident[static_cast<std::size_t>(k)] % 4;
      const TetElement& e = el.elements[static_cast<std::size_t>(t)];
      if (!e.active()) continue;
      const Mat3& r = rot[static_cast<std::size_t>(t)];
      const double s = (dt2 + dt_s * e.beta_s) * e.volume_m3;
      const Vec3 ra = r * e.grad[static_cast<std::size_t>(ca)];
      const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
      for (int cb = 0; cb < 4; ++cb) {
        if (node_constrained(mesh, el, static_cast<std::size_t>(tet[cb]))) continue;
        const Vec3 rb = r * e.grad[static_cast<std::size_t>(cb)];
        const Mat3 blk =
            s *
            (e.lambda_pa * ra * rb.transpose() + e.mu_pa * rb * ra.transpose() +
             e.mu_pa *
                 e.grad[static_cast<std::size_t>(ca)].dot(e.grad[static_cast<std::size_t>(cb)]) *
                 Mat3::Identity());
        const std::int32_t b0 =
            p.block[static_cast<std::size_t>(t)][static_cast<std::size_t>(4 * ca + cb)];
        for (int r0 = 0; r0 < 3; ++r0)
          for (int c0 = 0; c0 < 3; ++c0)
            a.val[static_cast<std::size_t>(b0 + r0 * len + c0)] += blk(r0, c0);
      }
    }
  }
}

}  // namespace serosa::fem
