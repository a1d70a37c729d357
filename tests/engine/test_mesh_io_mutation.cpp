// Property: whatever is done to a valid mesh file (truncation, deleted, duplicated or swapped
// lines, a token replaced by something hostile, random bytes), a reader either returns a mesh that
// satisfies every invariant or throws InputError that names the file and a line inside it. Any
// other exception, or a crash under the sanitizers, fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "test_mesh_io_util.h"

namespace serosa {
namespace {

// Small valid files, one per reader (two tets, so that mutations often stay readable).
const char* const kGmsh22 =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"a b\"\n$EndPhysicalNames\n"
    "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n$Elements\n3\n"
    "1 2 2 3 3 2 3 4\n2 4 2 1 1 1 2 3 4\n3 4 2 2 1 2 3 4 5\n$EndElements\n";
const char* const kGmsh41 =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 5 \"organ\"\n$EndPhysicalNames\n"
    "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 5 0\n$EndEntities\n$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n"
    "4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n$Elements\n1 2 1 2\n3 1 4 2\n"
    "1 1 2 3 4\n2 2 3 4 5\n$EndElements\n";
const char* const kVtk3 =
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
    "0 0 0 1 0 0\n0 1 0 0 0 1\n1 1 1\nCELLS 3 14\n4 0 1 2 3\n4 1 2 3 4\n3 0 1 2\n"
    "CELL_TYPES 3\n10\n10\n5\nCELL_DATA 3\nSCALARS group int 1\nLOOKUP_TABLE default\n4\n4\n2\n"
    "POINT_DATA 5\nVECTORS v double\n0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n";
const char* const kVtk51 =
    "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
    "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nMETADATA\nINFORMATION 0\n\nCELLS 3 8\n"
    "OFFSETS vtktypeint64\n0 4 8\nCONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4\nCELL_TYPES 2\n10 10\n"
    "CELL_DATA 2\nFIELD FieldData 1\ngmsh:physical 1 2 int\n3 4\n";
const char* const kNode = "# pts\n5 3 0 1\n1 0 0 0 1\n2 1 0 0 1\n3 0 1 0 1\n4 0 0 1 0\n5 1 1 1 0\n";
const char* const kEle = "2 4 1\n1 1 2 3 4 2\n2 2 3 4 5 2\n";

const std::vector<std::string> kHostile = {"",
                                           "-1",
                                           "0",
                                           "nan",
                                           "inf",
                                           "-inf",
                                           "1e308",
                                           "1e999",
                                           "abc",
                                           "$EndNodes",
                                           "$Nodes",
                                           "4",
                                           "10",
                                           "3.5",
                                           "+",
                                           "-",
                                           "99999999999999999999",
                                           "9223372036854775807",
                                           "-9223372036854775808",
                                           "2147483648",
                                           "65536",
                                           "\"",
                                           "\"x\"",
                                           "#",
                                           "\t",
                                           "\r",
                                           "1e-320",
                                           "LOOKUP_TABLE",
                                           "CELLS",
                                           "OFFSETS",
                                           "METADATA",
                                           "FIELD",
                                           "SCALARS",
                                           "1000000000000"};

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t nl = s.find('\n', start);
    if (nl == std::string::npos) {
      if (start < s.size()) lines.push_back(s.substr(start));
      break;
    }
    lines.push_back(s.substr(start, nl - start));
    start = nl + 1;
  }
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

std::string mutate(const std::string& text, std::mt19937& rng) {
  std::vector<std::string> lines = split_lines(text);
  auto pick = [&](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  const int ops = 1 + static_cast<int>(pick(3));
  for (int op = 0; op < ops && !lines.empty(); ++op) {
    switch (pick(7)) {
      case 0:  // delete a line
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(pick(lines.size())));
        break;
      case 1: {  // duplicate a line
        const std::size_t i = pick(lines.size());
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
        break;
      }
      case 2:  // swap two lines
        std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        break;
      case 3:
      case 4: {  // replace one token of a line with something hostile
        std::string& l = lines[pick(lines.size())];
        std::vector<std::pair<std::size_t, std::size_t>> tokens;
        for (std::size_t i = 0; i < l.size();) {
          while (i < l.size() && l[i] == ' ') ++i;
          const std::size_t b = i;
          while (i < l.size() && l[i] != ' ') ++i;
          if (i > b) tokens.emplace_back(b, i - b);
        }
        if (tokens.empty()) break;
        const auto [b, len] = tokens[pick(tokens.size())];
        l.replace(b, len, kHostile[pick(kHostile.size())]);
        break;
      }
      case 5: {  // truncate at a random byte
        std::string s = join_lines(lines);
        s.resize(pick(s.size() + 1));
        return s;
      }
      default: {  // a random byte somewhere
        std::string& l = lines[pick(lines.size())];
        l.insert(l.begin() + static_cast<std::ptrdiff_t>(pick(l.size() + 1)),
                 static_cast<char>(pick(256)));
        break;
      }
    }
  }
  return join_lines(lines);
}

// Reads; checks the outcome is a valid mesh or a well-formed InputError.
void check_outcome(const std::string& text, MeshFormat format, const std::string& name,
                   const std::string& ele = {}) {
  const auto lines = static_cast<std::int64_t>(std::count(text.begin(), text.end(), '\n') + 1);
  const auto ele_lines = static_cast<std::int64_t>(std::count(ele.begin(), ele.end(), '\n') + 1);
  try {
    MeshReadOptions opt;
    opt.repair_inverted = true;
    const TetMesh m = read_mesh_text(text, format, name, opt, nullptr, ele);
    test::expect_mesh_invariants(m);
  } catch (const InputError& e) {
    const bool is_ele = e.file() != name;
    EXPECT_EQ(e.file(), is_ele ? std::string("m.ele") : name);
    EXPECT_GE(e.line(), 0);
    EXPECT_LE(e.line(), is_ele ? ele_lines : lines) << e.what();
    EXPECT_NE(std::string(e.what()).find(e.file()), std::string::npos);
  }
}

TEST(MeshIoMutation, MutatedFilesGiveValidMeshesOrInputErrors) {
  std::mt19937 rng(424242);
  struct Source {
    const char* text;
    MeshFormat format;
    const char* name;
  };
  for (const Source& s :
       {Source{kGmsh22, MeshFormat::kGmsh, "m.msh"}, Source{kGmsh41, MeshFormat::kGmsh, "m.msh"},
        Source{kVtk3, MeshFormat::kVtk, "m.vtk"}, Source{kVtk51, MeshFormat::kVtk, "m.vtk"}}) {
    SCOPED_TRACE(s.text);
    check_outcome(s.text, s.format, s.name);  // the unmutated file reads
    EXPECT_NO_THROW((void)read_mesh_text(s.text, s.format, s.name));
    for (int i = 0; i < 3000; ++i) {
      const std::string m = mutate(s.text, rng);
      check_outcome(m, s.format, s.name);
      if (::testing::Test::HasFailure()) FAIL() << "mutant:\n" << m;
    }
  }
}

TEST(MeshIoMutation, MutatedTetGenPairsGiveValidMeshesOrInputErrors) {
  std::mt19937 rng(777);
  EXPECT_NO_THROW((void)read_mesh_text(kNode, MeshFormat::kTetGen, "m.node", {}, nullptr, kEle));
  for (int i = 0; i < 3000; ++i) {
    const bool node_side = i % 2 == 0;
    const std::string node = node_side ? mutate(kNode, rng) : kNode;
    const std::string ele = node_side ? std::string(kEle) : mutate(kEle, rng);
    check_outcome(node, MeshFormat::kTetGen, "m.node", ele);
    if (::testing::Test::HasFailure()) FAIL() << "node:\n" << node << "ele:\n" << ele;
  }
}

}  // namespace
}  // namespace serosa
