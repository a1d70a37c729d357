// The boundary extraction of the paper's Figure 10, written once over a Thrust execution policy
// and a storage type, and compiled twice: by g++ with thrust::omp::par on std::vector storage
// (extract_surface_omp.cpp) and by nvcc with thrust::cuda::par on thrust::device_vector storage
// (extract_surface_cuda.cu). Include only from those two files. Free of Eigen and TetMesh, so
// that nvcc compiles only Thrust and this file.
//
// Pipeline, for m tets (F = 4 m faces):
//  1. face ids 0..F-1 (face = 4 tet + l, l the local node it is opposite) and their sorted-node
//     keys (surface/face_key.h);
//  2. sort_by_key(keys, face ids): the two copies of an interior face become neighbours;
//  3. reduce_by_key(keys, (face id, 1)) -> per distinct face (smallest face id, count);
//  4. copy_if count == 1: the boundary faces (count 2: interior; 3 or more: invalid mesh, dropped);
//  5. stable_sort_by_key(group of each boundary face, face ids): each group contiguous, faces
//     inside a group stay in key order (so the result is deterministic);
//  6. reduce_by_key(groups, 1) -> (group id, face count) per group;
//  7. write each face with outward orientation from its tet (face_key.h outward_face) and its tet.
// Limits: m < 2^30 tets (face ids are uint32), node ids in [0, 2^31).
#pragma once

#include <thrust/copy.h>
#include <thrust/for_each.h>
#include <thrust/functional.h>
#include <thrust/iterator/constant_iterator.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/discard_iterator.h>
#include <thrust/iterator/zip_iterator.h>
#include <thrust/memory.h>
#include <thrust/reduce.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform.h>
#include <thrust/tuple.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "surface/face_key.h"
#include "surface/hd.h"

namespace serosa::surface::detail {

/// Key of face id f (= 4 tet + l).
template <class Key, class TetPtr>
struct FaceKeyOf {
  TetPtr tets;  ///< (m) tets, each indexable by 0..3
  SEROSA_HD Key operator()(std::uint32_t f) const {
    std::int32_t a = 0, b = 0, c = 0;
    outward_face(tets[f >> 2], static_cast<int>(f & 3u), a, b, c);
    return make_face_key<Key>(a, b, c);
  }
};

/// Combines (face id, count) pairs of equal keys: smallest id, summed count.
struct MinIdSumCount {
  using Pair = thrust::tuple<std::uint32_t, std::int32_t>;
  SEROSA_HD Pair operator()(const Pair& p, const Pair& q) const {
    const std::uint32_t i = thrust::get<0>(p);
    const std::uint32_t j = thrust::get<0>(q);
    return Pair(i < j ? i : j, thrust::get<1>(p) + thrust::get<1>(q));
  }
};

struct IsOnce {
  SEROSA_HD bool operator()(std::int32_t count) const { return count == 1; }
};

/// Group of the tet owning face id f.
struct GroupOfFace {
  const std::uint16_t* group;  ///< (m)
  SEROSA_HD std::uint16_t operator()(std::uint32_t f) const { return group[f >> 2]; }
};

/// Writes boundary face i: outward node ids and owning tet.
template <class TetPtr, class TriT>
struct WriteFace {
  TetPtr tets;                   ///< (m)
  const std::uint32_t* face_id;  ///< (f) boundary face ids, group order
  TriT* tri;                     ///< (f) out
  std::int32_t* tet;             ///< (f) out
  SEROSA_HD void operator()(std::int64_t i) const {
    const std::uint32_t f = face_id[i];
    std::int32_t a = 0, b = 0, c = 0;
    outward_face(tets[f >> 2], static_cast<int>(f & 3u), a, b, c);
    tri[i] = TriT{{a, b, c}};
    tet[i] = static_cast<std::int32_t>(f >> 2);
  }
};

/// Output of extract_boundary, in the backend's storage Vec.
template <template <class> class Vec, class TriT>
struct Boundary {
  Vec<TriT> faces;                ///< (f) outward node ids, grouped
  Vec<std::int32_t> face_tet;     ///< (f) owning tet
  Vec<std::uint16_t> face_group;  ///< (f) ascending
  Vec<std::uint16_t> group_ids;   ///< (g) ascending, distinct
  Vec<std::int32_t> group_count;  ///< (g) faces per group
};

/// Runs the pipeline above. `tets` and `group` point to m entries in the policy's memory
/// (host for OpenMP, device for CUDA); Key is NarrowKey (ids < 2^21) or WideKey.
template <class Key, template <class> class Vec, class TriT, class Policy, class TetPtr>
void extract_boundary(const Policy& policy, TetPtr tets, const std::uint16_t* group, std::int32_t m,
                      Boundary<Vec, TriT>& out) {
  out = Boundary<Vec, TriT>{};
  if (m <= 0) return;
  const auto nf = static_cast<std::int64_t>(m) * 4;

  // 1.-2. Keys of every face, sorted with their face ids.
  Vec<std::uint32_t> face_id(static_cast<std::size_t>(nf));
  Vec<Key> key(static_cast<std::size_t>(nf));
  std::uint32_t* id_p = thrust::raw_pointer_cast(face_id.data());
  Key* key_p = thrust::raw_pointer_cast(key.data());
  thrust::sequence(policy, id_p, id_p + nf);
  thrust::transform(policy, id_p, id_p + nf, key_p, FaceKeyOf<Key, TetPtr>{tets});
  thrust::sort_by_key(policy, key_p, key_p + nf, id_p);

  // 3. Count the copies of each distinct face.
  Vec<std::uint32_t> uid(static_cast<std::size_t>(nf));
  Vec<std::int32_t> ucount(static_cast<std::size_t>(nf));
  std::uint32_t* uid_p = thrust::raw_pointer_cast(uid.data());
  std::int32_t* ucount_p = thrust::raw_pointer_cast(ucount.data());
  const auto values = thrust::make_zip_iterator(
      thrust::make_tuple(id_p, thrust::make_constant_iterator<std::int32_t>(1)));
  const auto ends =
      thrust::reduce_by_key(policy, key_p, key_p + nf, values, thrust::make_discard_iterator(),
                            thrust::make_zip_iterator(thrust::make_tuple(uid_p, ucount_p)),
                            thrust::equal_to<Key>(), MinIdSumCount());
  const std::int64_t nu = thrust::get<0>(ends.second.get_iterator_tuple()) - uid_p;

  // 4. Keep the faces seen once (reusing face_id as the output).
  const std::int64_t nb =
      thrust::copy_if(policy, uid_p, uid_p + nu, ucount_p, id_p, IsOnce()) - id_p;

  // 5. Order by group, stable so that faces keep key order inside a group.
  out.face_group.resize(static_cast<std::size_t>(nb));
  std::uint16_t* fg_p = thrust::raw_pointer_cast(out.face_group.data());
  thrust::transform(policy, id_p, id_p + nb, fg_p, GroupOfFace{group});
  thrust::stable_sort_by_key(policy, fg_p, fg_p + nb, id_p);

  // 6. Faces per group.
  out.group_ids.resize(static_cast<std::size_t>(nb));
  out.group_count.resize(static_cast<std::size_t>(nb));
  std::uint16_t* gid_p = thrust::raw_pointer_cast(out.group_ids.data());
  std::int32_t* gcount_p = thrust::raw_pointer_cast(out.group_count.data());
  const auto gends = thrust::reduce_by_key(
      policy, fg_p, fg_p + nb, thrust::make_constant_iterator<std::int32_t>(1), gid_p, gcount_p);
  const std::int64_t ng = gends.first - gid_p;
  out.group_ids.resize(static_cast<std::size_t>(ng));
  out.group_count.resize(static_cast<std::size_t>(ng));

  // 7. Oriented faces and their tets.
  out.faces.resize(static_cast<std::size_t>(nb));
  out.face_tet.resize(static_cast<std::size_t>(nb));
  thrust::for_each(policy, thrust::make_counting_iterator<std::int64_t>(0),
                   thrust::make_counting_iterator<std::int64_t>(nb),
                   WriteFace<TetPtr, TriT>{tets, id_p, thrust::raw_pointer_cast(out.faces.data()),
                                           thrust::raw_pointer_cast(out.face_tet.data())});
}

/// Host side, before the pipeline: checks the limits (fewer than 2^30 tets, node ids >= 0) and
/// returns true when the 64-bit NarrowKey is exact (every id < 2^21) and not `force_wide`.
/// Throws std::invalid_argument past the limits. TetVec: a host vector of 4-id tets.
template <class TetVec>
inline bool pick_narrow_keys(const TetVec& tets, bool force_wide) {
  if (tets.size() >= (std::size_t{1} << 30))
    throw std::invalid_argument("extract_surface: " + std::to_string(tets.size()) +
                                " tets, more than 2^30");
  std::int32_t lo = 0, hi = 0;
  for (const auto& t : tets)
    for (int k = 0; k < 4; ++k) {
      lo = t[k] < lo ? t[k] : lo;
      hi = t[k] > hi ? t[k] : hi;
    }
  if (lo < 0) throw std::invalid_argument("extract_surface: negative node id in a tet");
  return !force_wide && hi < kNarrowKeyMaxNodes;
}

}  // namespace serosa::surface::detail
