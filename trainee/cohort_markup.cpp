#include "trainee/cohort_markup.h"

#include <cstdio>

namespace serosa::trainee {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string url_path(std::string_view path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '/' || c == '-' || c == '_' || c == '.' || c == '~';
    if (plain) {
      out += c;
    } else {
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return out;
}

std::string file_href(const std::filesystem::path& file, const std::filesystem::path& page_dir) {
  const std::filesystem::path f = std::filesystem::absolute(file).lexically_normal();
  const std::filesystem::path dir = std::filesystem::absolute(page_dir).lexically_normal();
  const std::filesystem::path shared = dir.parent_path();
  const std::filesystem::path inside = f.lexically_relative(shared);
  if (!shared.empty() && shared != shared.root_path() && !inside.empty() && *inside.begin() != "..")
    return url_path(f.lexically_relative(dir).generic_string());
  return std::string("file://") + url_path(f.generic_string());
}

std::string score_text(std::optional<double> score) {
  if (!score) return "\u2013";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", *score);
  std::string t = buf;
  if (t.size() > 2 && t.compare(t.size() - 2, 2, ".0") == 0) t.resize(t.size() - 2);  // "80"
  return t;
}

std::string date_text(const std::string& started_utc) {
  std::string d = started_utc;
  if (d.size() == 20 && d[10] == 'T' && d[19] == 'Z') {
    d[10] = ' ';
    d.replace(19, 1, " UTC");
  }
  return d;
}

}  // namespace serosa::trainee
