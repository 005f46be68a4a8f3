#include "io/vtk_writer.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace dentsph::io {

namespace {

// Collects the appended-data block: each array is a UInt64 byte count followed by its bytes.
class Appended {
 public:
  template <class T>
  std::uint64_t add(const std::vector<T>& values) {
    const std::uint64_t offset = bytes_.size();
    const std::uint64_t n = values.size() * sizeof(T);
    append(&n, sizeof n);
    append(values.data(), n);
    return offset;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  void append(const void* p, std::size_t n) { bytes_.append(static_cast<const char*>(p), n); }
  std::string bytes_;
};

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(v.size() * 3);
  for (const Vec3& a : v) out.insert(out.end(), {a.x, a.y, a.z});
  return out;
}

std::string array_tag(const char* type, const char* name, int components, std::uint64_t offset) {
  return fmt::format(R"(<DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)", type,
                     name, components, offset);
}

}  // namespace

void write_vtu(const std::filesystem::path& file, const State& s) {
  const std::size_t n = s.size();
  Appended data;
  const auto o_points = data.add(flatten(s.pos));
  const auto o_vel = data.add(flatten(s.vel));
  const auto o_rho = data.add(s.rho);
  const auto o_p = data.add(s.pressure);
  std::vector<std::int32_t> role(n), bonds(n);
  std::vector<std::uint32_t> ids(s.id);
  for (std::size_t i = 0; i < n; ++i) {
    role[i] = std::int32_t(s.role[i]);
    bonds[i] = s.bonds.count(s.id[i]);
  }
  const auto o_role = data.add(role);
  const auto o_bonds = data.add(bonds);
  const auto o_id = data.add(ids);
  // The cure state (kept by id): degree of conversion and radiant exposure in J/cm^2.
  std::vector<double> conversion(n), dose(n);
  for (std::size_t i = 0; i < n; ++i) {
    conversion[i] = s.cure.alpha[s.id[i]];
    dose[i] = s.cure.dose[s.id[i]] / 1e4;
  }
  const auto o_conversion = data.add(conversion);
  const auto o_dose = data.add(dose);
  std::vector<std::int64_t> conn(n), offs(n);
  for (std::size_t i = 0; i < n; ++i) conn[i] = std::int64_t(i), offs[i] = std::int64_t(i + 1);
  const auto o_conn = data.add(conn);
  const auto o_offs = data.add(offs);
  const auto o_types = data.add(std::vector<std::uint8_t>(n, 1));  // VTK_VERTEX

  std::string xml;
  xml += R"(<?xml version="1.0"?>)" "\n";
  xml += R"(<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">)" "\n";
  xml += fmt::format("<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  xml += "<PointData Scalars=\"density\" Vectors=\"velocity\">\n";
  xml += array_tag("Float64", "velocity", 3, o_vel) + "\n";
  xml += array_tag("Float64", "density", 1, o_rho) + "\n";
  xml += array_tag("Float64", "pressure", 1, o_p) + "\n";
  xml += array_tag("Int32", "role", 1, o_role) + "\n";  // 0 material, 1 boundary, 2 tool
  xml += array_tag("Int32", "bond_count", 1, o_bonds) + "\n";
  xml += array_tag("UInt32", "id", 1, o_id) + "\n";
  xml += array_tag("Float64", "conversion", 1, o_conversion) + "\n";
  xml += array_tag("Float64", "dose_J_per_cm2", 1, o_dose) + "\n";
  xml += "</PointData>\n<Points>\n" + array_tag("Float64", "position", 3, o_points) + "\n</Points>\n";
  xml += "<Cells>\n" + array_tag("Int64", "connectivity", 1, o_conn) + "\n" + array_tag("Int64", "offsets", 1, o_offs) +
         "\n" + array_tag("UInt8", "types", 1, o_types) + "\n</Cells>\n";
  xml += "</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";

  std::ofstream out(file, std::ios::binary);
  out << xml << data.bytes() << "\n</AppendedData>\n</VTKFile>\n";
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the snapshot", file.string()));
}

void write_vtp(const std::filesystem::path& file, const SurfaceMesh& mesh) {
  // Single precision and 32-bit indices: the mesh comes from a single-precision level set, and a
  // surface is written beside every snapshot.
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  Appended data;
  std::vector<float> points;
  points.reserve(3 * nv);
  for (const Vec3& v : mesh.vertices) points.insert(points.end(), {float(v.x), float(v.y), float(v.z)});
  const auto o_points = data.add(points);
  std::vector<std::int32_t> conn, offs(nt);
  conn.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) conn.push_back(std::int32_t(v));
    offs[t] = std::int32_t(3 * (t + 1));
  }
  const auto o_conn = data.add(conn);
  const auto o_offs = data.add(offs);
  std::string xml;
  xml += R"(<?xml version="1.0"?>)" "\n";
  xml += R"(<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)" "\n";
  xml += fmt::format("<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                     "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                     nv, nt);
  xml += "<Points>\n" + array_tag("Float32", "position", 3, o_points) + "\n</Points>\n";
  xml += "<Polys>\n" + array_tag("Int32", "connectivity", 1, o_conn) + "\n" + array_tag("Int32", "offsets", 1, o_offs) +
         "\n</Polys>\n";
  xml += "</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::ofstream out(file, std::ios::binary);
  out << xml << data.bytes() << "\n</AppendedData>\n</VTKFile>\n";
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the surface", file.string()));
}

void PvdIndex::add(double t, const std::string& relative_file) {
  entries_.emplace_back(t, relative_file);
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const auto& [time, name] : entries_)
    xml += fmt::format("<DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, name);
  xml += "</Collection>\n</VTKFile>\n";
  std::ofstream out(file_);
  out << xml;
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the snapshot index", file_.string()));
}

}  // namespace dentsph::io
