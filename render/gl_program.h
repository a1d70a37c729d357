// GlProgram: a linked GLSL program object, compiled from sources (requires a current context).
#pragma once

#include <string>
#include <vector>

namespace serosa::render {

/// One shader stage's source: `stage` is the GL enum (GL_VERTEX_SHADER, ...), `name` is used in
/// error messages.
struct ShaderSource {
  unsigned int stage = 0;
  const char* text = nullptr;
  const char* name = "";
};

/// A linked program; deletes it on destruction. The GL context must be current for every call.
class GlProgram {
 public:
  /// Compiles and links the stages.
  /// @throws std::runtime_error with the stage's name and the driver's info log on failure
  explicit GlProgram(const std::vector<ShaderSource>& stages);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  GlProgram(GlProgram&&) = delete;
  GlProgram& operator=(GlProgram&&) = delete;

  [[nodiscard]] unsigned int id() const { return id_; }
  /// The uniform's location, -1 when the program has none by that name (optimised away).
  [[nodiscard]] int uniform(const char* name) const;

 private:
  unsigned int id_ = 0;
};

}  // namespace serosa::render
