// `serosa check` and `serosa surface` end to end: run the built executable on small meshes written
// with write_gmsh22 into a temporary folder, and check exit codes, JSON and the OBJ it writes.
// Needs the `serosa` executable built (::serosa::test_paths::binary_dir()/app/serosa).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/boundary.h"
#include "engine/box_meshes.h"
#include "engine/io/mesh_io.h"
#include "support/test_paths.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

struct CliResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CliCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(m_exe)) << m_exe << " is missing: build the serosa target first";
    std::random_device rd;
    m_dir = fs::temp_directory_path() /
            ("serosa_cli_check_" + std::to_string(rd()) + "_" + std::to_string(rd()));
    fs::create_directories(m_dir);
  }
  void TearDown() override {
    std::error_code ec;
    if (!m_dir.empty()) fs::remove_all(m_dir, ec);
  }

  // Runs `serosa ARGS`, capturing stdout, stderr and the exit code.
  CliResult serosa(const std::string& args) const {
    const fs::path err = m_dir / "stderr.txt";
    const std::string cmd = quoted(m_exe.string()) + " " + args + " 2>" + quoted(err.string());
    CliResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (pipe == nullptr) return r;
    std::array<char, 4096> buf{};
    std::size_t got = 0;
    while ((got = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), got);
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = slurp(err);
    return r;
  }

  fs::path write(const std::string& name, const TetMesh& m,
                 const std::map<int, std::string>& names = {}) const {
    const fs::path p = m_dir / name;
    write_gmsh22(p, m, false, names);
    return p;
  }

  fs::path m_exe = fs::path(::serosa::test_paths::binary_dir()) / "app" / "serosa";
  fs::path m_dir;
};

// A 2 x 2 x 2 grid of Kuhn cubes over a 0.04 x 0.02 x 0.01 m box, groups 1 and 2.
TetMesh grid() {
  return test_meshes::kuhn_lattice({0.0, 0.015, 0.04}, {0.0, 0.012, 0.02}, {0.0, 0.004, 0.01}, 2);
}

TEST_F(CliCheck, ValidMeshExitsZeroWithRightJsonCounts) {
  const TetMesh m = grid();
  const fs::path p = write("grid.msh", m, {{1, "left"}, {2, "right"}});
  const CliResult r = serosa("check --json " + quoted(p.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("nodes").get<int>(), 27);
  EXPECT_EQ(j.at("tets").get<int>(), 48);
  EXPECT_EQ(j.at("boundary_faces").get<int>(), 48);
  EXPECT_EQ(j.at("interior_faces").get<int>(), (4 * 48 - 48) / 2);
  EXPECT_EQ(j.at("overshared_faces").get<int>(), 0);
  EXPECT_EQ(j.at("inverted_tets").get<int>(), 0);
  EXPECT_EQ(j.at("flat_tets").get<int>(), 0);
  EXPECT_TRUE(j.at("valid").get<bool>());
  EXPECT_NEAR(j.at("volume_m3").get<double>(), 0.04 * 0.02 * 0.01, 1e-15);
  const auto& groups = j.at("groups");
  ASSERT_EQ(groups.size(), 2U);
  EXPECT_EQ(groups[0].at("id").get<int>(), 1);
  EXPECT_EQ(groups[0].at("tets").get<int>(), 24);
  EXPECT_NEAR(groups[0].at("volume_m3").get<double>(), 0.015 * 0.02 * 0.01, 1e-15);
  EXPECT_EQ(groups[1].at("name").get<std::string>(), "right");
  EXPECT_GT(j.at("min_quality").get<double>(), 0.0);
  EXPECT_LE(j.at("min_quality").get<double>(), j.at("median_quality").get<double>());
}

TEST_F(CliCheck, ValidMeshTextNamesCounts) {
  const fs::path p = write("cube.msh", fixtures::cube_mesh(fixtures::five_tets()));
  const CliResult r = serosa("check " + quoted(p.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("tets        5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("12 boundary"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("valid"), std::string::npos) << r.out;
}

TEST_F(CliCheck, DuplicatedTetExitsOneNamingTheFile) {
  TetMesh m = grid();
  m.add_tet(m.tets[7], m.group[7]);
  const fs::path p = write("dup.msh", m);
  for (const std::string flags : {"", "--json "}) {
    const CliResult r = serosa("check " + flags + quoted(p.string()));
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
  }
  // The duplicate is named by its element id (Gmsh numbers from 1) and its line in the file: the
  // last element line, before $EndElements.
  std::istringstream lines(slurp(p));
  int line_no = 0, last_element = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_no;
    if (line == "$EndElements") break;
    last_element = line_no;
  }
  const CliResult r = serosa("check " + quoted(p.string()));
  EXPECT_NE(r.err.find("(first tet: 48, element 49 at line " + std::to_string(last_element) +
                       " of " + p.string() + ")"),
            std::string::npos)
      << r.err;
}

TEST_F(CliCheck, MissingFileExitsOneNamingTheFile) {
  const fs::path p = m_dir / "no_such_mesh.msh";
  for (const std::string cmd : {"check ", "check --json ", "surface --out x.obj "}) {
    const CliResult r = serosa(cmd + quoted(p.string()));
    EXPECT_EQ(r.exit_code, 1) << cmd << r.out << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
  }
}

// A mesh that does not load is, with --json, a JSON error object on stdout as well: a script that
// reads stdout gets what and where, never nothing.
TEST_F(CliCheck, JsonSaysWhyAMeshDidNotLoad) {
  TetMesh m = grid();
  std::swap(m.tets[3][0], m.tets[3][1]);
  const fs::path inverted = write("inverted_json.msh", m);
  const CliResult r = serosa("check --json " + quoted(inverted.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j.at("valid").get<bool>());
  EXPECT_EQ(j.at("error").at("file").get<std::string>(), inverted.string());
  EXPECT_GT(j.at("error").at("line").get<int>(), 0);
  EXPECT_NE(j.at("error").at("message").get<std::string>().find("inverted tet"), std::string::npos);
  // The way out is the command's own option, not a C++ name.
  EXPECT_NE(j.at("error").at("expected").get<std::string>().find("--repair-inverted"),
            std::string::npos)
      << j.dump(1);
  const CliResult missing = serosa("check --json " + quoted((m_dir / "none.msh").string()));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(nlohmann::json::parse(missing.out).at("error").at("message"), "no such file");
}

TEST_F(CliCheck, InvertedTetIsRejectedUnlessRepaired) {
  TetMesh m = grid();
  std::swap(m.tets[3][0], m.tets[3][1]);
  const fs::path p = write("inverted.msh", m);
  CliResult r = serosa("check " + quoted(p.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
  r = serosa("check --json --repair-inverted " + quoted(p.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("repaired_inverted").get<int>(), 1);
  EXPECT_EQ(j.at("inverted_tets").get<int>(), 0);
  EXPECT_EQ(j.at("overshared_faces").get<int>(), 0);
}

// The faces of an OBJ (1-based ids in the file, returned 0-based), its vertices and group names.
struct Obj {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  std::vector<std::string> groups;
};

Obj read_obj(const fs::path& p) {
  Obj obj;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Vec3 x;
      ls >> x.x() >> x.y() >> x.z();
      obj.v.push_back(x);
    } else if (tag == "f") {
      std::array<int, 3> f{};
      std::vector<std::string> words;
      for (std::string w; ls >> w;) words.push_back(w);
      EXPECT_EQ(words.size(), 3U) << line;
      for (std::size_t k = 0; k < 3 && k < words.size(); ++k) {
        f[k] = std::stoi(words[k].substr(0, words[k].find('/'))) - 1;  // "i", "i/t" or "i//n"
      }
      obj.f.push_back(f);
    } else if (tag == "g") {
      std::string name;
      ls >> name;
      obj.groups.push_back(name);
    }
  }
  return obj;
}

TEST_F(CliCheck, SurfaceWritesOutwardBoundaryPerGroup) {
  const TetMesh m = grid();
  const fs::path p = write("grid.msh", m, {{1, "left"}, {2, "right"}});
  const fs::path out = m_dir / "grid.obj";
  const CliResult r = serosa("surface " + quoted(p.string()) + " --out " + quoted(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("48 boundary faces"), std::string::npos) << r.out;
  const Obj obj = read_obj(out);
  EXPECT_EQ(obj.f.size(), face_census(m).boundary.size());
  EXPECT_EQ(obj.v.size(), m.rest.size());
  // Outward faces enclose the mesh volume with a positive sign.
  double volume = 0.0;
  for (const auto& f : obj.f) {
    for (const int id : f) ASSERT_TRUE(id >= 0 && id < static_cast<int>(obj.v.size()));
    volume +=
        signed_volume(Vec3::Zero(), obj.v[static_cast<std::size_t>(f[0])],
                      obj.v[static_cast<std::size_t>(f[1])], obj.v[static_cast<std::size_t>(f[2])]);
  }
  EXPECT_NEAR(volume, 0.04 * 0.02 * 0.01, 1e-15);
  EXPECT_GT(volume, 0.0);
  ASSERT_EQ(obj.groups.size(), 2U);
  EXPECT_EQ(obj.groups[0], "left");
  EXPECT_EQ(obj.groups[1], "right");
}

TEST_F(CliCheck, SurfaceRefusesAnInvalidMesh) {
  TetMesh m = grid();
  m.add_tet(m.tets[7], m.group[7]);
  const fs::path p = write("dup.msh", m);
  const fs::path out = m_dir / "dup.obj";
  const CliResult r = serosa("surface " + quoted(p.string()) + " --out " + quoted(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find(p.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace serosa
