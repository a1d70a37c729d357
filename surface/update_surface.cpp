#include "surface/update_surface.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace serosa::surface {
namespace {

using Entry = FaceTable::Entry;

WideKey key_of(const Tri& f) { return make_face_key<WideKey>(f[0], f[1], f[2]); }

WideKey face_key(const Tet& t, int l) {
  std::int32_t a = 0, b = 0, c = 0;
  outward_face(t, l, a, b, c);
  return make_face_key<WideKey>(a, b, c);
}

// Edits of the group-contiguous face arrays, keeping table.key_at and every entry's pos in step.
class FaceArrays {
 public:
  FaceArrays(SurfaceMesh& s, FaceTable& t, std::vector<std::int32_t>* changed)
      : s_(s), t_(t), changed_(changed) {}

  // Records that slot p was written.
  void touch(std::int32_t p) {
    if (changed_ != nullptr) changed_->push_back(p);
  }

  // Moves face `from` onto slot `to` (overwriting it).
  void move(std::int32_t from, std::int32_t to) {
    const auto f = static_cast<std::size_t>(from), d = static_cast<std::size_t>(to);
    s_.faces[d] = s_.faces[f];
    s_.face_tet[d] = s_.face_tet[f];
    s_.face_group[d] = s_.face_group[f];
    s_.face_cut[d] = s_.face_cut[f];
    t_.key_at[d] = t_.key_at[f];
    touch(to);
    t_.faces.find(t_.key_at[d])->pos = to;
  }

  // Index of group g's range, inserting an empty one in order when absent.
  std::size_t range_of(std::uint16_t g) {
    auto it = std::lower_bound(s_.groups.begin(), s_.groups.end(), g,
                               [](const GroupRange& r, std::uint16_t id) { return r.group < id; });
    if (it == s_.groups.end() || it->group != g) {
      const std::int32_t offset = it == s_.groups.end() ? s_.num_faces() : it->offset;
      it = s_.groups.insert(it, GroupRange{g, offset, 0});
    }
    return static_cast<std::size_t>(it - s_.groups.begin());
  }

  // Removes face p (its entry's pos must already be cleared by the caller): the last face of its
  // group fills the slot, then each later group shifts down by one through its last face.
  void remove(std::int32_t p) {
    std::size_t r = range_of(s_.face_group[static_cast<std::size_t>(p)]);
    GroupRange& own = s_.groups[r];
    std::int32_t hole = own.offset + own.count - 1;
    if (p != hole) move(hole, p);
    --own.count;
    for (++r; r < s_.groups.size(); ++r) {
      GroupRange& g = s_.groups[r];
      const std::int32_t last = g.offset + g.count - 1;
      if (g.count > 0) {
        move(last, hole);
        hole = last;
      }
      --g.offset;
    }
    s_.faces.pop_back();
    s_.face_tet.pop_back();
    s_.face_group.pop_back();
    s_.face_cut.pop_back();
    t_.key_at.pop_back();
  }

  // Appends a face to group g's range: each later group shifts up by one through its first face.
  void insert(const WideKey& key, Entry& e, const Tri& tri, std::int32_t tet, std::uint16_t g,
              std::uint8_t cut) {
    const std::size_t r = range_of(g);
    std::int32_t hole = s_.num_faces();
    s_.faces.emplace_back();
    s_.face_tet.push_back(0);
    s_.face_group.push_back(0);
    s_.face_cut.push_back(0);
    t_.key_at.emplace_back();
    for (std::size_t q = s_.groups.size() - 1; q > r; --q) {
      GroupRange& h = s_.groups[q];
      if (h.count > 0) {
        move(h.offset, hole);
        hole = h.offset;
      }
      ++h.offset;
    }
    GroupRange& own = s_.groups[r];
    const auto d = static_cast<std::size_t>(hole);
    s_.faces[d] = tri;
    s_.face_tet[d] = tet;
    s_.face_group[d] = g;
    s_.face_cut[d] = cut;
    t_.key_at[d] = key;
    touch(hole);
    e.pos = hole;
    ++own.count;
  }

 private:
  SurfaceMesh& s_;
  FaceTable& t_;
  std::vector<std::int32_t>* changed_;
};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("update_surface: " + what);
}

}  // namespace

FaceTable build_face_table(const TetMesh& mesh, const SurfaceMesh& s) {
  FaceTable t;
  // Headroom, so that the tets a cut appends rarely reallocate (and page-fault) the whole mirror.
  t.tets.reserve(mesh.tets.size() + mesh.tets.size() / 4 + 1024);
  t.tets = mesh.tets;
  t.faces.reserve(mesh.tets.size() * 5 / 2);
  for (std::int32_t i = 0; i < mesh.num_tets(); ++i)
    for (int l = 0; l < 4; ++l) {
      Entry& e = t.faces.get_or_insert(face_key(mesh.tets[static_cast<std::size_t>(i)], l));
      ++e.count;
      e.code_sum += std::int64_t{i} * 4 + l;
    }
  t.key_at.resize(s.faces.size());
  for (std::size_t i = 0; i < s.faces.size(); ++i) {
    t.key_at[i] = key_of(s.faces[i]);
    Entry* e = t.faces.find(t.key_at[i]);
    require(e != nullptr && e->count == 1 && e->pos < 0,
            "face " + std::to_string(i) + " is not a boundary face of the mesh");
    e->pos = static_cast<std::int32_t>(i);
  }
  return t;
}

void update_surface(SurfaceMesh& s, FaceTable& table, const TetMesh& after, const TopologyDelta& d,
                    const OriginalSurface* original, std::vector<std::int32_t>* changed_slots) {
  const auto removed = d.removed_tets.size();
  const auto added = d.added_tets.size();
  require(s.topology_version == d.version_before,
          "surface is at topology version " + std::to_string(s.topology_version) +
              ", the delta starts at " + std::to_string(d.version_before));
  require(d.slot_of_added.size() == added, "delta not applied (slot_of_added missing)");
  require(table.tets.size() + added - removed == after.tets.size(),
          "tet counts of table, delta and mesh disagree");
  require(s.face_cut.size() == s.faces.size(), "face_cut and faces differ in size");
  if (changed_slots != nullptr) changed_slots->clear();

  std::vector<WideKey> touched;
  touched.reserve(4 * (removed + added + d.moved_tets.size()));
  std::vector<Tet>& tets = table.tets;

  // The table is large and cold (the solver ran since the last update): each step below first
  // computes its keys and prefetches their slots, so the cache misses overlap.

  // 1. Removed tets (old ids, nodes from the mirror): one use less of each face.
  for (std::int32_t r : d.removed_tets)
    for (int l = 0; l < 4; ++l) {
      touched.push_back(face_key(tets[static_cast<std::size_t>(r)], l));
      table.faces.prefetch(touched.back());
    }
  for (std::size_t i = 0; i < 4 * removed; ++i) {
    const std::int32_t r = d.removed_tets[i / 4];
    Entry* found = table.faces.find(touched[i]);
    require(found != nullptr, "removed tet " + std::to_string(r) + " has a face the table lacks");
    --found->count;
    found->code_sum -= std::int64_t{r} * 4 + static_cast<std::int64_t>(i % 4);
  }

  // 2. Mirror apply(): added tets into reused slots or appended, then the moves.
  for (std::size_t k = 0; k < added; ++k) {
    const auto slot = static_cast<std::size_t>(d.slot_of_added[k]);
    if (slot < tets.size())
      tets[slot] = d.added_tets[k];
    else
      tets.push_back(d.added_tets[k]);
  }
  for (const auto& [from, to] : d.moved_tets) {
    const Tet t = tets[static_cast<std::size_t>(from)];
    for (int l = 0; l < 4; ++l) {
      const WideKey k = face_key(t, l);
      table.faces.find(k)->code_sum += (std::int64_t{to} - from) * 4;
      touched.push_back(k);
    }
    tets[static_cast<std::size_t>(to)] = t;
  }
  tets.resize(after.tets.size());

  // 3. Added tets (final ids): one use more of each face.
  const std::size_t first_added = touched.size();
  for (std::size_t k = 0; k < added; ++k)
    for (int l = 0; l < 4; ++l) {
      touched.push_back(face_key(d.added_tets[k], l));
      table.faces.prefetch(touched.back());
    }
  for (std::size_t i = 0; i < 4 * added; ++i) {
    Entry& e = table.faces.get_or_insert(touched[first_added + i]);
    ++e.count;
    e.code_sum += std::int64_t{d.slot_of_added[i / 4]} * 4 + static_cast<std::int64_t>(i % 4);
  }

  // 4. Reconcile each touched face with the surface arrays, in the order touched (deterministic).
  // A key touched twice is reconciled twice, harmlessly: the second pass finds the face already
  // in place (count 1), already out (count 2), or erased (count 0).
  for (const WideKey& key : touched) table.faces.prefetch(key);
  FaceArrays arrays(s, table, changed_slots);
  for (const WideKey& key : touched) {
    Entry* found = table.faces.find(key);
    if (found == nullptr) continue;  // erased by an earlier pass over the same key
    Entry& e = *found;
    if (e.count == 1) {
      const auto tet = static_cast<std::int32_t>(e.code_sum >> 2);
      const auto l = static_cast<int>(e.code_sum & 3);
      require(tet >= 0 && tet < after.num_tets(), "face owner out of range (delta mismatch)");
      Tri tri{};
      outward_face(tets[static_cast<std::size_t>(tet)], l, tri[0], tri[1], tri[2]);
      const std::uint16_t g = after.group[static_cast<std::size_t>(tet)];
      if (e.pos >= 0 && s.face_group[static_cast<std::size_t>(e.pos)] == g) {
        // Same nodes and group: face_cut (a function of both) stays.
        s.faces[static_cast<std::size_t>(e.pos)] = tri;
        s.face_tet[static_cast<std::size_t>(e.pos)] = tet;
        arrays.touch(e.pos);
        continue;
      }
      if (e.pos >= 0) {
        const std::int32_t p = e.pos;
        e.pos = -1;
        arrays.remove(p);
      }
      const std::uint8_t cut =
          original != nullptr ? classify_face(tri, g, after, *original) : std::uint8_t{0};
      arrays.insert(key, e, tri, tet, g, cut);
    } else {
      if (e.pos >= 0) {
        const std::int32_t p = e.pos;
        e.pos = -1;
        arrays.remove(p);
      }
      if (e.count == 0) table.faces.erase(key);
    }
  }
  std::erase_if(s.groups, [](const GroupRange& r) { return r.count == 0; });
  s.topology_version = after.topology_version;
  if (changed_slots != nullptr) {
    std::sort(changed_slots->begin(), changed_slots->end());
    changed_slots->erase(std::unique(changed_slots->begin(), changed_slots->end()),
                         changed_slots->end());
    std::erase_if(*changed_slots, [&](std::int32_t p) { return p >= s.num_faces(); });
  }
}

}  // namespace serosa::surface
