// Area-weighted vertex normals of a triangle soup (no GL).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace serosa::render {

/// Area-weighted vertex normals: each vertex gets the normalised sum of the (unnormalised)
/// cross products (b - a) x (c - a) of the triangles around it, i.e. twice their area times their
/// unit normal, so large triangles weigh more.
/// @param pos  (n x 3) vertex positions, m
/// @param tri  (t x 3) vertex ids, counter-clockwise seen from the side the normal points to
/// @return     (n x 3) unit normals; (0, 0, 0) for vertices no triangle uses or whose triangles
///             are all degenerate
/// @throws std::invalid_argument when a size is not a multiple of 3 or an id is out of range
[[nodiscard]] std::vector<float> compute_vertex_normals(std::span<const float> pos,
                                                        std::span<const std::uint32_t> tri);

}  // namespace serosa::render
