#include "engine/io/text_cursor.h"

#include <charconv>
#include <system_error>
#include <utility>

#include "engine/input_error.h"

namespace serosa::io {
namespace {

bool is_space(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace

std::string quote_token(std::string_view tok) {
  std::string s = "'";
  const std::size_t n = tok.size() < 40 ? tok.size() : 40;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    s.push_back(c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?');
  }
  if (tok.size() > n) s.append("...");
  s.push_back('\'');
  return s;
}

bool iequals(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i];
    char y = b[i];
    if (x >= 'a' && x <= 'z') x = static_cast<char>(x - 'a' + 'A');
    if (y >= 'a' && y <= 'z') y = static_cast<char>(y - 'a' + 'A');
    if (x != y) return false;
  }
  return true;
}

TextCursor::TextCursor(std::string_view text, std::string file, char comment)
    : m_text(text), m_file(std::move(file)), m_comment(comment) {}

void TextCursor::skip_spaces() {
  while (m_pos < m_text.size()) {
    const char c = m_text[m_pos];
    if (is_space(c)) {
      ++m_pos;
    } else if (m_comment != '\0' && c == m_comment) {
      while (m_pos < m_text.size() && m_text[m_pos] != '\n') ++m_pos;
    } else {
      break;
    }
  }
}

void TextCursor::skip_spaces_and_lines() {
  for (;;) {
    skip_spaces();
    if (m_pos < m_text.size() && m_text[m_pos] == '\n') {
      ++m_pos;
      ++m_line;
    } else {
      return;
    }
  }
}

std::int64_t TextCursor::eof_line() const noexcept {
  // At the end of a file that ends with a line break, the last line is the one before.
  if (!m_text.empty() && m_pos >= m_text.size() && m_text.back() == '\n' && m_line > 1) {
    return m_line - 1;
  }
  return m_line;
}

std::string_view TextCursor::take_token() {
  const std::size_t start = m_pos;
  while (m_pos < m_text.size()) {
    const char c = m_text[m_pos];
    if (is_space(c) || c == '\n' || (m_comment != '\0' && c == m_comment)) break;
    ++m_pos;
  }
  m_token_line = m_line;
  return m_text.substr(start, m_pos - start);
}

bool TextCursor::at_end() {
  skip_spaces_and_lines();
  return m_pos >= m_text.size();
}

std::string_view TextCursor::token(std::string_view expected) {
  if (at_end()) {
    fail_at(eof_line(), "unexpected end of file (truncated?)", expected);
  }
  return take_token();
}

std::string_view TextCursor::try_token() {
  if (at_end()) return {};
  return take_token();
}

void TextCursor::fail_eof(std::string_view expected) const {
  fail_at(eof_line(), "unexpected end of file (truncated?)", expected);
}

std::string_view TextCursor::token_on_line(std::string_view expected) {
  skip_spaces();
  if (m_pos >= m_text.size()) {
    fail_at(eof_line(), "unexpected end of file (truncated?)", expected);
  }
  if (m_text[m_pos] == '\n') fail_at(m_line, "line ends too early", expected);
  return take_token();
}

bool TextCursor::more_on_line() {
  skip_spaces();
  return m_pos < m_text.size() && m_text[m_pos] != '\n';
}

void TextCursor::end_line(std::string_view what) {
  if (more_on_line()) {
    const std::string_view extra = take_token();
    std::string msg = "unexpected ";
    msg.append(quote_token(extra));
    msg.append(" after ");
    msg.append(what);
    fail(msg, "end of line");
  }
  if (m_pos < m_text.size()) {  // the '\n'
    ++m_pos;
    ++m_line;
  }
}

void TextCursor::skip_line() { (void)rest_of_line(); }

std::string_view TextCursor::rest_of_line() {
  const std::size_t start = m_pos;
  while (m_pos < m_text.size() && m_text[m_pos] != '\n') ++m_pos;
  std::size_t end = m_pos;
  if (end > start && m_text[end - 1] == '\r') --end;
  m_token_line = m_line;
  if (m_pos < m_text.size()) {
    ++m_pos;
    ++m_line;
  }
  return m_text.substr(start, end - start);
}

std::int64_t TextCursor::to_int(std::string_view tok, std::string_view expected) const {
  std::string_view s = tok;
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range)
    fail("integer " + quote_token(tok) + " out of range", expected);
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) {
    fail(quote_token(tok) + " is not an integer", expected);
  }
  return value;
}

double TextCursor::to_double(std::string_view tok, std::string_view expected) const {
  std::string_view s = tok;
  if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range)
    fail("number " + quote_token(tok) + " out of range", expected);
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) {
    fail(quote_token(tok) + " is not a number", expected);
  }
  return value;
}

void TextCursor::fail(const std::string& message, std::string_view expected) const {
  fail_at(m_token_line, message, expected);
}

void TextCursor::fail_at(std::int64_t line, const std::string& message,
                         std::string_view expected) const {
  throw InputError(m_file, line, message, std::string(expected));
}

}  // namespace serosa::io
