// The VTU and OBJ writers: the VTU is well-formed XML with the right counts and values (parsed
// back by a minimal XML reader below); the OBJ has one `g` per group and faces = node ids + 1.
#include <gtest/gtest.h>

#include <charconv>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/io/mesh_io.h"
#include "support/test_paths.h"
#include "test_mesh_io_util.h"

namespace serosa {
namespace {

// ------------------------------------------------------------------ a minimal XML reader
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // character data directly inside (for DataArray: the numbers)
  std::vector<XmlElement> children;
};

// Parses the XML subset VTU uses (declaration, elements, attributes in double quotes, text);
// fails the test on anything malformed: unbalanced or mismatched tags, bad attributes, junk.
class MiniXml {
 public:
  explicit MiniXml(std::string s) : m_s(std::move(s)) {}

  XmlElement parse() {
    skip_ws();
    if (m_s.compare(m_pos, 5, "<?xml") == 0) {
      const std::size_t end = m_s.find("?>", m_pos);
      if (end == std::string::npos) throw std::runtime_error("unterminated declaration");
      m_pos = end + 2;
    }
    skip_ws();
    XmlElement root = element();
    skip_ws();
    if (m_pos != m_s.size()) throw std::runtime_error("content after the root element");
    return root;
  }

 private:
  void skip_ws() {
    while (m_pos < m_s.size() && std::isspace(static_cast<unsigned char>(m_s[m_pos])) != 0) ++m_pos;
  }
  std::string name() {
    const std::size_t start = m_pos;
    while (m_pos < m_s.size() && (std::isalnum(static_cast<unsigned char>(m_s[m_pos])) != 0 ||
                                  m_s[m_pos] == '_' || m_s[m_pos] == ':' || m_s[m_pos] == '-')) {
      ++m_pos;
    }
    if (m_pos == start) throw std::runtime_error("expected a name at " + std::to_string(start));
    return m_s.substr(start, m_pos - start);
  }
  void expect(char c) {
    if (m_pos >= m_s.size() || m_s[m_pos] != c) {
      throw std::runtime_error(std::string("expected '") + c + "' at " + std::to_string(m_pos));
    }
    ++m_pos;
  }
  XmlElement element() {
    XmlElement e;
    expect('<');
    e.name = name();
    for (;;) {
      skip_ws();
      if (m_pos >= m_s.size()) throw std::runtime_error("unterminated tag");
      if (m_s[m_pos] == '/') {
        ++m_pos;
        expect('>');
        return e;
      }
      if (m_s[m_pos] == '>') {
        ++m_pos;
        break;
      }
      const std::string key = name();
      expect('=');
      expect('"');
      const std::size_t end = m_s.find('"', m_pos);
      if (end == std::string::npos) throw std::runtime_error("unterminated attribute");
      const std::string value = m_s.substr(m_pos, end - m_pos);
      if (value.find_first_of("<&") != std::string::npos) throw std::runtime_error("bad attribute");
      if (!e.attributes.emplace(key, value).second) throw std::runtime_error("duplicate attribute");
      m_pos = end + 1;
    }
    for (;;) {
      const std::size_t lt = m_s.find('<', m_pos);
      if (lt == std::string::npos) throw std::runtime_error("unclosed <" + e.name + ">");
      e.text.append(m_s, m_pos, lt - m_pos);
      m_pos = lt;
      if (m_s.compare(m_pos, 2, "</") == 0) {
        m_pos += 2;
        if (name() != e.name) throw std::runtime_error("mismatched </...> for <" + e.name + ">");
        skip_ws();
        expect('>');
        if (e.text.find('&') != std::string::npos) throw std::runtime_error("unescaped '&'");
        return e;
      }
      e.children.push_back(element());
    }
  }

  std::string m_s;
  std::size_t m_pos = 0;
};

const XmlElement& child(const XmlElement& e, const std::string& name) {
  for (const auto& c : e.children) {
    if (c.name == name) return c;
  }
  throw std::runtime_error("no <" + name + "> in <" + e.name + ">");
}

const XmlElement& array(const XmlElement& e, const std::string& name) {
  for (const auto& c : e.children) {
    if (c.name == "DataArray" && c.attributes.count("Name") != 0 &&
        c.attributes.at("Name") == name) {
      return c;
    }
  }
  throw std::runtime_error("no DataArray " + name + " in <" + e.name + ">");
}

std::vector<double> numbers(const XmlElement& e) {
  std::vector<double> out;
  std::istringstream in(e.text);
  std::string tok;
  while (in >> tok) {
    double v = 0.0;
    const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (r.ec != std::errc() || r.ptr != tok.data() + tok.size()) {
      throw std::runtime_error("not a number: " + tok);
    }
    out.push_back(v);
  }
  return out;
}

void check_vtu(const TetMesh& m, const std::string& text) {
  const XmlElement root = MiniXml(text).parse();
  ASSERT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attributes.at("type"), "UnstructuredGrid");
  const XmlElement& piece = child(child(root, "UnstructuredGrid"), "Piece");
  const auto n = static_cast<std::size_t>(m.num_nodes());
  const auto k = static_cast<std::size_t>(m.num_tets());
  EXPECT_EQ(piece.attributes.at("NumberOfPoints"), std::to_string(n));
  EXPECT_EQ(piece.attributes.at("NumberOfCells"), std::to_string(k));

  const std::vector<double> pts = numbers(array(child(piece, "Points"), "Points"));
  const std::vector<double> rest = numbers(array(child(piece, "PointData"), "rest"));
  const std::vector<double> vel = numbers(array(child(piece, "PointData"), "velocity"));
  ASSERT_EQ(pts.size(), 3 * n);
  ASSERT_EQ(rest.size(), 3 * n);
  ASSERT_EQ(vel.size(), 3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      const std::size_t j = 3 * i + static_cast<std::size_t>(d);
      EXPECT_EQ(pts[j], m.x[i][d]);  // bit for bit
      EXPECT_EQ(rest[j], m.rest[i][d]);
      EXPECT_EQ(vel[j], m.v[i][d]);
    }
  }
  const XmlElement& cells = child(piece, "Cells");
  const std::vector<double> conn = numbers(array(cells, "connectivity"));
  const std::vector<double> offsets = numbers(array(cells, "offsets"));
  const std::vector<double> types = numbers(array(cells, "types"));
  const std::vector<double> group = numbers(array(child(piece, "CellData"), "group"));
  ASSERT_EQ(conn.size(), 4 * k);
  ASSERT_EQ(offsets.size(), k);
  ASSERT_EQ(types.size(), k);
  ASSERT_EQ(group.size(), k);
  for (std::size_t t = 0; t < k; ++t) {
    for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(conn[4 * t + j], m.tets[t][j]);
    EXPECT_EQ(offsets[t], static_cast<double>(4 * (t + 1)));
    EXPECT_EQ(types[t], 10.0);
    EXPECT_EQ(group[t], m.group[t]);
  }
}

TEST(MeshIoWrite, VtuIsWellFormedWithRightCountsAndValues) {
  test::ScratchDir dir;
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    TetMesh m = test::random_valid_mesh(rng, 4 + trial % 40, 1 + trial % 33);
    std::normal_distribution<double> g(0.0, 1.0);
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      m.x[i] = m.rest[i] + Vec3(g(rng), g(rng), g(rng)) * 1e-3;
      m.v[i] = Vec3(g(rng), g(rng), g(rng));
    }
    write_vtu(dir / test::numbered("m", trial, ".vtu"), m);
    check_vtu(m, test::slurp(dir / test::numbered("m", trial, ".vtu")));
    if (::testing::Test::HasFailure()) FAIL() << "trial " << trial;
  }
}

TEST(MeshIoWrite, VtuOfTheSampleMesh) {
  test::ScratchDir dir;
  const TetMesh m =
      read_mesh(std::filesystem::path(::serosa::test_paths::test_data()) / "meshes" / "box22.msh");
  write_vtu(dir / "box.vtu", m);
  check_vtu(m, test::slurp(dir / "box.vtu"));
}

TEST(MeshIoWrite, MiniXmlRejectsMalformedXml) {
  // The checker itself must be able to fail.
  for (const char* bad : {"<a><b></a></b>", "<a>", "<a x=\"1></a>", "<a></a><b/>",
                          "<a x=\"1\" x=\"2\"/>", "<a>&</a>"}) {
    EXPECT_THROW((void)MiniXml(bad).parse(), std::runtime_error) << bad;
  }
  EXPECT_NO_THROW((void)MiniXml("<?xml version=\"1.0\"?>\n<a k=\"v\"><b/> 1 2 </a>\n").parse());
}

// ------------------------------------------------------------------ OBJ
struct ObjFile {
  std::vector<Vec3> v;
  std::vector<std::string> group_order;                       // g names in file order
  std::map<std::string, std::vector<std::array<long, 3>>> f;  // faces per g, 1-based
};

ObjFile parse_obj(const std::string& text) {
  ObjFile o;
  std::istringstream in(text);
  std::string line;
  std::string current;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "v") {
      double x = 0, y = 0, z = 0;
      ls >> x >> y >> z;
      o.v.emplace_back(x, y, z);
    } else if (kw == "g") {
      ls >> current;
      std::string extra;
      EXPECT_FALSE(ls >> extra) << "g line with more than one name: " << line;
      o.group_order.push_back(current);
    } else if (kw == "f") {
      std::array<long, 3> f{};
      ls >> f[0] >> f[1] >> f[2];
      EXPECT_FALSE(current.empty()) << "face before any g";
      o.f[current].push_back(f);
    }
  }
  return o;
}

TEST(MeshIoWrite, ObjHasOneGroupPerGroupAndOneBasedFaces) {
  test::ScratchDir dir;
  std::mt19937 rng(13);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 3 + trial % 50;
    std::vector<Vec3> pos;
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < n; ++i) pos.emplace_back(u(rng), u(rng), u(rng));
    std::uniform_int_distribution<int> node(0, n - 1);
    std::uniform_int_distribution<int> grp(0, 1 + trial % 6);
    std::vector<Tri> faces;
    std::vector<std::uint16_t> fg;
    for (int k = 0; k < trial % 40; ++k) {
      faces.push_back({node(rng), node(rng), node(rng)});
      fg.push_back(static_cast<std::uint16_t>(grp(rng) * 1000));
    }
    const std::map<int, std::string> names = {{0, "liver surface"}, {2000, "duct"}};
    write_obj(dir / test::numbered("s", trial, ".obj"), pos, faces, fg, names);
    const ObjFile o = parse_obj(test::slurp(dir / test::numbered("s", trial, ".obj")));

    ASSERT_EQ(o.v.size(), pos.size());
    for (std::size_t i = 0; i < pos.size(); ++i) EXPECT_EQ(o.v[i], pos[i]);
    // One g per distinct group, each once, in increasing group order.
    const std::set<std::uint16_t> groups(fg.begin(), fg.end());
    ASSERT_EQ(o.group_order.size(), groups.size());
    std::size_t gi = 0;
    for (const std::uint16_t g : groups) {
      const std::string expect_name = g == 0      ? "liver_surface"
                                      : g == 2000 ? "duct"
                                                  : "group_" + std::to_string(g);
      EXPECT_EQ(o.group_order[gi++], expect_name);
      // The group's faces, in their given order, ids + 1.
      std::vector<std::array<long, 3>> want;
      for (std::size_t f = 0; f < faces.size(); ++f) {
        if (fg[f] == g) want.push_back({faces[f][0] + 1L, faces[f][1] + 1L, faces[f][2] + 1L});
      }
      EXPECT_EQ(o.f.at(expect_name), want);
    }
    if (::testing::Test::HasFailure()) FAIL() << "trial " << trial;
  }
}

TEST(MeshIoWrite, ObjRefusesInconsistentInput) {
  test::ScratchDir dir;
  const std::vector<Vec3> pos = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::vector<Tri> faces = {{0, 1, 2}};
  const std::vector<std::uint16_t> two = {1, 2};
  EXPECT_THROW(write_obj(dir / "a.obj", pos, faces, two), std::invalid_argument);
  const std::vector<Tri> bad = {{0, 1, 3}};
  const std::vector<std::uint16_t> one = {1};
  EXPECT_THROW(write_obj(dir / "b.obj", pos, bad, one), std::invalid_argument);
  const std::vector<Tri> negative = {{0, -1, 2}};
  EXPECT_THROW(write_obj(dir / "c.obj", pos, negative, one), std::invalid_argument);
}

}  // namespace
}  // namespace serosa
