#include "app/run_series.h"

#include <cstdio>
#include <stdexcept>

#include "engine/io/mesh_io.h"

namespace serosa::app {

StepSeries::StepSeries(const std::filesystem::path& file, const Scene& scene)
    : m_file(file), m_out(file), m_tools(scene.tools.size()) {
  if (!m_out) throw std::runtime_error("cannot write --series " + file.string());
  m_out << "time_s,step,step_ms,fem_ms,cg_iterations,residual,energy_j";
  for (const Tool& t : scene.tools) m_out << ",force_n." << t.name;
  m_out << '\n';
}

void StepSeries::add(const SimState& state, double step_ms, double fem_ms,
                     const fem::StepStatus& status) {
  char row[160];
  std::snprintf(row, sizeof row, "%.6f,%llu,%.4f,%.4f,%d,%.6g,%.9g", state.time_s,
                static_cast<unsigned long long>(state.step), step_ms, fem_ms, status.iterations,
                status.residual, status.energy_j);
  m_out << row;
  const auto& force = state.events.tool_force_n;
  for (std::size_t i = 0; i < m_tools; ++i) {
    std::snprintf(row, sizeof row, ",%.6g", i < force.size() ? force[i].norm() : 0.0);
    m_out << row;
  }
  m_out << '\n';
}

void StepSeries::close() {
  m_out.flush();
  if (!m_out) throw std::runtime_error("cannot write --series " + m_file.string());
}

VtuSeries::VtuSeries(std::filesystem::path dir, std::int64_t every)
    : m_dir(std::move(dir)), m_every(every) {
  std::filesystem::create_directories(m_dir);  // checked before the run: its parent exists
}

void VtuSeries::add(const SimState& state) {
  if (static_cast<std::int64_t>(state.step) % m_every != 0) return;
  char name[32];
  std::snprintf(name, sizeof name, "step_%06llu.vtu", static_cast<unsigned long long>(state.step));
  write_vtu(m_dir / name, state.mesh);
  m_written.emplace_back(state.time_s, name);
}

std::size_t VtuSeries::close() {
  std::ofstream out(m_dir / "series.pvd");
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& [t, file] : m_written) {
    char line[128];
    std::snprintf(line, sizeof line, "    <DataSet timestep=\"%.6f\" part=\"0\" file=\"%s\"/>\n", t,
                  file.c_str());
    out << line;
  }
  out << "  </Collection>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("cannot write " + (m_dir / "series.pvd").string());
  return m_written.size();
}

}  // namespace serosa::app
