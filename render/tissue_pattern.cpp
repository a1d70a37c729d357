// The tissue's pattern (see tissue_pattern.h): periodic gradient noise for the vessels, mottling
// and relief, periodic cell noise for the fat lobules, each evaluated on the unit cube and scaled
// so that a whole number of lattice cells fits one period.
#include "render/tissue_pattern.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace serosa::render {
namespace {

using P3 = std::array<double, 3>;

std::uint32_t mix(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352dU;
  h ^= h >> 15;
  h *= 0x846ca68bU;
  h ^= h >> 16;
  return h;
}

// A hash of a lattice point taken modulo `period` (so the noise repeats), and a seed.
std::uint32_t lattice_hash(int x, int y, int z, int period, std::uint32_t seed) {
  const auto wrap = [period](int v) {
    return static_cast<std::uint32_t>(((v % period) + period) % period);
  };
  return mix(wrap(x) + mix(wrap(y) + mix(wrap(z) + mix(seed))));
}

double unit(std::uint32_t h) { return static_cast<double>(h & 0xffffffU) / 16777216.0; }

// One of Perlin's twelve edge gradients.
double gradient_dot(std::uint32_t h, double x, double y, double z) {
  switch (h % 12U) {
    case 0:
      return x + y;
    case 1:
      return -x + y;
    case 2:
      return x - y;
    case 3:
      return -x - y;
    case 4:
      return x + z;
    case 5:
      return -x + z;
    case 6:
      return x - z;
    case 7:
      return -x - z;
    case 8:
      return y + z;
    case 9:
      return -y + z;
    case 10:
      return y - z;
    default:
      return -y - z;
  }
}

// The lattice cell holding p (lattice units): the floor of each coordinate.
std::array<int, 3> lattice_cell(const P3& p) {
  return {static_cast<int>(std::floor(p[0])), static_cast<int>(std::floor(p[1])),
          static_cast<int>(std::floor(p[2]))};
}

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Gradient noise at `p` (lattice units), repeating every `period` cells; about [-1, 1].
double gradient_noise(const P3& p, int period, std::uint32_t seed) {
  const std::array<int, 3> i = lattice_cell(p);
  const P3 f{p[0] - i[0], p[1] - i[1], p[2] - i[2]};
  double corner[2][2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c)
        corner[a][b][c] = gradient_dot(lattice_hash(i[0] + a, i[1] + b, i[2] + c, period, seed),
                                       f[0] - a, f[1] - b, f[2] - c);
  const double u = fade(f[0]), v = fade(f[1]), w = fade(f[2]);
  const auto lerp = [](double x0, double x1, double t) { return x0 + t * (x1 - x0); };
  double yz[2][2];
  for (int b = 0; b < 2; ++b)
    for (int c = 0; c < 2; ++c) yz[b][c] = lerp(corner[0][b][c], corner[1][b][c], u);
  return lerp(lerp(yz[0][0], yz[1][0], v), lerp(yz[0][1], yz[1][1], v), w);
}

// Fractal sum of `octaves` gradient noises on the unit cube, the first with `cells` lattice cells
// per period, each next one twice as fine and half as strong; about [-1, 1].
double fractal(const P3& q, int cells, int octaves, std::uint32_t seed) {
  double sum = 0.0, amp = 1.0, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    const P3 p{q[0] * cells, q[1] * cells, q[2] * cells};
    sum += amp * gradient_noise(p, cells, seed + static_cast<std::uint32_t>(o));
    norm += amp;
    amp *= 0.5;
    cells *= 2;
  }
  return sum / norm;
}

// Cell noise on the unit cube with `cells` cells per period: F2 - F1, the distance (in cell
// units) between a point's nearest and second-nearest feature points: 0 on a cell border.
double cell_border(const P3& q, int cells, std::uint32_t seed) {
  const P3 p{q[0] * cells, q[1] * cells, q[2] * cells};
  const std::array<int, 3> i = lattice_cell(p);
  double f1 = 1e9, f2 = 1e9;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        const std::array<int, 3> cell{i[0] + a, i[1] + b, i[2] + c};
        const std::uint32_t h = lattice_hash(cell[0], cell[1], cell[2], cells, seed);
        const P3 feature{cell[0] + 0.1 + 0.8 * unit(h), cell[1] + 0.1 + 0.8 * unit(mix(h + 1U)),
                         cell[2] + 0.1 + 0.8 * unit(mix(h + 2U))};
        const double d = std::hypot(feature[0] - p[0], feature[1] - p[1], feature[2] - p[2]);
        if (d < f1) {
          f2 = f1;
          f1 = d;
        } else if (d < f2) {
          f2 = d;
        }
      }
  return f2 - f1;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

// Vessels: where a warped noise crosses zero, a thin line; a coarse network of larger vessels
// and a finer, fainter one of their branches. The warp bends the lines so they meander.
double vessels(const P3& q) {
  const P3 w{q[0] + 0.06 * fractal(q, 3, 2, 11U), q[1] + 0.06 * fractal(q, 3, 2, 12U),
             q[2] + 0.06 * fractal(q, 3, 2, 13U)};
  const double coarse = 1.0 - smoothstep(0.0, 0.07, std::abs(fractal(w, 5, 2, 21U)));
  const double fine = 1.0 - smoothstep(0.0, 0.08, std::abs(fractal(w, 9, 2, 31U)));
  return std::max(coarse, 0.55 * fine);
}

}  // namespace

TissuePattern make_tissue_pattern(int size) {
  if (size < 4) throw std::invalid_argument("make_tissue_pattern: size must be at least 4");
  TissuePattern out;
  out.size = size;
  const auto n = static_cast<std::size_t>(size);
  out.rgba.resize(4 * n * n * n);
  for (std::size_t z = 0; z < n; ++z)
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const P3 q{static_cast<double>(x) / size, static_cast<double>(y) / size,
                   static_cast<double>(z) / size};
        std::uint8_t* v = &out.rgba[4 * ((z * n + y) * n + x)];
        v[kVessels] = to_byte(vessels(q));
        v[kLobules] = to_byte(1.0 - smoothstep(0.0, 0.2, cell_border(q, 7, 41U)));
        v[kMottle] = to_byte(0.5 + 0.7 * fractal(q, 4, 3, 51U));
        v[kRelief] = to_byte(0.5 + 0.8 * fractal(q, 8, 3, 61U));
      }
  return out;
}

const TissuePattern& tissue_pattern() {
  static const TissuePattern pattern = make_tissue_pattern(kTissuePatternSize);
  return pattern;
}

}  // namespace serosa::render
