// Legacy VTK reader: ASCII DATASET UNSTRUCTURED_GRID, file versions 2.0 to 5.1 (5.x writes CELLS as
// OFFSETS and CONNECTIVITY arrays). Cells of type 10 (VTK_TETRA) become tets; other cells are
// skipped and counted. A tet's group comes from a 1-component cell-data array named "group"
// (preferred) or "gmsh:physical", given as SCALARS or as a FIELD array; 1 when neither is present.
// Point data, other cell data, lookup tables and METADATA blocks are read past.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/raw_mesh.h"
#include "engine/io/text_cursor.h"

namespace serosa::io {
namespace {

constexpr std::size_t kMinValueBytes = 2;  // "0 "

std::string format_number(double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", v);
  return std::string(buf, static_cast<std::size_t>(n > 0 ? n : 0));
}

enum class Context { kNone, kPoints, kCells };

struct GroupArray {
  std::vector<double> value;       // (cells) group per cell, as written
  std::vector<std::int64_t> line;  // (cells) line of each value
  bool present = false;
};

class VtkParser {
 public:
  VtkParser(std::string_view text, const std::string& name, MeshReadReport& report)
      : m_c(text, name), m_text(text), m_text_size(text.size()), m_report(report) {
    m_raw.node_file = name;
    m_raw.tet_file = name;
  }

  RawMesh parse() {
    read_header();
    check_no_nul(m_text, m_c.file());
    while (!m_c.at_end()) {
      const std::string_view kw = m_c.token("a VTK keyword");
      if (iequals(kw, "POINTS")) {
        read_points();
      } else if (iequals(kw, "CELLS")) {
        if (m_version >= 5.0)
          read_cells5();
        else
          read_cells_legacy();
      } else if (iequals(kw, "CELL_TYPES")) {
        read_cell_types();
      } else if (iequals(kw, "CELL_DATA")) {
        m_context = Context::kCells;
        m_count = data_count("number of cells", m_have_cells, num_cells());
      } else if (iequals(kw, "POINT_DATA")) {
        m_context = Context::kPoints;
        m_count = data_count("number of points", m_have_points,
                             static_cast<std::int64_t>(m_raw.node_id.size()));
      } else if (iequals(kw, "FIELD")) {
        read_field();
      } else if (iequals(kw, "METADATA")) {
        skip_metadata();
      } else if (!read_attribute(kw)) {
        m_c.fail("unknown keyword " + quote_token(kw),
                 "POINTS, CELLS, CELL_TYPES, CELL_DATA, POINT_DATA or a data attribute");
      }
    }
    return finish();
  }

 private:
  [[nodiscard]] std::int64_t num_cells() const {
    return static_cast<std::int64_t>(m_cell_start.size()) - 1;
  }

  std::int64_t count_on_line(std::string_view what) {
    const std::int64_t n = m_c.int_on_line(what);
    if (n < 0) m_c.fail("negative " + std::string(what), "a count >= 0");
    return n;
  }

  void read_header() {
    const std::string_view first = m_c.rest_of_line();
    constexpr std::string_view kMagic = "# vtk DataFile Version";
    if (first.size() < kMagic.size() || !iequals(first.substr(0, kMagic.size()), kMagic)) {
      m_c.fail_at(1, "not a legacy VTK file: first line is " + quote_token(first),
                  "'# vtk DataFile Version x.x'");
    }
    std::string_view v = first.substr(kMagic.size());
    while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
    while (!v.empty() && (v.back() == ' ' || v.back() == '\t')) v.remove_suffix(1);
    m_version = v.empty() ? 0.0 : m_c.to_double(v, "version 2.0 to 5.1");
    if (!(m_version >= 2.0 && m_version <= 5.1)) {
      m_c.fail_at(1, "unsupported VTK file version " + quote_token(v), "version 2.0 to 5.1");
    }
    m_report.format = "vtk " + std::string(v);
    (void)m_c.rest_of_line();  // title
    const std::string_view enc = m_c.token("ASCII");
    if (iequals(enc, "BINARY")) m_c.fail("binary VTK file", "ASCII");
    if (!iequals(enc, "ASCII")) m_c.fail("found " + quote_token(enc), "ASCII or BINARY");
    m_c.end_line("ASCII");
    const std::string_view ds = m_c.token("DATASET");
    if (!iequals(ds, "DATASET")) m_c.fail("found " + quote_token(ds), "DATASET");
    const std::string_view type = m_c.token_on_line("dataset type");
    if (!iequals(type, "UNSTRUCTURED_GRID")) {
      m_c.fail("dataset type " + quote_token(type) + " is not supported", "UNSTRUCTURED_GRID");
    }
    m_c.end_line("the dataset type");
  }

  void read_points() {
    if (m_have_points) m_c.fail("second POINTS section", "one POINTS section");
    m_have_points = true;
    const std::int64_t n = count_on_line("number of points");
    (void)m_c.token_on_line("data type");
    m_c.end_line("the POINTS header");
    const std::size_t r = safe_reserve(n, m_text_size, 3 * kMinValueBytes);
    m_raw.node_id.reserve(r);
    m_raw.node_pos.reserve(r);
    m_raw.node_id_line.reserve(r);
    m_raw.node_line.reserve(r);
    for (std::int64_t i = 0; i < n; ++i) {
      Vec3 p;
      p.x() = m_c.to_double(value_token("x of point", i + 1, n), "x coordinate");
      const std::int64_t line = m_c.token_line();
      p.y() = m_c.to_double(value_token("y of point", i + 1, n), "y coordinate");
      p.z() = m_c.to_double(value_token("z of point", i + 1, n), "z coordinate");
      m_raw.add_node(i, p, line, line);
    }
  }

  // A value token (item `index` of `count`, 1-based, for the message); a keyword in its place
  // means the data ended early. Messages are built only on failure.
  std::string_view value_token(const char* what, std::int64_t index, std::int64_t count) {
    const std::string_view tok = m_c.try_token();
    const auto expected = [&] {
      return std::string(what) + " " + std::to_string(index) + " of " + std::to_string(count);
    };
    if (tok.empty()) m_c.fail_eof(expected());
    const char c0 = tok[0];
    if ((c0 >= 'A' && c0 <= 'Z' && tok.size() > 3) || c0 == '_') {
      m_c.fail("keyword-like " + quote_token(tok) + " where data was expected (too few values?)",
               expected());
    }
    return tok;
  }

  void begin_cells() {
    if (m_have_cells) m_c.fail("second CELLS section", "one CELLS section");
    m_have_cells = true;
  }

  void read_cells_legacy() {
    begin_cells();
    const std::int64_t header_line = m_c.token_line();
    const std::int64_t n = count_on_line("number of cells");
    const std::int64_t size = count_on_line("size of the cell list");
    m_c.end_line("the CELLS header");
    const std::size_t r = safe_reserve(n, m_text_size, 2 * kMinValueBytes);
    m_cell_start.reserve(r + 1);
    m_cell_line.reserve(r);
    m_conn.reserve(safe_reserve(size, m_text_size, kMinValueBytes));
    std::int64_t used = 0;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t k =
          m_c.to_int(value_token("point count of cell", i + 1, n), "number of points in the cell");
      if (k < 0) m_c.fail("negative number of points in a cell", "a count >= 0");
      m_cell_line.push_back(m_c.token_line());
      // Checked before adding (used <= size here), so a hostile count cannot overflow.
      if (k > size - used - 1) {
        m_c.fail("cell list longer than the size " + std::to_string(size) + " declared",
                 "CELLS n size with size = sum of (1 + points per cell)");
      }
      used += 1 + k;
      for (std::int64_t j = 0; j < k; ++j) {
        m_conn.push_back(m_c.to_int(value_token("point id of cell", i + 1, n), "point id"));
      }
      m_cell_start.push_back(static_cast<std::int64_t>(m_conn.size()));
    }
    if (used != size) {
      m_c.fail_at(header_line,
                  "CELLS declares size " + std::to_string(size) + " but the cells use " +
                      std::to_string(used),
                  "size = sum of (1 + points per cell)");
    }
  }

  // 5.x: CELLS <offsets> <connectivity>, OFFSETS <type> values, CONNECTIVITY <type> values.
  void read_cells5() {
    begin_cells();
    const std::int64_t noff = count_on_line("number of offsets");
    const std::int64_t nconn = count_on_line("connectivity size");
    m_c.end_line("the CELLS header");
    const std::string_view off_kw = m_c.token("OFFSETS");
    if (!iequals(off_kw, "OFFSETS")) m_c.fail("found " + quote_token(off_kw), "OFFSETS");
    (void)m_c.token_on_line("offset data type");
    m_c.end_line("the OFFSETS line");
    if (noff == 0 && nconn != 0) m_c.fail("connectivity without offsets", "at least one offset");
    std::vector<std::int64_t> offsets;
    offsets.reserve(safe_reserve(noff, m_text_size, kMinValueBytes));
    for (std::int64_t i = 0; i < noff; ++i) {
      const std::int64_t o = m_c.to_int(value_token("offset", i + 1, noff), "offset");
      if (i == 0 && o != 0) m_c.fail("first offset is " + std::to_string(o), "0");
      if (i > 0 && o < offsets.back()) m_c.fail("offsets decrease", "non-decreasing offsets");
      if (o > nconn)
        m_c.fail("offset beyond the connectivity size", "offset <= " + std::to_string(nconn));
      offsets.push_back(o);
      if (i > 0) m_cell_line.push_back(m_c.token_line());
    }
    if (noff > 0 && offsets.back() != nconn) {
      m_c.fail(
          "last offset " + std::to_string(offsets.back()) + " differs from the connectivity size",
          std::to_string(nconn));
    }
    const std::string_view conn_kw = m_c.token("CONNECTIVITY");
    if (!iequals(conn_kw, "CONNECTIVITY"))
      m_c.fail("found " + quote_token(conn_kw), "CONNECTIVITY");
    (void)m_c.token_on_line("connectivity data type");
    m_c.end_line("the CONNECTIVITY line");
    m_conn.reserve(safe_reserve(nconn, m_text_size, kMinValueBytes));
    // Each cell's line is that of its first connectivity value (more useful than its offset's).
    const std::size_t ncell = offsets.empty() ? 0 : offsets.size() - 1;
    std::size_t cell = 0;
    for (std::int64_t i = 0; i < nconn; ++i) {
      m_conn.push_back(m_c.to_int(value_token("connectivity value", i + 1, nconn), "point id"));
      while (cell < ncell && offsets[cell + 1] <= i) ++cell;
      if (cell < ncell && offsets[cell] == i) m_cell_line[cell] = m_c.token_line();
    }
    m_cell_start.clear();
    m_cell_start.push_back(0);
    for (std::size_t i = 1; i < offsets.size(); ++i) m_cell_start.push_back(offsets[i]);
  }

  void read_cell_types() {
    if (m_have_types) m_c.fail("second CELL_TYPES section", "one CELL_TYPES section");
    m_have_types = true;
    const std::int64_t n = count_on_line("number of cells");
    if (m_have_cells && n != num_cells()) {
      m_c.fail("CELL_TYPES declares " + std::to_string(n) + " cells but CELLS holds " +
                   std::to_string(num_cells()),
               "the same number of cells");
    }
    m_c.end_line("the CELL_TYPES header");
    m_cell_type.reserve(safe_reserve(n, m_text_size, kMinValueBytes));
    for (std::int64_t i = 0; i < n; ++i) {
      m_cell_type.push_back(m_c.to_int(value_token("type of cell", i + 1, n), "cell type"));
    }
  }

  std::int64_t data_count(std::string_view what, bool known, std::int64_t actual) {
    const std::int64_t n = count_on_line(what);
    if (known && n != actual) {
      m_c.fail("data section declares " + std::to_string(n) + " but the grid has " +
                   std::to_string(actual),
               std::to_string(actual));
    }
    m_c.end_line("the data section header");
    return n;
  }

  [[nodiscard]] static bool is_group_name(std::string_view name) {
    return name == "group" || name == "gmsh:physical";
  }

  std::int64_t product(std::int64_t a, std::int64_t b) {
    if (a < 0 || b < 0) m_c.fail("negative size", "sizes >= 0");
    if (b != 0 && a > std::numeric_limits<std::int64_t>::max() / b)
      m_c.fail("size overflows", "a smaller size");
    return a * b;
  }

  // Reads `n` values; when `group` is set they are this array's per-cell groups.
  void read_values(std::int64_t n, GroupArray* group) {
    if (group != nullptr) {
      group->present = true;
      group->value.clear();
      group->line.clear();
      group->value.reserve(safe_reserve(n, m_text_size, kMinValueBytes));
      group->line.reserve(safe_reserve(n, m_text_size, kMinValueBytes));
    }
    for (std::int64_t i = 0; i < n; ++i) {
      const std::string_view tok = m_c.try_token();
      if (tok.empty()) {
        m_c.fail_eof("data value " + std::to_string(i + 1) + " of " + std::to_string(n));
      }
      if (group != nullptr) {
        group->value.push_back(m_c.to_double(tok, "a group id"));
        group->line.push_back(m_c.token_line());
      }
    }
  }

  GroupArray* group_slot(std::string_view name, std::int64_t components, std::int64_t tuples) {
    if (m_context != Context::kCells || components != 1 || tuples != m_count) return nullptr;
    if (name == "group") return &m_group;
    if (name == "gmsh:physical") return &m_physical;
    return nullptr;
  }

  void need_context(std::string_view kw) {
    if (m_context == Context::kNone) {
      m_c.fail(quote_token(kw) + " before POINT_DATA or CELL_DATA",
               "POINT_DATA or CELL_DATA first");
    }
  }

  // SCALARS and the other dataset attributes; false when kw is none of them.
  bool read_attribute(std::string_view kw) {
    std::int64_t per = -1;  // values per point or cell
    if (iequals(kw, "SCALARS")) {
      need_context(kw);
      const std::string name(m_c.token_on_line("array name"));
      (void)m_c.token_on_line("data type");
      std::int64_t ncomp = 1;
      if (m_c.more_on_line()) ncomp = m_c.int_on_line("number of components");
      if (ncomp < 1 || ncomp > 4)
        m_c.fail("SCALARS with " + std::to_string(ncomp) + " components", "1 to 4");
      m_c.end_line("the SCALARS header");
      const TextCursor::Mark before = m_c.mark();
      if (!m_c.at_end() && iequals(m_c.token("LOOKUP_TABLE"), "LOOKUP_TABLE")) {
        (void)m_c.token_on_line("lookup table name");
        m_c.end_line("the LOOKUP_TABLE line");
      } else {
        m_c.reset(before);
      }
      read_values(product(m_count, ncomp), group_slot(name, ncomp, m_count));
      return true;
    }
    if (iequals(kw, "COLOR_SCALARS")) {
      need_context(kw);
      (void)m_c.token_on_line("array name");
      per = m_c.int_on_line("number of values");
    } else if (iequals(kw, "LOOKUP_TABLE")) {
      need_context(kw);
      (void)m_c.token_on_line("table name");
      const std::int64_t size = m_c.int_on_line("table size");
      m_c.end_line("the LOOKUP_TABLE header");
      read_values(product(size, 4), nullptr);
      return true;
    } else if (iequals(kw, "VECTORS") || iequals(kw, "NORMALS")) {
      per = 3;
    } else if (iequals(kw, "TENSORS")) {
      per = 9;
    } else if (iequals(kw, "TENSORS6")) {
      per = 6;
    } else if (iequals(kw, "GLOBAL_IDS") || iequals(kw, "PEDIGREE_IDS")) {
      per = 1;
    } else if (iequals(kw, "TEXTURE_COORDINATES")) {
      need_context(kw);
      (void)m_c.token_on_line("array name");
      per = m_c.int_on_line("dimension");
    } else {
      return false;
    }
    need_context(kw);
    if (iequals(kw, "VECTORS") || iequals(kw, "NORMALS") || iequals(kw, "TENSORS") ||
        iequals(kw, "TENSORS6") || iequals(kw, "GLOBAL_IDS") || iequals(kw, "PEDIGREE_IDS")) {
      (void)m_c.token_on_line("array name");
    }
    while (m_c.more_on_line()) (void)m_c.token_on_line("data type");
    m_c.skip_line();
    read_values(product(m_count, per), nullptr);
    return true;
  }

  // FIELD <name> <arrays>, then per array: <name> <components> <tuples> <type> and its values.
  void read_field() {
    (void)m_c.token_on_line("field name");
    const std::int64_t narrays = count_on_line("number of arrays");
    m_c.end_line("the FIELD header");
    for (std::int64_t a = 0; a < narrays; ++a) {
      const std::string name(
          m_c.token("array " + std::to_string(a + 1) + " of " + std::to_string(narrays)));
      const std::int64_t ncomp = count_on_line("number of components");
      const std::int64_t ntuples = count_on_line("number of tuples");
      (void)m_c.token_on_line("data type");
      m_c.end_line("the array header");
      read_values(product(ncomp, ntuples), group_slot(name, ncomp, ntuples));
      const TextCursor::Mark before = m_c.mark();
      if (!m_c.at_end() && iequals(m_c.token("METADATA"), "METADATA")) {
        skip_metadata();
      } else {
        m_c.reset(before);
      }
    }
  }

  // METADATA blocks run to the next blank line.
  void skip_metadata() {
    m_c.skip_line();
    for (;;) {
      const std::int64_t line = m_c.line();
      const std::string_view l = m_c.rest_of_line();
      if (l.find_first_not_of(" \t\r") == std::string_view::npos || m_c.line() == line) return;
    }
  }

  RawMesh finish() {
    if (!m_have_points) m_c.fail_at(0, "no POINTS section", "POINTS");
    if (!m_have_cells) m_c.fail_at(0, "no CELLS section", "CELLS");
    if (!m_have_types) m_c.fail_at(0, "no CELL_TYPES section", "CELL_TYPES");
    if (static_cast<std::int64_t>(m_cell_type.size()) != num_cells()) {
      m_c.fail_at(0,
                  "CELL_TYPES holds " + std::to_string(m_cell_type.size()) +
                      " cells but CELLS holds " + std::to_string(num_cells()),
                  "the same number of cells");
    }
    const GroupArray* groups =
        m_group.present ? &m_group : (m_physical.present ? &m_physical : nullptr);
    for (std::size_t i = 0; i + 1 < m_cell_start.size(); ++i) {
      const auto begin = static_cast<std::size_t>(m_cell_start[i]);
      const auto k = static_cast<std::size_t>(m_cell_start[i + 1]) - begin;
      if (m_cell_type[i] != 10) {
        ++m_report.skipped_elements;
        continue;
      }
      if (k != 4) {
        m_c.fail_at(m_cell_line[i], "tetra cell (type 10) with " + std::to_string(k) + " points",
                    "4 points");
      }
      std::int64_t group = 1;
      if (groups != nullptr) {
        const double g = groups->value[i];
        if (!(std::abs(g) < 1e15) || std::floor(g) != g) {
          m_c.fail_at(groups->line[i], "group value " + format_number(g) + " is not an integer",
                      "an integer group id");
        }
        group = static_cast<std::int64_t>(g);
      }
      m_raw.add_tet({m_conn[begin], m_conn[begin + 1], m_conn[begin + 2], m_conn[begin + 3]}, group,
                    m_cell_line[i], static_cast<std::int64_t>(i));
    }
    return std::move(m_raw);
  }

  TextCursor m_c;
  std::string_view m_text;
  std::size_t m_text_size;
  MeshReadReport& m_report;
  double m_version = 0.0;
  RawMesh m_raw;
  bool m_have_points = false;
  bool m_have_cells = false;
  bool m_have_types = false;
  std::vector<std::int64_t> m_cell_start{0};  // (cells + 1) offsets into m_conn
  std::vector<std::int64_t> m_conn;           // point ids of all cells
  std::vector<std::int64_t> m_cell_line;      // (cells) line of each cell
  std::vector<std::int64_t> m_cell_type;      // (cells) VTK cell type
  Context m_context = Context::kNone;
  std::int64_t m_count = 0;  // points or cells in the current data section
  GroupArray m_group;        // cell data "group"
  GroupArray m_physical;     // cell data "gmsh:physical"
};

}  // namespace

RawMesh parse_vtk(std::string_view text, const std::string& name, MeshReadReport& report) {
  return VtkParser(text, name, report).parse();
}

}  // namespace serosa::io
