// Running another program (gnuplot) through the shell, and quoting for the shell and for gnuplot.
#pragma once

#include <string>

namespace serosa {

/// 'text' for the POSIX shell.
[[nodiscard]] std::string shell_quote(const std::string& text);
/// 'text' for gnuplot (single-quoted: only '' is special).
[[nodiscard]] std::string gp_quote(const std::string& text);

struct Command {
  int code = -1;       ///< exit status; -1 when it did not run or did not exit
  std::string output;  ///< stdout and stderr together
};
/// Runs `command` through /bin/sh, capturing its output.
[[nodiscard]] Command run_command(const std::string& command);
/// The text up to its first newline.
[[nodiscard]] std::string first_line(const std::string& text);

}  // namespace serosa
