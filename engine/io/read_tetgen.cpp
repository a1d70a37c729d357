// TetGen reader: a .node file (points) and an .ele file (tets), with '#' comments and blank lines.
// .node: "<#points> <dimension = 3> <#attributes> <#boundary markers 0|1>", then
//        "<id> <x> <y> <z> [attributes] [marker]" per point.
// .ele:  "<#tets> <nodes per tet 4|10> <#attributes>", then "<id> <n1> .. <nk> [attributes]" per
//        tet; the first four nodes are the corners, the first attribute (the region) is the group
//        (1 when there is none). Ids may start at 0 or 1.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/io/raw_mesh.h"
#include "engine/io/text_cursor.h"

namespace serosa::io {
namespace {

constexpr std::size_t kMinLineBytes = 8;

// A header field that may be left out (TetGen fills in 0).
std::int64_t optional_count(TextCursor& c, std::string_view what) {
  if (!c.more_on_line()) return 0;
  const std::int64_t v = c.int_on_line(what);
  if (v < 0) c.fail("negative " + std::string(what), "a count >= 0");
  return v;
}

std::string_view record_start(TextCursor& c, std::int64_t done, std::int64_t declared,
                              std::string_view what) {
  const std::string_view tok = c.try_token();
  if (tok.empty()) {  // the message is built only on failure
    c.fail_eof(std::string(what) + " " + std::to_string(done + 1) + " of " +
               std::to_string(declared));
  }
  return tok;
}

void expect_no_more(TextCursor& c, std::int64_t declared, std::string_view what) {
  if (!c.at_end()) {
    (void)c.token("end of file");
    c.fail("more " + std::string(what) + "s than the " + std::to_string(declared) + " declared",
           "end of file");
  }
}

void read_nodes(TextCursor& c, std::size_t text_size, RawMesh& raw) {
  const std::int64_t n = c.next_int("number of points");
  if (n < 0) c.fail("negative number of points", "a count >= 0");
  if (n == 0) c.fail("0 points (points in a .poly/.smesh file are not supported)", "points");
  const std::int64_t dim = c.more_on_line() ? c.int_on_line("dimension") : 3;
  if (dim != 3) c.fail("dimension " + std::to_string(dim), "3");
  const std::int64_t nattr = optional_count(c, "number of point attributes");
  const std::int64_t nmarker = optional_count(c, "number of boundary markers");
  if (nmarker > 1) c.fail("number of boundary markers is " + std::to_string(nmarker), "0 or 1");
  c.end_line("the .node header");
  const std::size_t r = safe_reserve(n, text_size, kMinLineBytes);
  raw.node_id.reserve(r);
  raw.node_pos.reserve(r);
  raw.node_id_line.reserve(r);
  raw.node_line.reserve(r);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t id = c.to_int(record_start(c, i, n, "point"), "point id");
    const std::int64_t line = c.token_line();
    Vec3 p;
    p.x() = c.double_on_line("x coordinate");
    p.y() = c.double_on_line("y coordinate");
    p.z() = c.double_on_line("z coordinate");
    for (std::int64_t k = 0; k < nattr; ++k) (void)c.double_on_line("point attribute");
    for (std::int64_t k = 0; k < nmarker; ++k) (void)c.int_on_line("boundary marker");
    c.end_line("the point's fields");
    raw.add_node(id, p, line, line);
  }
  expect_no_more(c, n, "point");
}

void read_tets(TextCursor& c, std::size_t text_size, RawMesh& raw) {
  const std::int64_t n = c.next_int("number of tets");
  if (n < 0) c.fail("negative number of tets", "a count >= 0");
  const std::int64_t per = c.more_on_line() ? c.int_on_line("nodes per tet") : 4;
  if (per != 4 && per != 10) c.fail(std::to_string(per) + " nodes per tet", "4 or 10");
  const std::int64_t nattr = optional_count(c, "number of tet attributes");
  c.end_line("the .ele header");
  const std::size_t r = safe_reserve(n, text_size, kMinLineBytes);
  raw.tet_nodes.reserve(r);
  raw.tet_group.reserve(r);
  raw.tet_line.reserve(r);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t tet_id = c.to_int(record_start(c, i, n, "tet"), "tet id");
    const std::int64_t line = c.token_line();
    std::array<std::int64_t, 4> t{};
    for (auto& id : t) id = c.int_on_line("node id");
    for (std::int64_t k = 4; k < per; ++k) (void)c.int_on_line("node id");
    std::int64_t group = 1;
    for (std::int64_t k = 0; k < nattr; ++k) {
      const std::string_view tok = c.token_on_line("tet attribute");
      const double a = c.to_double(tok, "region attribute");
      if (k > 0) continue;
      if (!(std::abs(a) < 1e15) || std::floor(a) != a) {
        c.fail("region attribute " + quote_token(tok) + " is not an integer",
               "an integer group id");
      }
      group = static_cast<std::int64_t>(a);
    }
    c.end_line("the tet's fields");
    raw.add_tet(t, group, line, tet_id);
  }
  expect_no_more(c, n, "tet");
}

}  // namespace

RawMesh parse_tetgen(std::string_view node_text, const std::string& node_name,
                     std::string_view ele_text, const std::string& ele_name,
                     MeshReadReport& report) {
  RawMesh raw;
  raw.node_file = node_name;
  raw.tet_file = ele_name;
  report.format = "tetgen";
  check_no_nul(node_text, node_name);
  check_no_nul(ele_text, ele_name);
  TextCursor nodes(node_text, node_name, '#');
  read_nodes(nodes, node_text.size(), raw);
  TextCursor tets(ele_text, ele_name, '#');
  read_tets(tets, ele_text.size(), raw);
  return raw;
}

}  // namespace serosa::io
