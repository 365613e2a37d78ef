// What goes in comes out, through the support-slim CLI: the output has the input's
// vertex list and face list in the same order, with no welding, and the attributes the input
// carries; STL is welded and says so; malformed files are refused in one line; the summary has no
// empty field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "core/geometry/surface.h"
#include "mesh_io/mesh_io.h"
#include "support/attributed_mesh.h"
#include "support/bad_inputs.h"
#include "support/shapes.h"

using namespace slim;
using test::mentions;
using test::run_cli;
namespace fs = std::filesystem;

namespace {

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Every summary line is "  <label>  <value>" with a value (or a continuation): no field is left
// empty, as "solver" once was at --iterations 0.
void expect_no_empty_field(const std::string& summary) {
  std::istringstream lines(summary);
  std::string line;
  const std::regex empty_field(R"((^\s*\S+\s*$)|(\s$)|(:\s*$)|(\b(solver|in|of)\s*[;,)]))");
  while (std::getline(lines, line)) {
    if (line.rfind("support-slim: ", 0) == 0) continue;
    EXPECT_FALSE(std::regex_search(line, empty_field)) << "an empty field in: '" << line << "'\n" << summary;
  }
}

}  // namespace

TEST(CliFiles, PlyRoundTripsItsVertexAndFaceListsAndAttributesAtZeroIterations) {
  const fs::path dir = test::scratch();
  const test::AttributedMesh m = test::attributed_mesh();
  const fs::path in = dir / "parts.ply", out = dir / "parts_out.ply";
  test::write_attributed_ply(in.string(), m);
  const test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --iterations 0 --quiet --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const io::MeshFile back = io::read_mesh(out.string());
  // The arrays themselves, against what was written (positions are small integers, exact in the
  // file's floats; the normals and texture coordinates were floats).
  ASSERT_EQ(back.surface.V.rows(), m.surface.V.rows());
  EXPECT_EQ(back.surface.V, m.surface.V);
  EXPECT_EQ(back.surface.F, m.surface.F);
  EXPECT_EQ(back.vertex.colour, m.colour);
  EXPECT_EQ(back.vertex.texcoord.cast<float>(), m.texcoord.cast<float>());
  EXPECT_EQ(back.vertex.normal.cast<float>(), m.normal.cast<float>());  // nothing moved: the file's own
  // The copies are still there, each where it was.
  EXPECT_EQ(back.surface.V.row(m.seam_copy), back.surface.V.row(m.seam_original));
  EXPECT_EQ(back.surface.V.row(m.coincident_corner), m.surface.V.row(m.coincident_corner));
  // What the run replaces: face quality, colour and selection.
  EXPECT_EQ(back.face.quality.size(), m.surface.F.rows());
  EXPECT_EQ(back.face.colour.rows(), m.surface.F.rows());
  EXPECT_EQ(back.face.selected.size(), static_cast<size_t>(m.surface.F.rows()));

  EXPECT_NE(r.out.find("mesh            " + std::to_string(m.surface.V.rows()) + " vertices, " +
                       std::to_string(m.surface.F.rows()) + " faces, written back as read"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("3 vertices repeat an earlier one's position"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("solver none (no iteration ran)"), std::string::npos) << r.out;
  expect_no_empty_field(r.out);
  fs::remove_all(dir);
}

TEST(CliFiles, SlimmingMovesCopiesTogetherAndKeepsTheListsAndAttributes) {
  const fs::path dir = test::scratch();
  const test::AttributedMesh m = test::attributed_mesh();
  const fs::path in = dir / "parts.ply", out = dir / "parts_out.ply";
  test::write_attributed_ply(in.string(), m);
  const test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --iterations 8 --dir 1.4,0,1 --quiet");
  // Printed along (1.4, 0, 1) the boxes' faces overhang by a few degrees: 8 small steps make them
  // safe (aimed 10 degrees past the threshold, 4 save nothing yet) and save support. (Upright
  // their flat undersides need 45 degrees, which no iterate of 8 reaches; along (0.8, 0.5, 1) the
  // boxes stand on their corners, whose columns stay whatever the faces do: either way the input
  // would come back untouched, and nothing here would be tested.)
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::MeshFile back = io::read_mesh(out.string());
  ASSERT_EQ(back.surface.V.rows(), m.surface.V.rows());
  EXPECT_EQ(back.surface.F, m.surface.F);
  EXPECT_EQ(back.vertex.colour, m.colour);
  EXPECT_EQ(back.vertex.texcoord.cast<float>(), m.texcoord.cast<float>());
  EXPECT_GT((back.surface.V - m.surface.V).rowwise().norm().maxCoeff(), 1e-3) << "the overhanging boxes moved\n" << r.out;
  // Coincident vertices are one point for the core: they move as one, so no seam opens.
  for (const auto& [a, b] : {std::pair{m.seam_copy, m.seam_original}, std::pair{m.unreferenced_copy, m.seam_original}})
    EXPECT_EQ(back.surface.V.row(a), back.surface.V.row(b));
  const Eigen::RowVector3d corner(20, 20, 20);
  for (Eigen::Index v = 0; v < m.surface.V.rows(); ++v) {
    if (m.surface.V.row(v) == corner) {
      EXPECT_EQ(back.surface.V.row(v), back.surface.V.row(m.coincident_corner)) << v;
    }
  }
  // The normals no longer fit the moved surface: recomputed, unit length.
  ASSERT_EQ(back.vertex.normal.rows(), m.surface.V.rows());
  const Eigen::VectorXd lengths = back.vertex.normal.rowwise().norm();
  for (Eigen::Index v = 0; v < m.surface.V.rows(); ++v) {
    if (v != m.unreferenced_copy && v != m.unreferenced_apart) {
      EXPECT_NEAR(lengths(v), 1.0, 1e-9) << v;
    }
  }
  expect_no_empty_field(r.out);
  fs::remove_all(dir);
}

TEST(CliFiles, ObjComesBackLineForLineAndOffWithItsColours) {
  const fs::path dir = test::scratch();
  // An OBJ with everything the format holds: groups, materials, colours, texture coordinates,
  // normals, a polygon, relative indices, a line and a comment. At 0 iterations it comes back
  // byte for byte.
  const std::string obj =
      "# parts\nmtllib parts.mtl\no part\nv 0 0 0 1 0 0\nv 10 0 0 0 1 0\nv 10 10 0 0 0 1\nv 0 10 0 1 1 0\n"
      "v 5 5 8.25 0.5 0.5 0.5\nv 0 0 0 1 0 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 -1\nvn 0 0 1\ng base\n"
      "usemtl grey\ns off\nf 1/1/1 4/4/1 3/3/1 2/2/1\ng roof\nf 6/1/2 2/2/2 5/3/2\nf -5/2/2 -4/3/2 -2/4/2\n"
      "f 3//2 4//2 5//2\nf 4 1 5\nl 1 5\n";
  const fs::path in = dir / "parts.obj", out = dir / "parts_out.obj";
  std::ofstream(in, std::ios::binary) << obj;
  test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --iterations 0 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(file_text(out), obj);

  // The same part as OFF with vertex colours and normals: the lists and colours come back; the
  // faces carry the run's colour ramp.
  const fs::path off = dir / "parts.off", off_out = dir / "parts_out.off";
  const io::MeshFile read_obj = io::read_mesh(in.string());
  ASSERT_EQ(read_obj.vertex.colour.rows(), 6);
  io::MeshFile as_off = read_obj;
  as_off.obj.reset();
  as_off.vertex.normal = Points::Zero(6, 3);
  as_off.vertex.normal.col(0).setOnes();
  io::write_mesh(off.string(), as_off, as_off.surface.V);
  r = run_cli("'" + off.string() + "' -o '" + off_out.string() + "' --iterations 0 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::MeshFile back = io::read_mesh(off_out.string());
  EXPECT_EQ(back.surface.V, read_obj.surface.V);
  EXPECT_EQ(back.surface.F, read_obj.surface.F);
  EXPECT_EQ(back.vertex.colour, read_obj.vertex.colour);
  EXPECT_EQ(back.vertex.normal, as_off.vertex.normal);
  EXPECT_EQ(back.face.colour.rows(), read_obj.surface.F.rows());
  fs::remove_all(dir);
}

TEST(CliFiles, StlIsWeldedAndTheSummarySaysHowMuch) {
  const fs::path dir = test::scratch();
  const Surface t = test::t_shape();
  const fs::path in = dir / "t.stl", out = dir / "t_out.ply";
  io::save_surface(in.string(), t);
  const test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --iterations 0 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(std::to_string(t.F.rows()) + " triangles; STL stores each corner apart: " +
                       std::to_string(3 * t.F.rows()) + " corners welded into " + std::to_string(t.V.rows()) + " vertices"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(io::read_mesh(out.string()).surface.V.rows(), t.V.rows());
  expect_no_empty_field(r.out);
  fs::remove_all(dir);
}

TEST(CliFiles, TheSummaryHasNoEmptyFieldWhenNothingOverhangsOrNothingIterates) {
  const fs::path dir = test::scratch();
  const fs::path in = dir / "box.ply", out = dir / "box_out.ply";
  io::save_surface(in.string(), test::box({0, 0, 0}, {10, 10, 10}));
  const test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no risky faces"), std::string::npos) << r.out;
  expect_no_empty_field(r.out);
  // And with the orientation search's lines, at 0 iterations.
  const test::CliRun o = run_cli("'" + in.string() + "' -o '" + out.string() + "' --orient --orient-effort fast --iterations 0 --quiet");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.out.find("orientation     print direction"), std::string::npos) << o.out;
  expect_no_empty_field(o.out);
  fs::remove_all(dir);
}

namespace {
class BadFileCli : public ::testing::TestWithParam<test::BadFile> {};
}  // namespace

// The file-level catalogue through the CLI: exit code 1, one line that names the file and the
// reason, no output written; within 1 GB of address space (a reader that allocated for a
// claimed count would die of it instead).
TEST_P(BadFileCli, IsRefusedInOneLineNamingTheFile) {
  const test::BadFile& f = GetParam();
  const fs::path dir = test::scratch();
  const fs::path in = dir / (f.name + "." + f.extension), out = dir / (f.name + "_out.ply");
  std::ofstream(in, std::ios::binary) << f.bytes;
  const test::CliRun r = run_cli("'" + in.string() + "' -o '" + out.string() + "' --quiet", 1024 * 1024);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;  // a bad input file
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // exactly one line
  EXPECT_EQ(r.err.rfind("support-slim: ", 0), 0u) << r.err;
  EXPECT_TRUE(mentions(r.err, in.string())) << r.err;
  EXPECT_TRUE(mentions(r.err, f.refusal)) << f.name << ": " << r.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadFileCli, ::testing::ValuesIn(test::bad_files()),
                         [](const ::testing::TestParamInfo<test::BadFile>& info) { return info.param.name; });
