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

void rotated_gradients(const FemElements& el, std::span<const Mat3> rot, std::span<Vec3> rg) {
  const auto m = static_cast<std::ptrdiff_t>(el.elements.size());
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::ptrdiff_t t = 0; t < m; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    for (std::size_t c = 0; c < 4; ++c) rg[4 * ut + c] = rot[ut] * el.elements[ut].grad[c];
  }
}

void fill_system(const TetMesh& mesh, const FemElements& el, const SystemPattern& p,
                 std::span<const Vec3> rg, double dt_s, CsrMatrix& a) {
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
    // R K_ab R^T = V (lambda ra rb^T + mu rb ra^T + mu (ra . rb) I), ra = R b_a.
    for (std::int32_t k = p.incident_ptr[ui]; k < p.incident_ptr[ui + 1]; ++k) {
      const auto inc = static_cast<std::size_t>(p.incident[static_cast<std::size_t>(k)]);
      const std::size_t t = inc / 4;
      const std::size_t ca = inc % 4;
      const TetElement& e = el.elements[t];
      if (!e.active()) continue;
      const double s = (dt2 + dt_s * e.beta_s) * e.volume_m3;
      const double sl = s * e.lambda_pa;
      const double sm = s * e.mu_pa;
      const Vec3& ra = rg[4 * t + ca];
      const Tet& tet = mesh.tets[t];
      for (std::size_t cb = 0; cb < 4; ++cb) {
        if (node_constrained(mesh, el, static_cast<std::size_t>(tet[cb]))) continue;
        const Vec3& rb = rg[4 * t + cb];
        const double dd = sm * ra.dot(rb);
        double* blk = a.val.data() + p.block[t][4 * ca + cb];
        for (int r0 = 0; r0 < 3; ++r0) {
          double* row = blk + r0 * len;
          for (int c0 = 0; c0 < 3; ++c0) row[c0] += sl * ra[r0] * rb[c0] + sm * rb[r0] * ra[c0];
          row[r0] += dd;
        }
      }
    }
  }
}

void multiply_system(const SystemPattern& p, const CsrMatrix& a, std::span<const double> x,
                     std::span<double> y) {
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (p.nodes >= kParallelMin)
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const std::int32_t len = p.row_len[static_cast<std::size_t>(i)];
    const std::int32_t start = a.row_ptr[static_cast<std::size_t>(3 * i)];
    const double* v0 = a.val.data() + start;
    const double* v1 = v0 + len;
    const double* v2 = v1 + len;
    const std::int32_t* c = a.col.data() + start;
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (std::int32_t k = 0; k < len; k += 3) {
      const double* xb = xp + c[k];
      const double x0 = xb[0], x1 = xb[1], x2 = xb[2];
      y0 += v0[k] * x0 + v0[k + 1] * x1 + v0[k + 2] * x2;
      y1 += v1[k] * x0 + v1[k + 1] * x1 + v1[k + 2] * x2;
      y2 += v2[k] * x0 + v2[k + 1] * x1 + v2[k + 2] * x2;
    }
    yp[3 * i] = y0;
    yp[3 * i + 1] = y1;
    yp[3 * i + 2] = y2;
  }
}

void prepare_operator(const TetMesh& mesh, const FemElements& el, double dt_s, SystemOperator& op) {
  const auto n = static_cast<std::ptrdiff_t>(mesh.num_nodes());
  const auto m = static_cast<std::ptrdiff_t>(mesh.num_tets());
  op.diag.resize(static_cast<std::size_t>(n));
  op.free.resize(static_cast<std::size_t>(n));
  op.tet_scale.resize(static_cast<std::size_t>(m));
  op.corner.resize(4 * static_cast<std::size_t>(m));
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const bool c = node_constrained(mesh, el, ui);
    op.free[ui] = c ? 0 : 1;
    op.diag[ui] = c ? (el.node_mass[ui] > 0.0 ? el.node_mass[ui] : 1.0)
                    : el.node_mass[ui] + dt_s * el.node_damping[ui];
  }
  const double dt2 = dt_s * dt_s;
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::ptrdiff_t t = 0; t < m; ++t) {
    const TetElement& e = el.elements[static_cast<std::size_t>(t)];
    op.tet_scale[static_cast<std::size_t>(t)] =
        e.active() ? (dt2 + dt_s * e.beta_s) * e.volume_m3 : 0.0;
  }
}

void apply_operator(const TetMesh& mesh, const FemElements& el, const SystemPattern& p,
                    std::span<const Vec3> rg, SystemOperator& op, std::span<const double> x,
                    std::span<double> y) {
  const auto m = static_cast<std::ptrdiff_t>(mesh.num_tets());
  const double* xp = x.data();
  const std::uint8_t* fr = op.free.data();
  // Pass 1, per tet: s V sigma(sym H), H = sum_b x_b rb^T over free corners.
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::ptrdiff_t t = 0; t < m; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    const double sc = op.tet_scale[ut];
    if (sc == 0.0) {
      for (std::size_t a = 0; a < 4; ++a) op.corner[4 * ut + a].setZero();
      continue;
    }
    const Tet& tet = mesh.tets[ut];
    double h[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (std::size_t b = 0; b < 4; ++b) {
      const auto node = static_cast<std::size_t>(tet[b]);
      const double w = fr[node];  // 0 on constrained nodes (their columns are zero)
      const double* xb = xp + 3 * node;
      const Vec3& r = rg[4 * ut + b];
      const double x0 = w * xb[0], x1 = w * xb[1], x2 = w * xb[2];
      for (int j = 0; j < 3; ++j) {
        h[0][j] += x0 * r[j];
        h[1][j] += x1 * r[j];
        h[2][j] += x2 * r[j];
      }
    }
    const TetElement& e = el.elements[ut];
    const double tr = e.lambda_pa * (h[0][0] + h[1][1] + h[2][2]);
    const double m2 = 2.0 * e.mu_pa;
    const double sxx = sc * (tr + m2 * h[0][0]);
    const double syy = sc * (tr + m2 * h[1][1]);
    const double szz = sc * (tr + m2 * h[2][2]);
    const double sxy = sc * e.mu_pa * (h[0][1] + h[1][0]);
    const double syz = sc * e.mu_pa * (h[1][2] + h[2][1]);
    const double szx = sc * e.mu_pa * (h[2][0] + h[0][2]);
    for (std::size_t a = 0; a < 4; ++a) {
      const Vec3& r = rg[4 * ut + a];
      op.corner[4 * ut + a] =
          Vec3(sxx * r[0] + sxy * r[1] + szx * r[2], sxy * r[0] + syy * r[1] + syz * r[2],
               szx * r[0] + syz * r[1] + szz * r[2]);
    }
  }
  // Pass 2, per node: y_i = D_i x_i + sum of its incident corners' forces.
  double* yp = y.data();
  const Vec3* corner = op.corner.data();
#pragma omp parallel for schedule(static) if (p.nodes >= kParallelMin)
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const double d = op.diag[ui];
    double y0 = d * xp[3 * ui], y1 = d * xp[3 * ui + 1], y2 = d * xp[3 * ui + 2];
    if (fr[ui] != 0)
      for (std::int32_t k = p.incident_ptr[ui]; k < p.incident_ptr[ui + 1]; ++k) {
        const Vec3& c = corner[p.incident[static_cast<std::size_t>(k)]];
        y0 += c[0];
        y1 += c[1];
        y2 += c[2];
      }
    yp[3 * ui] = y0;
    yp[3 * ui + 1] = y1;
    yp[3 * ui + 2] = y2;
  }
}

void operator_inverse_diagonal(const FemElements& el, const SystemPattern& p,
                               std::span<const Vec3> rg, const SystemOperator& op,
                               std::span<double> inv_diag) {
#pragma omp parallel for schedule(static) if (p.nodes >= kParallelMin)
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    Vec3 d = Vec3::Constant(op.diag[ui]);
    if (op.free[ui] != 0)
      for (std::int32_t k = p.incident_ptr[ui]; k < p.incident_ptr[ui + 1]; ++k) {
        const auto inc = static_cast<std::size_t>(p.incident[static_cast<std::size_t>(k)]);
        const TetElement& e = el.elements[inc / 4];
        const double sc = op.tet_scale[inc / 4];
        const Vec3& r = rg[inc];
        // block aa = s V (lambda ra ra^T + mu ra ra^T + mu |ra|^2 I)
        d += sc * ((e.lambda_pa + e.mu_pa) * r.cwiseProduct(r) +
                   Vec3::Constant(e.mu_pa * r.squaredNorm()));
      }
    for (int c = 0; c < 3; ++c)
      inv_diag[3 * ui + static_cast<std::size_t>(c)] = d[c] > 0.0 ? 1.0 / d[c] : 1.0;
  }
}

}  // namespace serosa::fem
