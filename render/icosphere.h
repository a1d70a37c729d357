// Icospheres: the standard sphere meshes of the render tests and benchmarks (Phong tessellation
// accuracy, frame time against triangle count) and `serosa bench tessellation`.
#pragma once

#include "render/phong_tessellation.h"

namespace serosa::render {

/// The regular icosahedron inscribed in the sphere of `radius` m at the origin (12 vertices,
/// 20 outward, counter-clockwise faces).
[[nodiscard]] TriMesh icosahedron(float radius = 1.0f);

/// The icosahedron with every triangle split into 4, `levels` (>= 0) times, new vertices pushed
/// onto the sphere of `radius` m (20 × 4^levels triangles, shared vertices).
[[nodiscard]] TriMesh icosphere(int levels, float radius = 1.0f);

}  // namespace serosa::render
