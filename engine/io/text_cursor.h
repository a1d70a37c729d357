// TextCursor: a token reader over a whole file held in memory, with 1-based line tracking, for the
// mesh readers (private to engine/io). Numbers are parsed with std::from_chars (no iostreams, no
// locale). Every failure throws InputError naming the file and the line of the offending token.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace serosa::io {

class TextCursor {
 public:
  /// @param text    the whole file
  /// @param file    the name used in errors
  /// @param comment a character that starts a comment running to the end of the line ('\0': none)
  TextCursor(std::string_view text, std::string file, char comment = '\0');

  [[nodiscard]] const std::string& file() const noexcept { return m_file; }
  /// Line of the read position (1-based).
  [[nodiscard]] std::int64_t line() const noexcept { return m_line; }
  /// Line of the last token returned (1-based).
  [[nodiscard]] std::int64_t token_line() const noexcept { return m_token_line; }

  /// Skips whitespace, blank lines and comments; true when nothing but those is left.
  [[nodiscard]] bool at_end();
  /// The next token, on this line or a later one; fails at end of file.
  std::string_view token(std::string_view expected);
  /// The next token, or an empty view at end of file (callers build their message only then).
  std::string_view try_token();
  /// Throws InputError "unexpected end of file" at the last line.
  [[noreturn]] void fail_eof(std::string_view expected) const;
  /// The next token on the current line; fails when the line ends first.
  std::string_view token_on_line(std::string_view expected);
  /// True when another token follows on the current line.
  [[nodiscard]] bool more_on_line();
  /// Requires the current line to hold nothing more, then moves to the next line.
  void end_line(std::string_view what);
  /// Moves past the end of the current line, whatever it holds.
  void skip_line();
  /// The rest of the current line (without its line break, not trimmed); moves to the next line.
  std::string_view rest_of_line();

  /// A saved read position, to look ahead and come back.
  struct Mark {
    std::size_t pos;
    std::int64_t line;
    std::int64_t token_line;
  };
  [[nodiscard]] Mark mark() const noexcept { return {m_pos, m_line, m_token_line}; }
  void reset(const Mark& m) noexcept {
    m_pos = m.pos;
    m_line = m.line;
    m_token_line = m.token_line;
  }

  /// Parses a whole token as an integer (a leading '+' is allowed); fails at token_line().
  [[nodiscard]] std::int64_t to_int(std::string_view tok, std::string_view expected) const;
  /// Parses a whole token as a double ("nan" and "inf" pass: validation reports them).
  [[nodiscard]] double to_double(std::string_view tok, std::string_view expected) const;

  std::int64_t next_int(std::string_view expected) { return to_int(token(expected), expected); }
  std::int64_t int_on_line(std::string_view expected) {
    return to_int(token_on_line(expected), expected);
  }
  double next_double(std::string_view expected) { return to_double(token(expected), expected); }
  double double_on_line(std::string_view expected) {
    return to_double(token_on_line(expected), expected);
  }

  /// Throws InputError at token_line().
  [[noreturn]] void fail(const std::string& message, std::string_view expected = {}) const;
  /// Throws InputError at the given line.
  [[noreturn]] void fail_at(std::int64_t line, const std::string& message,
                            std::string_view expected = {}) const;

 private:
  void skip_spaces();            // spaces, tabs, CR and a comment; stops at '\n'
  void skip_spaces_and_lines();  // the same, across line breaks
  [[nodiscard]] std::string_view take_token();
  [[nodiscard]] std::int64_t eof_line() const noexcept;

  std::string_view m_text;
  std::string m_file;
  char m_comment;
  std::size_t m_pos = 0;
  std::int64_t m_line = 1;
  std::int64_t m_token_line = 1;
};

/// A token as it may appear in an error message: at most 40 characters, non-printing bytes as '?'.
[[nodiscard]] std::string quote_token(std::string_view tok);

/// Case-insensitive ASCII comparison (VTK keywords).
[[nodiscard]] bool iequals(std::string_view a, std::string_view b) noexcept;

}  // namespace serosa::io
