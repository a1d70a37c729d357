// cut_mesh: the paper's pattern-based scissor cut. This file runs the steps in order; each step
// lives in its own file (cutting/cut_state.h lists them) and docs/cutting.md explains the
// algorithm and why it is built this way (the paper's figures are missing).
#include "cutting/cut_mesh.h"

#include "cutting/cut_classify.h"
#include "cutting/cut_coplanar.h"
#include "cutting/cut_emit.h"
#include "cutting/cut_second_pass.h"
#include "cutting/cut_state.h"
#include "cutting/cut_welding.h"

namespace serosa::cutting {

namespace detail {

CutResult cut_pass(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                   const TetBoxQuery& query, double fixed_tol) {
  CutState cs(mesh, blade, options, query, fixed_tol);
  if (!find_candidates(cs)) return std::move(cs.result);
  classify(cs);  // signs, cases, cut points; partial tets analysed (cut_partial)
  decide_faces(cs);
  decide_edges(cs);
  decide_clones(cs);
  emit(cs);
  return std::move(cs.result);
}

}  // namespace detail

CutResult cut_mesh(const TetMesh& mesh, const ConvexPolygon& blade, const CutOptions& options,
                   const TetBoxQuery& query) {
  const TetBoxQuery brute = query ? TetBoxQuery{} : brute_force_query(mesh);
  const TetBoxQuery& q = query ? query : brute;
  CutResult r = detail::cut_pass(mesh, blade, options, q);
  if (r.stats.pinned_centred > 0 && !detail::second_pass(mesh, blade, options, q, r))
    ++r.stats.second_pass_failed;
  return r;
}

}  // namespace serosa::cutting
