// InputError: bad input from a file (mesh, scene, tool path, recording), naming where and what.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace serosa {

/// Thrown by every reader on bad input. what() reads "FILE:LINE: message (expected ...)".
/// line is 1-based; 0 when the error is about the file as a whole (missing, empty, binary).
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::int64_t line, std::string message, std::string expected = {});

  [[nodiscard]] const std::string& file() const noexcept { return m_file; }
  [[nodiscard]] std::int64_t line() const noexcept { return m_line; }
  [[nodiscard]] const std::string& message() const noexcept { return m_message; }
  [[nodiscard]] const std::string& expected() const noexcept { return m_expected; }

 private:
  std::string m_file;
  std::int64_t m_line;
  std::string m_message;
  std::string m_expected;
};

}  // namespace serosa
