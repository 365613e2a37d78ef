#include "vtk_writer.h"

#include <fstream>
#include <stdexcept>

namespace slim::eval {
namespace {

std::ofstream open_vtk(const std::string& path, const std::string& title) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(7);
  out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET POLYDATA\n";
  return out;
}

void close_vtk(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

void write_vtk_mesh(const std::string& path, const Surface& s, const std::string& name, const Eigen::VectorXd& per_vertex) {
  if (per_vertex.size() != s.V.rows()) throw std::runtime_error("write_vtk_mesh: one value per vertex expected");
  std::ofstream out = open_vtk(path, "support-slimming mesh");
  out << "POINTS " << s.V.rows() << " double\n";
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) out << s.V(v, 0) << " " << s.V(v, 1) << " " << s.V(v, 2) << "\n";
  out << "POLYGONS " << s.F.rows() << " " << 4 * s.F.rows() << "\n";
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) out << "3 " << s.F(f, 0) << " " << s.F(f, 1) << " " << s.F(f, 2) << "\n";
  out << "POINT_DATA " << s.V.rows() << "\nSCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
  for (Eigen::Index v = 0; v < per_vertex.size(); ++v) out << per_vertex(v) << "\n";
  close_vtk(out, path);
}

void write_vtk_segments(const std::string& path, const Segments& segments, const std::string& name) {
  const size_t n = segments.from.size();
  if (segments.to.size() != n || segments.value.size() != n) throw std::runtime_error("write_vtk_segments: sizes disagree");
  std::ofstream out = open_vtk(path, "support-slimming tool path");
  out << "POINTS " << 2 * n << " double\n";
  for (size_t i = 0; i < n; ++i) {
    out << segments.from[i].x() << " " << segments.from[i].y() << " " << segments.from[i].z() << "\n";
    out << segments.to[i].x() << " " << segments.to[i].y() << " " << segments.to[i].z() << "\n";
  }
  out << "LINES " << n << " " << 3 * n << "\n";
  for (size_t i = 0; i < n; ++i) out << "2 " << 2 * i << " " << 2 * i + 1 << "\n";
  out << "CELL_DATA " << n << "\nSCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
  for (double v : segments.value) out << v << "\n";
  close_vtk(out, path);
}

}  // namespace slim::eval
