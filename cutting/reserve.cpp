#include "cutting/reserve.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace serosa::cutting {
namespace {

template <class T>
void reserve_one(std::vector<T>& v, double spare) {
  const auto size = static_cast<double>(v.size());
  if (static_cast<double>(v.capacity()) >= size * (1.0 + 0.5 * spare)) return;
  v.reserve(static_cast<std::size_t>(std::ceil(size * (1.0 + spare))));
}

}  // namespace

void reserve_for_cuts(TetMesh& mesh, double spare) {
  if (!std::isfinite(spare) || spare < 0.0) {
    std::string what = "reserve_for_cuts: spare must be finite and >= 0, got ";
    what.append(std::to_string(spare));
    throw std::invalid_argument(what);
  }
  reserve_one(mesh.rest, spare);
  reserve_one(mesh.x, spare);
  reserve_one(mesh.v, spare);
  reserve_one(mesh.mass, spare);
  reserve_one(mesh.fixed, spare);
  reserve_one(mesh.tets, spare);
  reserve_one(mesh.group, spare);
}

}  // namespace serosa::cutting
