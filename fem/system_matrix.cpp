#include "fem/system_matrix.h"
#include "fem/parallel.h"

#include <algorithm>
#include <stdexcept>

namespace serosa::fem {

namespace {

// Items reserved beyond a list's size when it has to move (room for the next cuts nearby).
std::int32_t grown(std::int32_t count) { return count + count / 2 + 2; }

// Gives list i room for `count` items: in place when they fit its capacity, else a new range at
// the end of the storage (the old one becomes an unused gap). Returns true if it moved.
// `scale` entries of `extra` (value/column arrays) follow every item.
bool reserve_list(SlackLists& l, std::size_t i, std::int32_t count) {
  l.count[i] = count;
  if (count <= l.cap[i]) return false;
  const std::int32_t cap = grown(count);
  l.used += cap - l.cap[i];
  l.start[i] = static_cast<std::int32_t>(l.data.size());
  l.cap[i] = cap;
  l.data.resize(l.data.size() + static_cast<std::size_t>(cap));
  return true;
}

// Writes node i's three rows (columns, zero values) from its neighbour list; sets row_len and
// diag_start. The rows start at 9 * nbr.start[i], one after the other.
void write_rows(SystemPattern& p, CsrMatrix& a, std::size_t i) {
  const std::span<const std::int32_t> l = p.nbr.of(i);
  const auto len = static_cast<std::int32_t>(3 * l.size());
  const std::int32_t base = 9 * p.nbr.start[i];
  for (std::size_t r = 0; r < 3; ++r) {
    const auto row = 3 * i + r;
    const std::int32_t s = base + static_cast<std::int32_t>(r) * len;
    a.row_start[row] = s;
    a.row_nz[row] = len;
    auto k = static_cast<std::size_t>(s);
    for (std::int32_t j : l)
      for (std::int32_t c = 0; c < 3; ++c) a.col[k++] = 3 * j + c;
  }
  std::fill(a.val.begin() + base, a.val.begin() + base + 3 * len, 0.0);
  p.row_len[i] = len;
  const auto self = std::lower_bound(l.begin(), l.end(), static_cast<std::int32_t>(i)) - l.begin();
  p.diag_start[i] = base + 3 * static_cast<std::int32_t>(self);
}

// Block starts (3 t_a, 3 t_b) of tet t.
void write_block(const TetMesh& mesh, SystemPattern& p, std::size_t t) {
  const Tet& tet = mesh.tets[t];
  for (std::size_t ca = 0; ca < 4; ++ca) {
    const auto a = static_cast<std::size_t>(tet[ca]);
    const std::span<const std::int32_t> l = p.nbr.of(a);
    for (std::size_t cb = 0; cb < 4; ++cb) {
      const auto k = std::lower_bound(l.begin(), l.end(), tet[cb]) - l.begin();
      p.block[t][4 * ca + cb] = 9 * p.nbr.start[a] + 3 * static_cast<std::int32_t>(k);
    }
  }
}

// Sorted, unique neighbour list of node i (itself included) from its incidence.
void neighbours(const TetMesh& mesh, const SystemPattern& p, std::size_t i,
                std::vector<std::int32_t>& out) {
  out.clear();
  out.push_back(static_cast<std::int32_t>(i));
  for (std::int32_t inc : p.incident_of(i)) {
    const Tet& t = mesh.tets[static_cast<std::size_t>(inc / 4)];
    out.insert(out.end(), t.begin(), t.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

template <class T>
void reserve_ahead(std::vector<T>& v) {
  v.reserve(v.size() + v.size() / 4 + 1024);
}

}  // namespace

void build_pattern(const TetMesh& mesh, SystemPattern& p, CsrMatrix& a) {
  const std::int32_t n = mesh.num_nodes();
  const std::int32_t m = mesh.num_tets();
  const auto un = static_cast<std::size_t>(n);
  p.nodes = n;
  // Node -> (tet, corner) incidence, in ascending tet order (counting sort), no slack.
  SlackLists& inc = p.incident;
  inc.count.assign(un, 0);
  for (const Tet& t : mesh.tets)
    for (std::int32_t i : t) ++inc.count[static_cast<std::size_t>(i)];
  inc.start.resize(un);
  std::int32_t total = 0;
  for (std::size_t i = 0; i < un; ++i) {
    inc.start[i] = total;
    total += inc.count[i];
  }
  inc.cap = inc.count;
  inc.used = total;
  inc.data.clear();
  reserve_ahead(inc.data);
  inc.data.resize(static_cast<std::size_t>(total));
  {
    std::vector<std::int32_t> fill(inc.start);
    for (std::int32_t t = 0; t < m; ++t)
      for (int c = 0; c < 4; ++c) {
        const auto node = static_cast<std::size_t>(mesh.tets[static_cast<std::size_t>(t)][c]);
        inc.data[static_cast<std::size_t>(fill[node]++)] = 4 * t + c;
      }
  }
  // Sorted, unique neighbour list per node (itself included).
  std::vector<std::vector<std::int32_t>> nbr(un);
#pragma omp parallel for schedule(dynamic, 256) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i)
    neighbours(mesh, p, static_cast<std::size_t>(i), nbr[static_cast<std::size_t>(i)]);
  SlackLists& nl = p.nbr;
  nl.start.resize(un);
  nl.count.resize(un);
  total = 0;
  for (std::size_t i = 0; i < un; ++i) {
    nl.start[i] = total;
    nl.count[i] = static_cast<std::int32_t>(nbr[i].size());
    total += nl.count[i];
  }
  nl.cap = nl.count;
  nl.used = total;
  nl.data.clear();
  reserve_ahead(nl.data);
  nl.data.resize(static_cast<std::size_t>(total));
  // CSR structure: three rows per node, 9 entries per neighbour.
  a.rows = 3 * n;
  a.row_start.resize(3 * un + 1);
  a.row_nz.resize(3 * un);
  a.col.clear();
  a.val.clear();
  reserve_ahead(a.col);
  reserve_ahead(a.val);
  a.col.resize(9 * static_cast<std::size_t>(total));
  a.val.resize(9 * static_cast<std::size_t>(total));
  a.row_start[3 * un] = static_cast<std::int32_t>(a.col.size());
  p.row_len.resize(un);
  p.diag_start.resize(un);
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    std::copy(nbr[ui].begin(), nbr[ui].end(), nl.data.begin() + nl.start[ui]);
    write_rows(p, a, ui);
  }
  // Block starts of every (tet, a, b).
  p.block.resize(static_cast<std::size_t>(m));
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::int32_t t = 0; t < m; ++t) write_block(mesh, p, static_cast<std::size_t>(t));
  p.topology_version = mesh.topology_version;
}

PatternUpdateStats update_pattern(const TetMesh& mesh, const TopologyDelta& delta,
                                  std::span<const Tet> removed, SystemPattern& p, CsrMatrix& a) {
  if (p.topology_version != delta.version_before || mesh.topology_version != delta.version_after ||
      removed.size() != delta.removed_tets.size())
    throw std::logic_error("update_pattern: delta does not follow the pattern's version");
  PatternUpdateStats st;
  const auto n_old = static_cast<std::size_t>(p.nodes);
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  // 1. Old tet ids that no longer hold their tet (removed, or moved away), and new ids whose tet
  //    is new here (added, or moved in). Every other tet id keeps its tet (apply()'s slot rules).
  std::vector<std::int32_t> gone(delta.removed_tets);
  std::vector<std::int32_t> fresh(delta.slot_of_added);
  for (const auto& [from, to] : delta.moved_tets) {
    gone.push_back(from);
    fresh.push_back(to);
  }
  std::sort(gone.begin(), gone.end());
  gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
  std::sort(fresh.begin(), fresh.end());
  fresh.erase(std::unique(fresh.begin(), fresh.end()), fresh.end());
  // 2. Touched nodes: those of removed and fresh tets, and every new node. New corners by node.
  std::vector<std::pair<std::int32_t, std::int32_t>> corners;  // (node, 4 * tet + corner)
  corners.reserve(4 * fresh.size());
  for (std::int32_t t : fresh)
    for (int c = 0; c < 4; ++c)
      corners.emplace_back(mesh.tets[static_cast<std::size_t>(t)][c], 4 * t + c);
  std::sort(corners.begin(), corners.end());
  std::vector<std::int32_t> touched;
  for (const Tet& t : removed) touched.insert(touched.end(), t.begin(), t.end());
  for (const auto& c : corners) touched.push_back(c.first);
  for (std::size_t i = n_old; i < n; ++i) touched.push_back(static_cast<std::int32_t>(i));
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  st.nodes_touched = static_cast<std::int32_t>(touched.size());
  // 3. Per-node arrays grow for new nodes (empty lists, no storage yet).
  for (SlackLists* l : {&p.nbr, &p.incident}) {
    l->start.resize(n, 0);
    l->count.resize(n, 0);
    l->cap.resize(n, 0);
  }
  p.row_len.resize(n, 0);
  p.diag_start.resize(n, 0);
  a.rows = static_cast<std::int32_t>(3 * n);
  a.row_start.resize(3 * n + 1);
  a.row_nz.resize(3 * n, 0);
  p.nodes = static_cast<std::int32_t>(n);
  // 4. Incidence of touched nodes: kept old corners plus new ones, ascending.
  std::vector<std::int32_t> list;
  std::vector<std::int32_t> changed;  // nodes whose neighbour list changed
  auto corner = corners.begin();
  for (std::int32_t node : touched) {
    const auto i = static_cast<std::size_t>(node);
    list.clear();
    for (std::int32_t c : p.incident_of(i))
      if (!std::binary_search(gone.begin(), gone.end(), c / 4)) list.push_back(c);
    for (; corner != corners.end() && corner->first == node; ++corner)
      list.push_back(corner->second);
    std::sort(list.begin(), list.end());
    reserve_list(p.incident, i, static_cast<std::int32_t>(list.size()));
    std::copy(list.begin(), list.end(), p.incident.data.begin() + p.incident.start[i]);
  }
  // 5. Neighbour lists and rows of touched nodes, rewritten only where they changed.
  for (std::int32_t node : touched) {
    const auto i = static_cast<std::size_t>(node);
    neighbours(mesh, p, i, list);
    const std::span<const std::int32_t> old = p.nbr.of(i);
    if (i < n_old && std::equal(old.begin(), old.end(), list.begin(), list.end())) continue;
    if (reserve_list(p.nbr, i, static_cast<std::int32_t>(list.size()))) {
      ++st.rows_moved;
      a.col.resize(9 * p.nbr.data.size());
      a.val.resize(9 * p.nbr.data.size());
    }
    std::copy(list.begin(), list.end(), p.nbr.data.begin() + p.nbr.start[i]);
    write_rows(p, a, i);
    changed.push_back(node);
  }
  st.rows_rewritten = static_cast<std::int32_t>(changed.size());
  a.row_start[3 * n] = static_cast<std::int32_t>(a.col.size());
  // 6. Block starts of fresh tets and of every tet touching a rewritten row.
  p.block.resize(m);
  std::vector<std::int32_t> dirty(fresh);
  for (std::int32_t node : changed)
    for (std::int32_t c : p.incident_of(static_cast<std::size_t>(node))) dirty.push_back(c / 4);
  std::sort(dirty.begin(), dirty.end());
  dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
  for (std::int32_t t : dirty) write_block(mesh, p, static_cast<std::size_t>(t));
  st.blocks_updated = static_cast<std::int32_t>(dirty.size());
  p.topology_version = mesh.topology_version;
  // 7. Compaction once the gaps outweigh the lists (amortized over the moves that made them).
  const auto wasteful = [](const SlackLists& l) {
    return static_cast<std::int64_t>(l.data.size()) > l.used + l.used / 2 + 64;
  };
  if (wasteful(p.nbr) || wasteful(p.incident)) {
    build_pattern(mesh, p, a);
    st.compacted = true;
  }
  return st;
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
    double* row0 = a.val.data() + a.row_start[static_cast<std::size_t>(3 * i)];
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
    for (const std::int32_t ic : p.incident_of(ui)) {
      const auto inc = static_cast<std::size_t>(ic);
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
    const std::int32_t start = a.row_start[static_cast<std::size_t>(3 * i)];
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
      for (const std::int32_t ic : p.incident_of(ui)) {
        const Vec3& c = corner[ic];
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
      for (const std::int32_t ic : p.incident_of(ui)) {
        const auto inc = static_cast<std::size_t>(ic);
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
