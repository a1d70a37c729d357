// Gmsh ASCII reader, versions 2.x (2.0, 2.1, 2.2) and 4.1. Sections read: $MeshFormat,
// $PhysicalNames, $Entities (4.1), $Nodes, $Elements; any other section is skipped to its $End.
// Elements other than 4-node tets (type 4) are skipped and counted.
//
// Groups: 2.x takes the element's physical tag (first tag), else its elementary tag (second tag)
// when the physical tag is 0, else 1. 4.1 takes the first physical tag of the tet's volume entity
// from $Entities, else the entity tag. Only 3-D physical names go into report.group_names.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/io/raw_mesh.h"
#include "engine/io/text_cursor.h"

namespace serosa::io {
namespace {

enum class Version { k2, k41 };

std::string plural(std::string_view what) {
  if (!what.empty() && what.back() == 'y')
    return std::string(what.substr(0, what.size() - 1)) + "ies";
  return std::string(what) + "s";
}

// Smallest number of bytes a node or element line can take ("1 0 0 0\n" / "1 4 0 1 2 3 4\n").
constexpr std::size_t kMinNodeBytes = 8;
constexpr std::size_t kMinElementBytes = 10;

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& name, MeshReadReport& report)
      : m_c(text, name), m_text(text), m_text_size(text.size()), m_report(report) {
    m_raw.node_file = name;
    m_raw.tet_file = name;
  }

  RawMesh parse() {
    read_header();
    check_no_nul(m_text, m_c.file());
    bool have_nodes = false;
    bool have_elements = false;
    while (!m_c.at_end()) {
      const std::string_view tok = m_c.token("a section header such as $Nodes");
      if (tok.empty() || tok[0] != '$') {
        m_c.fail("unexpected " + quote_token(tok) + " between sections",
                 "a section header ($Name)");
      }
      m_c.end_line(std::string(tok));
      if (tok == "$Nodes") {
        if (have_nodes) m_c.fail("second $Nodes section", "one $Nodes section");
        have_nodes = true;
        if (m_version == Version::k2)
          read_nodes2();
        else
          read_nodes41();
      } else if (tok == "$Elements") {
        if (have_elements) m_c.fail("second $Elements section", "one $Elements section");
        have_elements = true;
        if (m_version == Version::k2)
          read_elements2();
        else
          read_elements41();
      } else if (tok == "$PhysicalNames") {
        read_physical_names();
      } else if (tok == "$Entities" && m_version == Version::k41) {
        read_entities();
      } else if (tok == "$MeshFormat") {
        m_c.fail("second $MeshFormat section", "one $MeshFormat section");
      } else if (tok.substr(0, 4) == "$End") {
        m_c.fail(quote_token(tok) + " without its opening section", "a section header");
      } else {
        skip_section(tok);
      }
    }
    if (!have_nodes) m_c.fail_at(0, "no $Nodes section", "a $Nodes section");
    if (!have_elements) m_c.fail_at(0, "no $Elements section", "an $Elements section");
    if (m_version == Version::k41) resolve_groups41();
    return std::move(m_raw);
  }

 private:
  void expect(std::string_view keyword, std::string_view context) {
    const std::string_view tok = m_c.token(keyword);
    if (tok != keyword) {
      std::string msg = "found " + quote_token(tok);
      msg.append(context.empty() ? "" : " ");
      msg.append(context);
      m_c.fail(msg, keyword);
    }
    m_c.end_line(keyword);
  }

  // A record's first token; `$...` there means the section ended early.
  std::string_view record_start(std::string_view end_keyword, std::int64_t done,
                                std::int64_t declared, std::string_view what) {
    const std::string_view tok = m_c.try_token();
    if (tok.empty() || tok[0] == '$') {  // the message is built only on failure
      const std::string expected =
          std::string(what) + " " + std::to_string(done + 1) + " of " + std::to_string(declared);
      if (tok.empty()) m_c.fail_eof(expected);
      m_c.fail(quote_token(tok) + " after only " + std::to_string(done) + " " + plural(what) +
                   " (" + std::to_string(declared) + " declared)",
               expected + " before " + std::string(end_keyword));
    }
    return tok;
  }

  // The end keyword of a section; anything else means the section holds more than declared.
  void expect_end(std::string_view end_keyword, const std::string& more_message) {
    const std::string_view tok = m_c.token(end_keyword);
    if (tok != end_keyword) {
      m_c.fail(tok[0] == '$' ? "found " + quote_token(tok)
                             : more_message + ": found " + quote_token(tok),
               end_keyword);
    }
    m_c.end_line(end_keyword);
  }

  static std::string more_than(std::int64_t declared, std::string_view what) {
    return "more " + std::string(what) + " than the " + std::to_string(declared) + " declared";
  }

  std::int64_t count(std::string_view what) {
    const std::int64_t n = m_c.int_on_line(what);
    if (n < 0) m_c.fail("negative " + std::string(what) + " " + std::to_string(n), "a count >= 0");
    return n;
  }

  void read_header() {
    const std::string_view first = m_c.token("$MeshFormat");
    if (first != "$MeshFormat") {
      m_c.fail("not a Gmsh mesh: first line starts with " + quote_token(first), "$MeshFormat");
    }
    m_c.end_line("$MeshFormat");
    const std::string_view version = m_c.token("version number");
    const double v = m_c.to_double(version, "version number 2.2 or 4.1");
    if (v == 2.0 || v == 2.1 || v == 2.2) {
      m_version = Version::k2;
    } else if (v == 4.1) {
      m_version = Version::k41;
    } else {
      m_c.fail("unsupported Gmsh format version " + quote_token(version), "2.2 or 4.1 (ASCII)");
    }
    m_report.format = "gmsh " + std::string(version);
    const std::int64_t file_type = m_c.int_on_line("file-type (0 = ASCII)");
    if (file_type != 0) {
      m_c.fail("binary Gmsh file (file-type " + std::to_string(file_type) + ")",
               "an ASCII file (file-type 0): re-export with Mesh.Binary = 0");
    }
    (void)m_c.int_on_line("data-size");
    m_c.end_line("the $MeshFormat line");
    expect("$EndMeshFormat", "");
  }

  void skip_section(std::string_view name) {
    const std::int64_t start = m_c.token_line();
    const std::string end = "$End" + std::string(name.substr(1));
    for (;;) {
      if (m_c.at_end()) m_c.fail_at(start, "section " + quote_token(name) + " never closed", end);
      const std::string_view tok = m_c.token(end);
      if (tok == end) {
        m_c.end_line(end);
        return;
      }
      m_c.skip_line();
    }
  }

  void read_physical_names() {
    const std::int64_t n = count("number of physical names");
    m_c.end_line("the number of physical names");
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t dim =
          m_c.to_int(record_start("$EndPhysicalNames", i, n, "physical name"), "dimension");
      const std::int64_t tag = m_c.int_on_line("physical tag");
      std::string_view rest = m_c.rest_of_line();
      while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
      while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.remove_suffix(1);
      if (rest.size() < 2 || rest.front() != '"' || rest.back() != '"') {
        m_c.fail("physical name " + quote_token(rest) + " is not quoted", "\"name\"");
      }
      if (tag < INT32_MIN || tag > INT32_MAX) m_c.fail("physical tag out of range", "a 32-bit tag");
      if (dim == 3)
        m_report.group_names[static_cast<int>(tag)] = std::string(rest.substr(1, rest.size() - 2));
    }
    expect_end("$EndPhysicalNames", more_than(n, "physical names"));
  }

  // ---------------------------------------------------------------- 2.x
  void read_nodes2() {
    const std::int64_t n = count("number of nodes");
    m_c.end_line("the number of nodes");
    reserve_nodes(n);
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t id = m_c.to_int(record_start("$EndNodes", i, n, "node"), "node id");
      const std::int64_t line = m_c.token_line();
      Vec3 p;
      p.x() = m_c.double_on_line("x coordinate");
      p.y() = m_c.double_on_line("y coordinate");
      p.z() = m_c.double_on_line("z coordinate");
      m_c.end_line("the node's x y z");
      m_raw.add_node(id, p, line, line);
    }
    expect_end("$EndNodes", more_than(n, "nodes"));
  }

  void read_elements2() {
    const std::int64_t n = count("number of elements");
    m_c.end_line("the number of elements");
    reserve_tets(n);
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t element =
          m_c.to_int(record_start("$EndElements", i, n, "element"), "element id");
      const std::int64_t line = m_c.token_line();
      const std::int64_t type = m_c.int_on_line("element type");
      const std::int64_t ntags = m_c.int_on_line("number of tags");
      if (ntags < 0) m_c.fail("negative number of tags", "a count >= 0");
      std::int64_t physical = 0;
      std::int64_t elementary = 0;
      for (std::int64_t k = 0; k < ntags; ++k) {
        const std::int64_t tag = m_c.int_on_line("element tag");
        if (k == 0) physical = tag;
        if (k == 1) elementary = tag;
      }
      if (type != 4) {
        m_c.skip_line();
        ++m_report.skipped_elements;
        continue;
      }
      std::array<std::int64_t, 4> t{};
      for (auto& id : t) id = m_c.int_on_line("4 node ids of the tet");
      m_c.end_line("the tet's 4 node ids");
      const std::int64_t group = physical != 0 ? physical : (ntags >= 2 ? elementary : 1);
      m_raw.add_tet(t, group, line, element);
    }
    expect_end("$EndElements", more_than(n, "elements"));
  }

  // ---------------------------------------------------------------- 4.1
  void read_entities() {
    std::int64_t counts[4] = {0, 0, 0, 0};
    const char* names[4] = {"number of points", "number of curves", "number of surfaces",
                            "number of volumes"};
    for (int d = 0; d < 4; ++d) counts[d] = count(names[d]);
    m_c.end_line("the entity counts");
    const char* what[4] = {"point entity", "curve entity", "surface entity", "volume entity"};
    for (int d = 0; d < 4; ++d) {
      for (std::int64_t i = 0; i < counts[d]; ++i) {
        const std::int64_t tag =
            m_c.to_int(record_start("$EndEntities", i, counts[d], what[d]), "entity tag");
        if (d < 3) {
          m_c.skip_line();
          continue;
        }
        for (int k = 0; k < 6; ++k) (void)m_c.double_on_line("bounding box (6 numbers)");
        const std::int64_t nphys = m_c.int_on_line("number of physical tags");
        if (nphys < 0) m_c.fail("negative number of physical tags", "a count >= 0");
        for (std::int64_t k = 0; k < nphys; ++k) {
          const std::int64_t phys = m_c.int_on_line("physical tag");
          if (k == 0) m_volume_physical[tag] = phys;
        }
        m_c.skip_line();  // bounding surfaces
      }
    }
    expect_end("$EndEntities", "more entities than the header declares");
  }

  void read_nodes41() {
    const std::int64_t blocks = count("number of entity blocks");
    const std::int64_t n = count("number of nodes");
    (void)m_c.int_on_line("minimum node tag");
    (void)m_c.int_on_line("maximum node tag");
    const std::int64_t header_line = m_c.token_line();
    m_c.end_line("the $Nodes header");
    reserve_nodes(n);
    std::int64_t total = 0;
    std::vector<std::int64_t> tags;
    std::vector<std::int64_t> tag_lines;
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::int64_t dim =
          m_c.to_int(record_start("$EndNodes", b, blocks, "node entity block"), "entity dimension");
      if (dim < 0 || dim > 3) m_c.fail("entity dimension " + std::to_string(dim), "0, 1, 2 or 3");
      (void)m_c.int_on_line("entity tag");
      const std::int64_t parametric = m_c.int_on_line("parametric flag");
      if (parametric != 0 && parametric != 1) m_c.fail("parametric flag not 0 or 1", "0 or 1");
      const std::int64_t nin = count("number of nodes in block");
      m_c.end_line("the node block header");
      if (nin > n - total) {  // total <= n here: no overflow
        m_c.fail(
            "the node blocks hold more nodes than the header declares (" + std::to_string(n) + ")",
            "block sizes that add up to the header's count");
      }
      tags.clear();
      tag_lines.clear();
      for (std::int64_t i = 0; i < nin; ++i) {
        tags.push_back(
            m_c.to_int(record_start("$EndNodes", i, nin, "node tag of block"), "node tag"));
        tag_lines.push_back(m_c.token_line());
        m_c.end_line("the node tag");
      }
      const std::int64_t extra = parametric != 0 ? dim : 0;
      for (std::int64_t i = 0; i < nin; ++i) {
        Vec3 p;
        p.x() = m_c.to_double(record_start("$EndNodes", i, nin, "node coordinate line of block"),
                              "x coordinate");
        const std::int64_t line = m_c.token_line();
        p.y() = m_c.double_on_line("y coordinate");
        p.z() = m_c.double_on_line("z coordinate");
        for (std::int64_t k = 0; k < extra; ++k) (void)m_c.double_on_line("parametric coordinate");
        m_c.end_line("the node's coordinates");
        m_raw.add_node(tags[static_cast<std::size_t>(i)], p, tag_lines[static_cast<std::size_t>(i)],
                       line);
      }
      total += nin;
    }
    if (total != n) {
      m_c.fail_at(header_line,
                  "the node blocks hold " + std::to_string(total) +
                      " nodes but the header declares " + std::to_string(n),
                  "matching counts");
    }
    expect_end("$EndNodes", "more nodes or node blocks than the header declares");
  }

  void read_elements41() {
    const std::int64_t blocks = count("number of entity blocks");
    const std::int64_t n = count("number of elements");
    (void)m_c.int_on_line("minimum element tag");
    (void)m_c.int_on_line("maximum element tag");
    const std::int64_t header_line = m_c.token_line();
    m_c.end_line("the $Elements header");
    reserve_tets(n);
    std::int64_t total = 0;
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = m_c.to_int(
          record_start("$EndElements", b, blocks, "element entity block"), "entity dimension");
      const std::int64_t entity = m_c.int_on_line("entity tag");
      const std::int64_t type = m_c.int_on_line("element type");
      const std::int64_t nin = count("number of elements in block");
      m_c.end_line("the element block header");
      if (nin > n - total) {  // total <= n here: no overflow
        m_c.fail("the element blocks hold more elements than the header declares (" +
                     std::to_string(n) + ")",
                 "block sizes that add up to the header's count");
      }
      if (type == 4 && dim != 3) {
        m_c.fail("tet block on an entity of dimension " + std::to_string(dim), "dimension 3");
      }
      for (std::int64_t i = 0; i < nin; ++i) {
        const std::int64_t element =
            m_c.to_int(record_start("$EndElements", i, nin, "element of block"), "element tag");
        const std::int64_t line = m_c.token_line();
        if (type != 4) {
          m_c.skip_line();
          ++m_report.skipped_elements;
          continue;
        }
        std::array<std::int64_t, 4> t{};
        for (auto& id : t) id = m_c.int_on_line("4 node ids of the tet");
        m_c.end_line("the tet's 4 node ids");
        m_raw.add_tet(t, entity, line, element);  // entity tag for now: resolved after $Entities
      }
      total += nin;
    }
    if (total != n) {
      m_c.fail_at(header_line,
                  "the element blocks hold " + std::to_string(total) +
                      " elements but the header declares " + std::to_string(n),
                  "matching counts");
    }
    expect_end("$EndElements", "more elements or element blocks than the header declares");
  }

  // A tet's group: its volume's first physical tag, else the volume's entity tag.
  void resolve_groups41() {
    for (auto& g : m_raw.tet_group) {
      const auto it = m_volume_physical.find(g);
      if (it != m_volume_physical.end()) g = it->second;
    }
  }

  void reserve_nodes(std::int64_t n) {
    const std::size_t r = safe_reserve(n, m_text_size, kMinNodeBytes);
    m_raw.node_id.reserve(r);
    m_raw.node_pos.reserve(r);
    m_raw.node_id_line.reserve(r);
    m_raw.node_line.reserve(r);
  }
  void reserve_tets(std::int64_t n) {
    const std::size_t r = safe_reserve(n, m_text_size, kMinElementBytes);
    m_raw.tet_nodes.reserve(r);
    m_raw.tet_group.reserve(r);
    m_raw.tet_line.reserve(r);
  }

  TextCursor m_c;
  std::string_view m_text;
  std::size_t m_text_size;
  MeshReadReport& m_report;
  Version m_version = Version::k2;
  RawMesh m_raw;
  std::map<std::int64_t, std::int64_t> m_volume_physical;  // volume entity tag -> physical tag
};

}  // namespace

RawMesh parse_gmsh(std::string_view text, const std::string& name, MeshReadReport& report) {
  return GmshParser(text, name, report).parse();
}

}  // namespace serosa::io
