// write_vtu: VTK XML UnstructuredGrid, ASCII, for ParaView: points at current positions, tets as
// VTK type 10, cell data "group", point data "rest" (m) and "velocity" (m/s).
#include <stdexcept>
#include <string>

#include "engine/io/mesh_io.h"
#include "engine/io/text_format.h"

namespace serosa {
namespace {

void append_vectors(std::string& out, const std::vector<Vec3>& values, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = i < values.size() ? values[i] : Vec3::Zero();
    out.append("          ");
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out.push_back(' ');
      io::append_double(out, p[k]);
    }
    out.push_back('\n');
  }
}

}  // namespace

void write_vtu(const std::filesystem::path& path, const TetMesh& mesh) {
  const std::size_t n = mesh.rest.size();
  const std::size_t m = mesh.tets.size();
  const std::string where = path.string() + ": ";
  if (mesh.group.size() != m)
    throw std::invalid_argument(where + "mesh.group and mesh.tets differ in size");
  // Current positions when the mesh has them, else rest positions.
  const std::vector<Vec3>& x = mesh.x.size() == n ? mesh.x : mesh.rest;

  std::string out;
  out.reserve(512 + n * 200 + m * 40);
  out.append("<?xml version=\"1.0\"?>\n");
  out.append(
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n");
  out.append("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"");
  io::append_int(out, static_cast<std::int64_t>(n));
  out.append("\" NumberOfCells=\"");
  io::append_int(out, static_cast<std::int64_t>(m));
  out.append("\">\n");

  out.append("      <PointData Vectors=\"velocity\">\n");
  out.append(
      "        <DataArray type=\"Float64\" Name=\"rest\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n");
  append_vectors(out, mesh.rest, n);
  out.append("        </DataArray>\n");
  out.append(
      "        <DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n");
  append_vectors(out, mesh.v, n);
  out.append("        </DataArray>\n      </PointData>\n");

  out.append("      <CellData Scalars=\"group\">\n");
  out.append("        <DataArray type=\"Int32\" Name=\"group\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < m; ++k) {
    out.append(k % 16 == 0 ? "          " : " ");
    io::append_int(out, mesh.group[k]);
    if (k % 16 == 15 || k + 1 == m) out.push_back('\n');
  }
  out.append("        </DataArray>\n      </CellData>\n");

  out.append(
      "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" "
      "NumberOfComponents=\"3\" format=\"ascii\">\n");
  append_vectors(out, x, n);
  out.append("        </DataArray>\n      </Points>\n");

  out.append(
      "      <Cells>\n        <DataArray type=\"Int64\" Name=\"connectivity\" "
      "format=\"ascii\">\n");
  for (std::size_t k = 0; k < m; ++k) {
    out.append("          ");
    for (int j = 0; j < 4; ++j) {
      const std::int32_t id = mesh.tets[k][static_cast<std::size_t>(j)];
      if (id < 0 || static_cast<std::size_t>(id) >= n) {
        throw std::invalid_argument(where + "tet " + std::to_string(k) + " refers to node " +
                                    std::to_string(id) + " of " + std::to_string(n));
      }
      if (j > 0) out.push_back(' ');
      io::append_int(out, id);
    }
    out.push_back('\n');
  }
  out.append(
      "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" "
      "format=\"ascii\">\n");
  for (std::size_t k = 0; k < m; ++k) {
    out.append(k % 16 == 0 ? "          " : " ");
    io::append_int(out, 4 * static_cast<std::int64_t>(k + 1));
    if (k % 16 == 15 || k + 1 == m) out.push_back('\n');
  }
  out.append(
      "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" "
      "format=\"ascii\">\n");
  for (std::size_t k = 0; k < m; ++k) {
    out.append(k % 16 == 0 ? "          10" : " 10");
    if (k % 16 == 15 || k + 1 == m) out.push_back('\n');
  }
  out.append("        </DataArray>\n      </Cells>\n");
  out.append("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  io::write_text_file(path, out);
}

}  // namespace serosa
