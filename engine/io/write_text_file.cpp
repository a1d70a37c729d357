#include <fstream>
#include <stdexcept>

#include "engine/io/text_format.h"

namespace serosa::io {

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path.string() + ": cannot open file for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": write failed (disk full?)");
}

}  // namespace serosa::io
