#include "engine/input_error.h"

#include <utility>

namespace serosa {
namespace {

std::string format(const std::string& file, std::int64_t line, const std::string& message,
                   const std::string& expected) {
  // Appended piece by piece: g++ 12 reports a false -Wrestrict on operator+ chains at -O3.
  std::string s = file;
  if (line > 0) {
    s.append(":");
    s.append(std::to_string(line));
  }
  s.append(": ");
  s.append(message);
  if (!expected.empty()) {
    s.append(" (expected ");
    s.append(expected);
    s.append(")");
  }
  return s;
}

}  // namespace

InputError::InputError(std::string file, std::int64_t line, std::string message,
                       std::string expected)
    : std::runtime_error(format(file, line, message, expected)),
      m_file(std::move(file)),
      m_line(line),
      m_message(std::move(message)),
      m_expected(std::move(expected)) {}

}  // namespace serosa
