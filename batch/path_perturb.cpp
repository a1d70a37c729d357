#include "batch/path_perturb.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>

#include "engine/instrument_hold.h"

namespace serosa::batch {
namespace {

struct Wave {
  double amplitude, frequency_hz, phase;
};

// Three sines whose amplitudes add up to `amplitude`: the offset never exceeds it.
std::array<Wave, 3> waves(std::mt19937_64& rng, double amplitude) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::array<Wave, 3> w{};
  double sum = 0.0;
  for (Wave& x : w) {
    x.amplitude = 0.2 + unit(rng);
    x.frequency_hz = 0.3 + 1.7 * unit(rng);
    x.phase = 2.0 * std::numbers::pi * unit(rng);
    sum += x.amplitude;
  }
  for (Wave& x : w) x.amplitude *= amplitude / sum;
  return w;
}

}  // namespace

ToolPath perturb_path(const ToolPath& path, std::uint64_t seed, double amplitude_m) {
  ToolPath out = path;
  out.file = path.file + " (perturbed, seed " + std::to_string(seed) + ")";
  std::mt19937_64 rng(seed);
  for (auto& rows : out.samples) {
    std::array<std::array<Wave, 3>, 3> axis{};
    for (auto& a : axis) a = waves(rng, amplitude_m);
    for (ToolState& s : rows)
      for (std::size_t k = 0; k < 3; ++k)
        for (const Wave& w : axis[k])
          s.tip_m[k] +=
              w.amplitude * std::sin(2.0 * std::numbers::pi * w.frequency_hz * s.time_s + w.phase);
  }
  return out;
}

namespace {

// The hand column's word for a row (engine/instrument_hold.h).
const char* hand_word(const ToolState& s) {
  if (in_port(s)) return "port";
  const std::optional<Hand> h = holder(s);
  return !h ? "" : *h == Hand::kLeft ? "left" : "right";
}

}  // namespace

void write_tool_path(const ToolPath& path, const std::filesystem::path& file) {
  std::ofstream out(file);
  out << "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n";
  char line[512];
  for (std::size_t i = 0; i < path.tools.size(); ++i)
    for (const ToolState& s : path.samples[i]) {
      std::snprintf(line, sizeof line,
                    "%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%u,%s\n", s.time_s,
                    path.tools[i].c_str(), s.tip_m[0], s.tip_m[1], s.tip_m[2], s.quat_wxyz[0],
                    s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3], s.jaw_rad,
                    static_cast<unsigned>(s.buttons & kDeviceButtons), hand_word(s));
      out << line;
    }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace serosa::batch
