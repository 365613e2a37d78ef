// Closed-form test shapes, built in code so every expected figure can be derived by hand.
// All are closed and outward-oriented unless the name says otherwise; units are mm; +Z is up
// and every shape rests on z = 0 unless stated.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "core/geometry/surface.h"

namespace slim::test {

// Axis-aligned box [x0,x1] x [y0,y1] x [z0,z1], 12 triangles.
Surface box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Union of boxes as one surface (separate components; touching boxes share no vertices).
Surface merge(const Surface& a, const Surface& b);

// Merges vertices at identical positions (exact compare: shapes are built from exact values), so
// touching shapes share their vertices.
Surface weld(const Surface& s);

// A slab [-w/2, w/2]² × [z, z + 2] on a 4 × 4 stem from the plate (the stem reaches into it): two
// boxes, merged.
Surface slab_on_stem(double width, double z);

// A T: a stem [-s/2,s/2]^2 x [0,h] and a bar of length L, width s, thickness t on top of it,
// built as one closed manifold (no internal faces). Risky area at any alpha < 90: the two arm
// undersides, 2 * (L - s)/2 * s = (L - s) * s.
struct TShape {
  double stem = 10, height = 20, bar_length = 50, bar_thickness = 6;
};
Surface t_shape(const TShape& p = {});
double t_shape_arm_underside_area(const TShape& p = {});

// Icosahedron subdivided `levels` times and projected onto the sphere of radius r about c.
Surface icosphere(int levels, double r = 10.0, const Eigen::Vector3d& c = Eigen::Vector3d(0, 0, 10));

// The lower or upper half of an icosphere: an open surface (not closed).
Surface open_hemisphere(int levels, double r = 10.0, bool lower = true);

// The box [-10, 10]² × [0, 20] on a 1.25 mm grid of faces, with a window [0, width] × [6.25, 13.75]
// left open in its side y = -10 (and with windows = 2 also in y = +10): an open surface whose
// slices through the windows have gaps `width` wide. width: a multiple of 1.25 mm, up to 10.
Surface box_with_windows(double width, int windows = 1);

// Two unit cubes of side a that share exactly one edge (non-manifold edge, 4 faces on it).
Surface two_cubes_sharing_edge(double a = 10.0);

// Apply x -> R x + t to every vertex.
Surface transformed(const Surface& s, const Eigen::Matrix3d& R, const Eigen::Vector3d& t = Eigen::Vector3d::Zero());

// Rotation about a unit axis by an angle in radians.
Eigen::Matrix3d axis_angle(const Eigen::Vector3d& axis, double radians);

// A rotation drawn uniformly (a normalised Gaussian quaternion) from gen.
Eigen::Matrix3d random_rotation(std::mt19937_64& gen);

// Path of the sample bunny written by scripts/setup.sh (+Z up, resting on z = 0).
std::string sample_bunny_path();

#ifdef SLIM_TESTS_HAVE_VCG
// Loads any mesh VCG reads (PLY, STL, OBJ, OFF) into a Surface; throws on failure.
Surface load_mesh(const std::string& path);
// The sample bunny, loaded once.
const Surface& sample_bunny();
#endif

// The length of the bounding box's diagonal (mm).
double bbox_diagonal(const Surface& s);

}  // namespace slim::test

namespace slim::test {

// A solid of revolution about +Z: the profile (r, z) runs from a point on the axis at the bottom
// up to one on the axis at the top (faces outward), turned in `segments` steps.
Surface revolve(const std::vector<Eigen::Vector2d>& profile, int segments);

// A foot: a cylinder of radius 3 on the plate whose profile (r, z) flares out through the points
// given and then rises as a wall to z = 5 (revolve(), 64 segments).
Surface flared_foot(const std::vector<Eigen::Vector2d>& flare);

// A mushroom: a solid of revolution about +Z, stem radius 3 and height 10 on the plate, with a
// cap of radius 10 whose underside (z from 10 at the stem to 11 at the rim) overhangs.
Surface mushroom(int segments = 48);

// A simple polygon in the XZ plane (counter-clockwise in (x, z)) extruded along Y from y0 to y1.
Surface prism_xz(const std::vector<Eigen::Vector2d>& profile, double y0, double y1);

// An arch: an extruded inverted U, 30 wide, 20 high, 10 deep, standing on two legs, with a
// semicircular opening of radius 10 (its upper half is the overhang).
Surface arch(int arc_segments = 24);

// A mushroom designed for printing: stem radius 3 rising to z = 8, a cap of radius 10 whose
// underside climbs at 49 degrees from the horizontal (z 8 -> 16: self-supporting at 45), a rim up
// to 17 and the same low dome as mushroom() above it (to 20). Cap up it needs no support at all;
// upside down it balances on the dome's apex over a shallow, overhanging dome.
Surface printable_mushroom(int segments = 48);

// An L-bracket: a base plate [0, base] x [-width/2, width/2] x [0, thickness] on the plate and an
// upright [0, thickness] x ... x [0, upright] at x = 0, one closed manifold. Its largest flat face
// is the base's underside (base x width), then the upright's back (upright x width), then the
// L-shaped sides. Nothing overhangs as built.
struct LBracket {
  double base = 50, upright = 30, width = 30, thickness = 5;
};
Surface l_bracket(const LBracket& p = {});

}  // namespace slim::test

namespace slim::test {

// A named shape with the print direction to use for it: the cube, the sphere, the T, an open
// hemisphere, two cubes sharing one edge, the T turned arbitrarily with a tilted print direction,
// and the sample bunny when VCG can load it. `closed` says whether it encloses a volume.
struct ShapeCase {
  std::string name;
  Surface surface;
  Eigen::Vector3d print_direction = Eigen::Vector3d::UnitZ();
  bool closed = true;
};
std::vector<ShapeCase> domain_cases();

// One triangle (a, b, c): the simplest open surface.
Surface triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace slim::test

namespace slim::test {
// Splits every triangle into 4 at its edge midpoints, `levels` times (shared edges share their
// midpoint, so a closed surface stays closed). The shape is unchanged; only its tessellation is
// finer, as a scanned or remeshed part would be.
Surface refined(const Surface& s, int levels);
}  // namespace slim::test
