// Phong tessellation on the CPU (Boubekeur & Alexa 2008): the same formula as the visual view's
// tessellation evaluation shader (render/shaders.cpp), for measuring how far the drawn surface is
// from a reference (benchmarks) and for tests. No GL.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace serosa::render {

/// The Phong-tessellated point of a triangle with corners p0..p2 (m) and corner normals n0..n2
/// (normalised here; a zero normal leaves that corner's projection flat) at barycentric
/// coordinates b (b0 + b1 + b2 = 1), with shape factor alpha (0 = flat, 0.75 = the paper's):
/// q = (1 - alpha) p + alpha sum_i b_i (p - ((p - p_i) . n_i) n_i), p = sum_i b_i p_i.
[[nodiscard]] std::array<float, 3> phong_point(const std::array<std::array<float, 3>, 3>& p,
                                               const std::array<std::array<float, 3>, 3>& n,
                                               const std::array<float, 3>& b, float alpha);

/// A triangle mesh: (n x 3) positions, m, and (t x 3) vertex ids.
struct TriMesh {
  std::vector<float> pos;
  std::vector<std::uint32_t> tri;
};

/// Every triangle of (pos, nrm, tri) split into level^2 triangles on the uniform barycentric grid
/// of step 1/level, grid points moved by phong_point. Grid points on shared edges are computed
/// from that edge's two corners only, so they coincide between neighbours; they are not merged
/// (each input triangle gets its own (level+1)(level+2)/2 vertices). level >= 1; level 1 returns
/// the input triangles (with their own vertices).
/// @throws std::invalid_argument on sizes that are not multiples of 3, an id out of range, or
///         level < 1
[[nodiscard]] TriMesh phong_tessellate(std::span<const float> pos, std::span<const float> nrm,
                                       std::span<const std::uint32_t> tri, int level, float alpha);

/// Distance of a piecewise-flat mesh from the sphere of `radius` m centred at the origin,
/// sampled at every vertex, edge midpoint and centroid of its triangles: the largest and the
/// mean |‖q‖ - radius|, m.
struct SphereDistance {
  double max_m = 0.0;
  double mean_m = 0.0;
};
[[nodiscard]] SphereDistance distance_to_sphere(const TriMesh& mesh, double radius);

}  // namespace serosa::render
