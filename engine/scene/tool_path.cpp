#include "engine/scene/tool_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "engine/input_error.h"
#include "engine/instrument_hold.h"
#include "engine/math.h"

namespace serosa {
namespace {

constexpr std::string_view kHeader = "t,tool,px,py,pz,qw,qx,qy,qz,jaw";
// The same with the buttons a rig's handle reports (bit 0 clutch, 1 cautery pedal, 2 handle
// button: docs/rig-protocol.md), for the emulated rig's handles.
constexpr std::string_view kHeaderWithButtons = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons";
// The same with the hand that holds the tool at each row (left, right), or port when it waits in
// its port (engine/instrument_hold.h); empty: none, the script plays it directly.
constexpr std::string_view kHeaderWithHand = "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand";
constexpr std::size_t kMaxColumns = 12;
constexpr std::size_t kHandColumn = 11;
constexpr const char* kColumnNames[kMaxColumns] = {"t",  "tool", "px", "py",  "pz",      "qw",
                                                   "qx", "qy",   "qz", "jaw", "buttons", "hand"};

std::size_t columns_of(const std::string& header) {
  if (header == kHeader) return 10;
  if (header == kHeaderWithButtons) return 11;
  if (header == kHeaderWithHand) return kMaxColumns;
  return 0;
}

std::string_view header_of(std::size_t columns) {
  return columns == 10 ? kHeader : columns == 11 ? kHeaderWithButtons : kHeaderWithHand;
}

// The hand column's word into the holder bits of ToolState::buttons.
std::uint32_t parse_hand(std::string_view field, const std::string& file, std::int64_t line) {
  ToolState s;
  if (field == "left")
    set_holder(s, Hand::kLeft);
  else if (field == "right")
    set_holder(s, Hand::kRight);
  else if (field == "port")
    set_in_port(s, true);
  else if (!field.empty())
    throw InputError(file, line, "column 'hand': '" + std::string(field) + "' is not a hand",
                     "left, right, port, or empty (played directly)");
  return s.buttons;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

// Parses one numeric field; the whole field must be a finite number.
double parse_number(std::string_view field, const std::string& file, std::int64_t line,
                    std::size_t column) {
  double value = 0.0;
  const char* begin = field.data();
  const char* end = field.data() + field.size();
  if (!field.empty() && *begin == '+') ++begin;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  const std::string col = kColumnNames[column];
  if (field.empty() || ec != std::errc() || ptr != end) {
    throw InputError(file, line,
                     "column '" + col + "': '" + std::string(field) + "' is not a number",
                     "a decimal number");
  }
  if (!std::isfinite(value)) {
    throw InputError(file, line, "column '" + col + "': " + std::string(field) + " is not finite",
                     "a finite number");
  }
  return value;
}

// One span of time a hand holds a tool: from a row to the tool's next row.
struct Held {
  double from_s, to_s;
  std::size_t tool;
};

std::vector<Held> held_spans(const ToolPath& path, Hand hand) {
  std::vector<Held> out;
  for (std::size_t k = 0; k < path.samples.size(); ++k) {
    const auto& rows = path.samples[k];
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (holder(rows[i]) != hand) continue;
      const double to =
          i + 1 < rows.size() ? rows[i + 1].time_s : std::numeric_limits<double>::infinity();
      if (to > rows[i].time_s) out.push_back({rows[i].time_s, to, k});
    }
  }
  std::sort(out.begin(), out.end(),
            [](const Held& a, const Held& b) { return a.from_s < b.from_s; });
  return out;
}

// A hand holds one instrument at a time.
void check_hands(const ToolPath& path) {
  for (const Hand hand : {Hand::kLeft, Hand::kRight}) {
    const std::vector<Held> spans = held_spans(path, hand);
    double until = -1.0;  // the latest end of the spans so far, and whose
    std::size_t whose = 0;
    for (const Held& b : spans) {
      if (b.from_s < until && b.tool != whose) {
        char at[32];
        std::snprintf(at, sizeof at, "%.3f s", b.from_s);
        throw InputError(
            path.file, 0,
            "the " + std::string(hand == Hand::kLeft ? "left" : "right") + " hand holds both \"" +
                path.tools[whose] + "\" and \"" + path.tools[b.tool] + "\" at " + at,
            "one tool per hand at a time, the other in its port (hand column \"port\")");
      }
      if (b.to_s > until) {
        until = b.to_s;
        whose = b.tool;
      }
    }
  }
}

}  // namespace

std::optional<std::size_t> ToolPath::index_of(std::string_view tool) const {
  for (std::size_t i = 0; i < tools.size(); ++i) {
    if (tools[i] == tool) return i;
  }
  return std::nullopt;
}

double ToolPath::end_time_s() const {
  double t = 0.0;
  for (const auto& rows : samples) {
    if (!rows.empty()) t = std::max(t, rows.back().time_s);
  }
  return t;
}

ToolPath parse_tool_path_text(const std::string& text, const std::string& name) {
  ToolPath path;
  path.file = name;
  std::istringstream in(text);
  std::string raw;
  std::int64_t line = 0;
  bool have_header = false;
  std::size_t columns = 10;             // 11 with buttons, 12 with the hand
  std::vector<std::int64_t> last_line;  // (k) line of each tool's previous row

  while (std::getline(in, raw)) {
    ++line;
    const std::string_view content = trim(raw);
    if (content.empty() || content.front() == '#') continue;

    // The first non-comment line is the header.
    if (!have_header) {
      std::string header;
      for (const auto f : split_commas(content)) {
        if (!header.empty()) header += ',';
        header += f;
      }
      columns = columns_of(header);
      if (columns == 0) {
        throw InputError(
            name, line, "bad tool path header '" + std::string(content) + "'",
            "the header " + std::string(kHeader) + " (or with ,buttons or ,buttons,hand)");
      }
      have_header = true;
      continue;
    }

    const auto fields = split_commas(content);
    if (fields.size() != columns) {
      throw InputError(name, line, "row has " + std::to_string(fields.size()) + " columns",
                       std::to_string(columns) + " columns: " + std::string(header_of(columns)));
    }
    double v[kMaxColumns] = {};
    for (std::size_t c = 0; c < columns; ++c) {
      if (c != 1 && c != kHandColumn) v[c] = parse_number(fields[c], name, line, c);
    }
    const std::string tool(fields[1]);
    if (tool.empty()) {
      throw InputError(name, line, "column 'tool' is empty", "a tool name from the scene");
    }
    const double t = v[0];
    if (t < 0.0) {
      throw InputError(name, line, "column 't': time " + std::string(fields[0]) + " is negative",
                       "a time in s >= 0");
    }

    // Orientation: normalized; a norm far from 1 is a typo, not a rounding error.
    const Quat q(v[5], v[6], v[7], v[8]);
    const double norm = q.norm();
    if (norm < 0.5 || norm > 1.5) {
      std::ostringstream msg;
      msg << "quaternion (qw,qx,qy,qz) has norm " << norm;
      throw InputError(name, line, msg.str(), "a unit quaternion (norm within [0.5, 1.5])");
    }
    const double jaw = v[9];
    if (jaw < 0.0 || jaw > std::numbers::pi) {
      throw InputError(name, line, "column 'jaw': " + std::string(fields[9]) + " out of range",
                       "a jaw opening angle in rad within [0, pi]");
    }

    const double buttons = v[10];
    if (buttons < 0.0 || buttons > 65535.0 || buttons != std::floor(buttons)) {
      throw InputError(name, line,
                       "column 'buttons': " + std::string(fields[10]) + " is not a button mask",
                       "an integer 0..65535 (bit 0 clutch, bit 1 cautery pedal, bit 2 handle "
                       "button)");
    }

    // Append to the tool's rows; time must not go backwards within one tool.
    std::size_t k = 0;
    if (const auto found = path.index_of(tool)) {
      k = *found;
    } else {
      k = path.tools.size();
      path.tools.push_back(tool);
      path.samples.emplace_back();
      last_line.push_back(0);
    }
    auto& rows = path.samples[k];
    if (!rows.empty() && t < rows.back().time_s) {
      std::ostringstream msg;
      msg << "time " << t << " s of tool '" << tool << "' goes backwards (line " << last_line[k]
          << " has " << rows.back().time_s << " s)";
      throw InputError(name, line, msg.str(), "times non-decreasing per tool");
    }
    ToolState s;
    s.tick = rows.size();
    s.time_s = t;
    s.tip_m = {v[2], v[3], v[4]};
    s.quat_wxyz = {v[5] / norm, v[6] / norm, v[7] / norm, v[8] / norm};
    s.jaw_rad = jaw;
    s.buttons = static_cast<std::uint32_t>(buttons);
    if (columns == kMaxColumns) s.buttons |= parse_hand(fields[kHandColumn], name, line);
    rows.push_back(s);
    last_line[k] = line;
  }

  if (!have_header) {
    throw InputError(name, 0, "empty tool path", "the header " + std::string(kHeader));
  }
  if (path.tools.empty()) {
    throw InputError(name, line, "tool path has a header but no rows",
                     "at least one row t,tool,px,py,pz,qw,qx,qy,qz,jaw");
  }
  check_hands(path);
  return path;
}

ToolPath read_tool_path(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw InputError(file.string(), 0, "cannot open tool path", "a readable CSV file");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_tool_path_text(buffer.str(), file.string());
}

ToolState sample(const ToolPath& path, std::size_t tool, double t_s) {
  if (tool >= path.samples.size() || path.samples[tool].empty()) {
    throw std::out_of_range("tool path " + path.file + " has no tool #" + std::to_string(tool));
  }
  const auto& rows = path.samples[tool];

  // First row strictly after t: the segment is [hi - 1, hi].
  const auto it = std::upper_bound(rows.begin(), rows.end(), t_s,
                                   [](double t, const ToolState& s) { return t < s.time_s; });
  ToolState out;
  if (it == rows.begin()) {
    out = rows.front();
  } else if (it == rows.end()) {
    out = rows.back();
  } else {
    const ToolState& a = *(it - 1);
    const ToolState& b = *it;
    const double u = (t_s - a.time_s) / (b.time_s - a.time_s);  // b.time_s > a.time_s
    out = a;
    for (int i = 0; i < 3; ++i) out.tip_m[i] = a.tip_m[i] + u * (b.tip_m[i] - a.tip_m[i]);
    out.jaw_rad = a.jaw_rad + u * (b.jaw_rad - a.jaw_rad);
    const Quat qa(a.quat_wxyz[0], a.quat_wxyz[1], a.quat_wxyz[2], a.quat_wxyz[3]);
    const Quat qb(b.quat_wxyz[0], b.quat_wxyz[1], b.quat_wxyz[2], b.quat_wxyz[3]);
    const Quat q = qa.slerp(u, qb).normalized();  // Eigen's slerp takes the shortest arc
    out.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  }
  out.time_s = t_s;
  out.tick = it == rows.begin() ? 0 : static_cast<std::uint64_t>(it - rows.begin() - 1);
  return out;  // buttons: the row's at or before t_s (a button is pressed or not)
}

ToolState sample(const ToolPath& path, std::string_view tool, double t_s) {
  const auto k = path.index_of(tool);
  if (!k) {
    throw std::out_of_range("tool path " + path.file + " has no tool '" + std::string(tool) + "'");
  }
  return sample(path, *k, t_s);
}

}  // namespace serosa
