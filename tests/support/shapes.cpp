#include "support/shapes.h"

#include "support/source_paths.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace slim::test {

namespace {
Surface from_lists(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& f) {
  Surface s;
  s.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  s.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) s.V.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  for (size_t i = 0; i < f.size(); ++i) s.F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return s;
}

// One 1-to-4 midpoint split of every triangle; shared edges share their midpoint. The midpoints
// are pushed onto the unit sphere when asked (icosphere).
void split_in_four(std::vector<Eigen::Vector3d>& v, std::vector<Eigen::Vector3i>& f, bool onto_unit_sphere) {
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const Eigen::Vector3d m = (v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)]) / 2.0;
    v.push_back(onto_unit_sphere ? m.normalized() : m);
    return mid[key] = static_cast<int>(v.size()) - 1;
  };
  std::vector<Eigen::Vector3i> g;
  for (const auto& t : f) {
    const int a = midpoint(t(0), t(1)), b = midpoint(t(1), t(2)), c = midpoint(t(2), t(0));
    g.emplace_back(t(0), a, c);
    g.emplace_back(t(1), b, a);
    g.emplace_back(t(2), c, b);
    g.emplace_back(a, b, c);
  }
  f.swap(g);
}

// Extrudes a simple polygon given in the XZ plane (counter-clockwise in (x, z)) along Y from y0
// to y1. cap lists triangles of the polygon (indices into profile, counter-clockwise in (x, z)).
Surface extrude_xz(const std::vector<Eigen::Vector2d>& profile, const std::vector<Eigen::Vector3i>& cap,
                   double y0, double y1) {
  const int n = static_cast<int>(profile.size());
  std::vector<Eigen::Vector3d> v;
  for (double y : {y0, y1})
    for (const auto& p : profile) v.emplace_back(p.x(), y, p.y());
  std::vector<Eigen::Vector3i> f;
  for (const auto& t : cap) {
    f.emplace_back(t(0), t(1), t(2));              // y0 cap faces -Y
    f.emplace_back(n + t(0), n + t(2), n + t(1));  // y1 cap faces +Y
  }
  for (int i = 0; i < n; ++i) {  // side quads, outward = right of the counter-clockwise boundary
    const int p0 = i, q0 = (i + 1) % n, p1 = n + i, q1 = n + (i + 1) % n;
    f.emplace_back(p0, q1, q0);
    f.emplace_back(p0, p1, q1);
  }
  return from_lists(v, f);
}

}  // namespace

Surface weld(const Surface& s) {
  std::map<std::array<double, 3>, int> index;
  std::vector<Eigen::Vector3d> v;
  std::vector<int> remap(static_cast<size_t>(s.V.rows()));
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) {
    const std::array<double, 3> key{s.V(i, 0), s.V(i, 1), s.V(i, 2)};
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, static_cast<int>(v.size())).first;
      v.emplace_back(s.V.row(i).transpose());
    }
    remap[static_cast<size_t>(i)] = it->second;
  }
  std::vector<Eigen::Vector3i> f;
  for (Eigen::Index i = 0; i < s.F.rows(); ++i)
    f.emplace_back(remap[s.F(i, 0)], remap[s.F(i, 1)], remap[s.F(i, 2)]);
  return from_lists(v, f);
}

Surface box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const std::vector<Eigen::Vector2d> profile{{lo.x(), lo.z()}, {hi.x(), lo.z()}, {hi.x(), hi.z()}, {lo.x(), hi.z()}};
  return extrude_xz(profile, {{0, 1, 2}, {0, 2, 3}}, lo.y(), hi.y());
}

Surface merge(const Surface& a, const Surface& b) {
  Surface s;
  s.V.resize(a.V.rows() + b.V.rows(), 3);
  s.V << a.V, b.V;
  s.F.resize(a.F.rows() + b.F.rows(), 3);
  s.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return s;
}

Surface t_shape(const TShape& p) {
  const double s = p.stem / 2, h = p.height, L = p.bar_length / 2, top = p.height + p.bar_thickness;
  // Counter-clockwise T profile in (x, z); every corner is a profile vertex, so no T-junctions.
  const std::vector<Eigen::Vector2d> profile{{-s, 0}, {s, 0}, {s, h}, {L, h}, {L, top}, {-L, top}, {-L, h}, {-s, h}};
  const std::vector<Eigen::Vector3i> cap{{0, 1, 2}, {0, 2, 7},                       // stem
                                         {5, 6, 7}, {5, 7, 2}, {5, 2, 3}, {5, 3, 4}};  // bar
  return extrude_xz(profile, cap, -s, s);
}

double t_shape_arm_underside_area(const TShape& p) { return (p.bar_length - p.stem) * p.stem; }

Surface icosphere(int levels, double r, const Eigen::Vector3d& c) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<Eigen::Vector3i> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) split_in_four(v, f, /*onto_unit_sphere=*/true);
  for (auto& p : v) p = c + r * p;
  return from_lists(v, f);
}

namespace {
// The faces kept, with the vertices they use renumbered in order of first use.
Surface compacted(const Surface& full, std::vector<Eigen::Vector3i> kept) {
  std::vector<int> remap(static_cast<size_t>(full.V.rows()), -1);
  std::vector<Eigen::Vector3d> v;
  for (auto& tri : kept)
    for (int k = 0; k < 3; ++k) {
      int& m = remap[static_cast<size_t>(tri(k))];
      if (m < 0) {
        m = static_cast<int>(v.size());
        v.emplace_back(full.V.row(tri(k)).transpose());
      }
      tri(k) = m;
    }
  return from_lists(v, kept);
}
}  // namespace

Surface open_hemisphere(int levels, double r, bool lower) {
  const Surface full = icosphere(levels, r, Eigen::Vector3d(0, 0, r));
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index i = 0; i < full.F.rows(); ++i) {
    const double cz = (full.V(full.F(i, 0), 2) + full.V(full.F(i, 1), 2) + full.V(full.F(i, 2), 2)) / 3.0;
    if ((cz < r) == lower) kept.emplace_back(full.F.row(i).transpose());
  }
  return compacted(full, kept);
}

Surface slab_on_stem(double width, double z) {
  return merge(box({-2, -2, 0}, {2, 2, z + 1}), box({-width / 2, -width / 2, z}, {width / 2, width / 2, z + 2}));
}

Surface box_with_windows(double width, int windows) {
  const Surface full = refined(box({-10, -10, 0}, {10, 10, 20}), 4);
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index i = 0; i < full.F.rows(); ++i) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += full.V.row(full.F(i, k)).transpose() / 3.0;
    const bool side = std::abs(c.y() + 10) < 1e-9 || (windows == 2 && std::abs(c.y() - 10) < 1e-9);
    if (!(side && c.x() > 0 && c.x() < width && c.z() > 6.25 && c.z() < 13.75)) kept.emplace_back(full.F.row(i).transpose());
  }
  return compacted(full, kept);
}

Surface two_cubes_sharing_edge(double a) {
  return weld(merge(box({0, 0, 0}, {a, a, a}), box({a, a, 0}, {2 * a, 2 * a, a})));
}

Eigen::Matrix3d axis_angle(const Eigen::Vector3d& axis, double radians) {
  return Eigen::AngleAxisd(radians, axis.normalized()).toRotationMatrix();
}

Eigen::Matrix3d random_rotation(std::mt19937_64& gen) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(normal(gen), normal(gen), normal(gen), normal(gen)).normalized().toRotationMatrix();
}

Surface transformed(const Surface& s, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Surface out = s;
  out.V = (s.V * R.transpose()).rowwise() + t.transpose();
  return out;
}

std::string sample_bunny_path() { return data_dir() + "/bunny.ply"; }

}  // namespace slim::test

#ifdef SLIM_TESTS_HAVE_VCG
#include "mesh_io/mesh_io.h"
namespace slim::test {
Surface load_mesh(const std::string& path) { return io::load_surface(path); }
const Surface& sample_bunny() {
  static const Surface s = load_mesh(sample_bunny_path());
  return s;
}
}  // namespace slim::test
#endif

namespace slim::test {
double bbox_diagonal(const Surface& s) { return (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm(); }
}  // namespace slim::test

namespace slim::test {

Surface revolve(const std::vector<Eigen::Vector2d>& profile, int segments) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  const int bottom = 0;
  v.emplace_back(0, 0, profile.front().y());
  const int rings = static_cast<int>(profile.size()) - 2;  // profile points off the axis
  for (int i = 1; i <= rings; ++i)
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * M_PI * s / segments;
      v.emplace_back(profile[static_cast<size_t>(i)].x() * std::cos(a), profile[static_cast<size_t>(i)].x() * std::sin(a),
                     profile[static_cast<size_t>(i)].y());
    }
  const int top = static_cast<int>(v.size());
  v.emplace_back(0, 0, profile.back().y());
  auto ring = [&](int i, int s) { return 1 + (i - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    f.emplace_back(bottom, ring(1, s + 1), ring(1, s));
    for (int i = 1; i < rings; ++i) {
      f.emplace_back(ring(i, s), ring(i, s + 1), ring(i + 1, s + 1));
      f.emplace_back(ring(i, s), ring(i + 1, s + 1), ring(i + 1, s));
    }
    f.emplace_back(top, ring(rings, s), ring(rings, s + 1));
  }
  return from_lists(v, f);
}

namespace {
// Ear-clipping triangulation of a simple counter-clockwise polygon (test shapes only).
std::vector<Eigen::Vector3i> ear_clip(const std::vector<Eigen::Vector2d>& p) {
  std::vector<int> idx(p.size());
  for (size_t i = 0; i < p.size(); ++i) idx[i] = static_cast<int>(i);
  auto cross = [&](int a, int b, int c) {
    return (p[b] - p[a]).x() * (p[c] - p[a]).y() - (p[b] - p[a]).y() * (p[c] - p[a]).x();
  };
  std::vector<Eigen::Vector3i> tris;
  while (idx.size() > 3) {
    bool clipped = false;
    for (size_t i = 0; i < idx.size() && !clipped; ++i) {
      const int a = idx[(i + idx.size() - 1) % idx.size()], b = idx[i], c = idx[(i + 1) % idx.size()];
      if (cross(a, b, c) <= 1e-12) continue;  // reflex or flat corner
      bool empty = true;
      for (int q : idx)
        if (q != a && q != b && q != c && cross(a, b, q) >= 0 && cross(b, c, q) >= 0 && cross(c, a, q) >= 0) empty = false;
      if (!empty) continue;
      tris.emplace_back(a, b, c);
      idx.erase(idx.begin() + static_cast<long>(i));
      clipped = true;
    }
    if (!clipped) throw std::logic_error("ear_clip: polygon is not simple and counter-clockwise");
  }
  tris.emplace_back(idx[0], idx[1], idx[2]);
  return tris;
}
}  // namespace

Surface mushroom(int segments) {
  return revolve({{0, 0}, {3, 0}, {3, 10}, {10, 11}, {10, 13}, {6, 15.5}, {0, 16}}, segments);
}

Surface flared_foot(const std::vector<Eigen::Vector2d>& flare) {
  std::vector<Eigen::Vector2d> profile{{0, 0}, {3, 0}};
  profile.insert(profile.end(), flare.begin(), flare.end());
  profile.push_back({flare.back().x(), 5.0});
  profile.push_back({0, 5.0});
  return revolve(profile, 64);
}

Surface prism_xz(const std::vector<Eigen::Vector2d>& profile, double y0, double y1) {
  return extrude_xz(profile, ear_clip(profile), y0, y1);
}

Surface arch(int arc_segments) {
  std::vector<Eigen::Vector2d> profile{{-15, 0}, {-10, 0}};
  for (int i = 0; i <= arc_segments; ++i) {  // the opening's arc, from the left leg over to the right
    const double a = M_PI - M_PI * i / arc_segments;
    profile.emplace_back(10 * std::cos(a), 8 + 10 * std::sin(a));
  }
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(10, 0), Eigen::Vector2d(15, 0), Eigen::Vector2d(15, 20),
                                   Eigen::Vector2d(-15, 20)})
    profile.push_back(q);
  return extrude_xz(profile, ear_clip(profile), -5, 5);
}

Surface printable_mushroom(int segments) {
  return revolve({{0, 0}, {3, 0}, {3, 8}, {10, 16}, {10, 17}, {6, 19.5}, {0, 20}}, segments);
}

Surface l_bracket(const LBracket& p) {
  const std::vector<Eigen::Vector2d> profile{{0, 0}, {p.base, 0}, {p.base, p.thickness}, {p.thickness, p.thickness},
                                             {p.thickness, p.upright}, {0, p.upright}};
  return extrude_xz(profile, ear_clip(profile), -p.width / 2, p.width / 2);
}

}  // namespace slim::test

namespace slim::test {
std::vector<ShapeCase> domain_cases() {
  std::vector<ShapeCase> cases;
  cases.push_back({"cube", box({0, 0, 0}, {10, 20, 30})});  // at 24 cells its faces lie on grid planes
  cases.push_back({"sphere", icosphere(3)});
  cases.push_back({"T", t_shape()});
  cases.push_back({"open hemisphere", open_hemisphere(3), Eigen::Vector3d::UnitZ(), false});
  cases.push_back({"two cubes sharing an edge", two_cubes_sharing_edge()});
  const Eigen::Matrix3d R = axis_angle({1, 2, 3}, 0.7);
  cases.push_back({"turned T, tilted print direction", transformed(t_shape(), R, {3, -2, 5}),
                   Eigen::Vector3d(0.3, -0.5, 0.8).normalized()});
#ifdef SLIM_TESTS_HAVE_VCG
  cases.push_back({"bunny", load_mesh(sample_bunny_path())});
#endif
  return cases;
}

Surface triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return from_lists({a, b, c}, {{0, 1, 2}});
}
}  // namespace slim::test

namespace slim::test {
Surface refined(const Surface& s, int levels) {
  std::vector<Eigen::Vector3d> v;
  for (Eigen::Index i = 0; i < s.V.rows(); ++i) v.emplace_back(s.V.row(i).transpose());
  std::vector<Eigen::Vector3i> f;
  for (Eigen::Index i = 0; i < s.F.rows(); ++i) f.emplace_back(s.F.row(i).transpose());
  for (int l = 0; l < levels; ++l) split_in_four(v, f, /*onto_unit_sphere=*/false);
  return from_lists(v, f);
}
}  // namespace slim::test
