// What `serosa headless` writes besides its report, as an engineer feeds it to other tools: the
// final mesh in the format its name says (VTU that parses as ParaView reads it, with the same
// nodes as the Gmsh export of the same run), a per-step CSV, a VTU series with its .pvd; every
// output's place checked before the run, nothing created silently; --seconds for a dt sweep.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app_test_util.h"
#include "engine/io/mesh_io.h"
#include "engine/shell_command.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

// Each DataArray's numbers by its Name, and the Piece's counts, as a VTK XML reader takes them.
struct Vtu {
  std::int64_t points = -1, cells = -1;
  std::map<std::string, std::vector<double>> arrays;
};

// The number after `key="` in `text` (-1 when absent).
std::int64_t attribute(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key + "=\"");
  return at == std::string::npos ? -1 : std::stoll(text.substr(at + key.size() + 2));
}

// (No std::regex: under ASan GCC 12 warns inside it, a false positive, and warnings are errors.)
Vtu parse_vtu(const std::string& text) {
  Vtu v;
  v.points = attribute(text, "NumberOfPoints");
  v.cells = attribute(text, "NumberOfCells");
  for (std::size_t at = text.find("<DataArray"); at != std::string::npos;
       at = text.find("<DataArray", at + 1)) {
    const std::size_t open_end = text.find('>', at);
    const std::string open = text.substr(at, open_end - at);
    const std::size_t name = open.find("Name=\"");
    if (name == std::string::npos || open_end == std::string::npos) continue;
    const std::string key = open.substr(name + 6, open.find('"', name + 6) - name - 6);
    const std::size_t close = text.find("</DataArray>", open_end);
    std::istringstream in(text.substr(open_end + 1, close - open_end - 1));
    std::vector<double>& values = v.arrays[key];
    for (double x; in >> x;) values.push_back(x);
  }
  return v;
}

std::string beam_run(const fs::path& dir, const std::string& extra) {
  return "headless " + shell_quote(source("config/beam.toml").string()) + " --steps 12 --report " +
         shell_quote((dir / "r.json").string()) + " " + extra;
}

TEST(RunOutputs, TheFinalMeshIsWrittenInTheFormatItsNameSays) {
  const fs::path dir = out_dir("outputs_final");
  const CliResult vtu =
      run_serosa(beam_run(dir, "--export-final " + shell_quote((dir / "f.vtu").string())));
  ASSERT_EQ(vtu.code, 0) << vtu.out;
  const CliResult msh =
      run_serosa(beam_run(dir, "--export-final " + shell_quote((dir / "f.msh").string())));
  ASSERT_EQ(msh.code, 0) << msh.out;
  const std::string text = file_text(dir / "f.vtu");
  ASSERT_EQ(text.rfind("<?xml", 0), 0u) << "not XML";
  EXPECT_NE(text.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
  const Vtu v = parse_vtu(text);
  const TetMesh m = read_mesh(dir / "f.msh");  // written at the final, current positions
  ASSERT_EQ(v.points, m.num_nodes());
  ASSERT_EQ(v.cells, m.num_tets());
  ASSERT_EQ(v.arrays.at("Points").size(), 3u * static_cast<std::size_t>(m.num_nodes()));
  ASSERT_EQ(v.arrays.at("connectivity").size(), 4u * static_cast<std::size_t>(m.num_tets()));
  ASSERT_EQ(v.arrays.at("offsets").size(), static_cast<std::size_t>(m.num_tets()));
  for (double t : v.arrays.at("types")) EXPECT_EQ(t, 10.0);  // VTK_TETRA
  for (std::int32_t i = 0; i < m.num_nodes(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(v.arrays.at("Points")[3 * static_cast<std::size_t>(i) + k],
                  m.rest[static_cast<std::size_t>(i)][k], 1e-9)
          << "node " << i;
  for (std::int32_t t = 0; t < m.num_tets(); ++t)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(v.arrays.at("connectivity")[4 * static_cast<std::size_t>(t) + c],
                m.tets[static_cast<std::size_t>(t)][c]);

  const CliResult obj =
      run_serosa(beam_run(dir, "--export-final " + shell_quote((dir / "f.obj").string())));
  ASSERT_EQ(obj.code, 0) << obj.out;
  std::istringstream lines(file_text(dir / "f.obj"));
  int vertices = 0, faces = 0;
  for (std::string line; std::getline(lines, line);) {
    vertices += line.rfind("v ", 0) == 0;
    faces += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(vertices, m.num_nodes());
  EXPECT_GT(faces, 0);
}

TEST(RunOutputs, AnOutputThatCannotBeWrittenIsRefusedBeforeTheRun) {
  const fs::path dir = out_dir("outputs_refused");
  const fs::path nowhere = dir / "absent" / "deeper";
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      {"--export-final " + shell_quote((dir / "f.stl").string()), "'.stl' is not a mesh format"},
      {"--export-final " + shell_quote((nowhere / "f.msh").string()), "does not exist"},
      {"--series " + shell_quote((nowhere / "s.csv").string()), "--series"},
      {"--record " + shell_quote((nowhere / "r.lapr").string()), "--record"},
      {"--vtu-series " + shell_quote((nowhere / "v").string()), "--vtu-series"},
      {"--frames " + shell_quote((nowhere / "p").string()), "--frames"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    fs::remove(dir / "r.json");
    const CliResult r = run_serosa(beam_run(dir, c.args));
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "r.json")) << "the run went ahead";
  }
  const CliResult report =
      run_serosa("headless " + shell_quote(source("config/beam.toml").string()) +
                 " --steps 2 --report " + shell_quote((nowhere / "r.json").string()));
  EXPECT_EQ(report.code, 1) << report.out;
  EXPECT_NE(report.out.find("--report"), std::string::npos) << report.out;
  EXPECT_FALSE(fs::exists(dir / "absent")) << "a folder was created silently";
}

TEST(RunOutputs, TheSeriesHaveARowAStepAndAFileEveryNSteps) {
  const fs::path dir = out_dir("outputs_series");
  const CliResult r = run_serosa(
      beam_run(dir, "--series " + shell_quote((dir / "s.csv").string()) + " --vtu-series " +
                        shell_quote((dir / "vtu").string()) + " --vtu-every 5"));
  ASSERT_EQ(r.code, 0) << r.out;
  std::istringstream csv(file_text(dir / "s.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("time_s,step,step_ms,fem_ms,cg_iterations,residual,energy_j", 0), 0u)
      << header;
  int rows = 0;
  double last_t = 0.0;
  for (std::string line; std::getline(csv, line); ++rows) {
    const double t = std::stod(line.substr(0, line.find(',')));
    EXPECT_GT(t, last_t) << line;
    last_t = t;
  }
  EXPECT_EQ(rows, 12);
  // Steps 0, 5 and 10.
  for (const char* f : {"step_000000.vtu", "step_000005.vtu", "step_000010.vtu"})
    EXPECT_TRUE(fs::is_regular_file(dir / "vtu" / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "vtu/step_000012.vtu"));
  const std::string pvd = file_text(dir / "vtu/series.pvd");
  EXPECT_NE(pvd.find("<VTKFile type=\"Collection\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("file=\"step_000010.vtu\""), std::string::npos) << pvd;
  nlohmann::json report;
  std::ifstream(dir / "r.json") >> report;
  EXPECT_EQ(report["vtu_series"]["files"], 3);
}

TEST(RunOutputs, SecondsKeepTheSimulatedTimeAcrossADtSweep) {
  const fs::path dir = out_dir("outputs_seconds");
  for (const char* dt : {"0.005", "0.0025"}) {
    const CliResult r = run_serosa("headless " + shell_quote(source("config/beam.toml").string()) +
                                   " --seconds 0.05 --set scene.dt=" + dt + " --report " +
                                   shell_quote((dir / "r.json").string()));
    ASSERT_EQ(r.code, 0) << r.out;
    nlohmann::json report;
    std::ifstream(dir / "r.json") >> report;
    EXPECT_NEAR(report["simulated_time_s"].get<double>(), 0.05, 1e-12) << dt;
  }
  const CliResult both = run_serosa("headless " + shell_quote(source("config/beam.toml").string()) +
                                    " --seconds 0.05 --steps 3");
  EXPECT_NE(both.code, 0) << both.out;
}

}  // namespace
}  // namespace serosa::app
