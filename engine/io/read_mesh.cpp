// read_mesh and read_mesh_text: load the text, pick the reader (by extension or explicitly), parse,
// then validate (finish_mesh).
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "engine/input_error.h"
#include "engine/io/mesh_io.h"
#include "engine/io/raw_mesh.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return e;
}

MeshFormat format_from_extension(const fs::path& p) {
  const std::string e = lower_extension(p);
  if (e == ".msh") return MeshFormat::kGmsh;
  if (e == ".node" || e == ".ele") return MeshFormat::kTetGen;
  if (e == ".vtk") return MeshFormat::kVtk;
  return MeshFormat::kAuto;
}

// The whole file as a string; InputError (line 0) when it cannot be read.
std::string read_text(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st))
    throw InputError(path.string(), 0, "cannot open file: no such file", "an existing mesh file");
  if (fs::is_directory(st)) throw InputError(path.string(), 0, "is a directory", "a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path.string(), 0, "cannot open file for reading", "a readable mesh file");
  // Read in chunks: works for regular files and pipes alike.
  std::string text;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec) text.reserve(static_cast<std::size_t>(size));
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path.string(), 0, "read error", "a readable mesh file");
  return text;
}

TetMesh parse(const std::string& text, MeshFormat format, const std::string& name,
              const MeshReadOptions& options, MeshReadReport& report, const std::string& ele_text,
              const std::string& ele_name) {
  report = MeshReadReport{};
  io::check_text(text, name);
  io::RawMesh raw;
  switch (format) {
    case MeshFormat::kGmsh:
      raw = io::parse_gmsh(text, name, report);
      break;
    case MeshFormat::kVtk:
      raw = io::parse_vtk(text, name, report);
      break;
    case MeshFormat::kTetGen:
      io::check_text(ele_text, ele_name);
      raw = io::parse_tetgen(text, name, ele_text, ele_name, report);
      break;
    case MeshFormat::kAuto:
      throw InputError(name, 0, "cannot tell the mesh format",
                       "a .msh, .node, .ele or .vtk file, or a Gmsh or VTK header");
  }
  return io::finish_mesh(raw, options, report);
}

}  // namespace

TetMesh read_mesh(const std::filesystem::path& path, const MeshReadOptions& options,
                  MeshReadReport* report, MeshFormat format) {
  MeshReadReport local;
  MeshReadReport& r = report != nullptr ? *report : local;
  if (format == MeshFormat::kAuto) {
    format = format_from_extension(path);
    if (format == MeshFormat::kAuto) {
      throw InputError(path.string(), 0,
                       "unknown mesh file extension '" + path.extension().string() + "'",
                       ".msh (Gmsh), .node/.ele (TetGen) or .vtk (legacy VTK)");
    }
  }
  if (format == MeshFormat::kTetGen) {
    fs::path node = path;
    fs::path ele = path;
    node.replace_extension(".node");
    ele.replace_extension(".ele");
    const std::string node_text = read_text(node);
    const std::string ele_text = read_text(ele);
    return parse(node_text, format, node.string(), options, r, ele_text, ele.string());
  }
  return parse(read_text(path), format, path.string(), options, r, {}, {});
}

TetMesh read_mesh_text(const std::string& text, MeshFormat format, const std::string& name,
                       const MeshReadOptions& options, MeshReadReport* report,
                       const std::string& ele_text) {
  MeshReadReport local;
  MeshReadReport& r = report != nullptr ? *report : local;
  if (format == MeshFormat::kAuto) {
    // The name's extension first (as read_mesh), then the content.
    format = format_from_extension(name);
    if (format == MeshFormat::kAuto) {
      const std::size_t start = text.find_first_not_of(" \t\r\n");
      const std::string_view head =
          start == std::string::npos ? std::string_view() : std::string_view(text).substr(start);
      if (head.substr(0, 11) == "$MeshFormat") {
        format = MeshFormat::kGmsh;
      } else if (head.substr(0, 5) == "# vtk") {
        format = MeshFormat::kVtk;
      } else if (!ele_text.empty()) {
        format = MeshFormat::kTetGen;
      }
    }
  }
  fs::path ele_name(name);
  ele_name.replace_extension(".ele");
  return parse(text, format, name, options, r, ele_text, ele_name.string());
}

}  // namespace serosa
