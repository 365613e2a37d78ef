#include "fuzz/fuzz_case.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "core/domain/embedding.h"
#include "core/domain/voxel_domain.h"
#include "core/geometry/tet_mesh.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "core/rotation/min_rotation.h"
#include "support/bad_inputs.h"

namespace slim::fuzz {

namespace {

constexpr int kMaxVertices = 300, kMaxFaces = 600;
// The memory budget of every run (SlimmingOptions::max_memory_bytes, and the voxel domain's): a
// resolution of a million on a mesh that is long in one direction only still fits the default
// 2 GB domain budget, and would take seconds per input.
constexpr double kMemoryBudget = 5e7;
// Resolutions from here up stay as they are: even a grid one cell thick then needs more than the
// budget, so the guards must refuse them at once. Below, down to 25, they fold to 1..24: a
// resolution of 100,000 on a mesh long in one direction only is a 100,000-cell domain that fits
// the budget but takes seconds to embed under the sanitizers.
constexpr std::int32_t kAbsurdResolution = 1000000;
constexpr std::uint8_t kTetGen = 1, kPaper = 2, kRigid = 4, kFloatCoordinates = 8, kTwoThreads = 16;

// Reads values in host byte order (little-endian on every machine this builds for); past the
// end, zeros.
class Reader {
 public:
  Reader(const std::uint8_t* data, size_t size) : data_(data), size_(size) {}
  template <class T>
  T get() {
    unsigned char bytes[sizeof(T)] = {};
    const size_t n = std::min(sizeof(T), size_ - pos_);
    if (n > 0) std::memcpy(bytes, data_ + pos_, n);
    pos_ += n;
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }

 private:
  const std::uint8_t* data_;
  size_t size_, pos_ = 0;
};

class Writer {
 public:
  template <class T>
  void put(T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof value);
    out.insert(out.end(), bytes, bytes + sizeof(T));
  }
  std::vector<std::uint8_t> out;
};

// A refusal must say why in one line.
void check_refusal(const char* stage, const std::exception& e, std::ostringstream& problem) {
  const std::string what = e.what();
  if (what.empty() || what.find('\n') != std::string::npos) problem << stage << " refused without a one-line reason; ";
}

void check_analysis(const FuzzCase& c, std::ostringstream& problem) {
  PrintSetup o;
  o.direction = c.options.print.direction;
  o.alpha_max_deg = c.options.print.alpha_max_deg;
  try {
    const OverhangReport r = analyse_overhang(c.surface, o);
    if (!r.quality.allFinite() || !(r.risky_area >= 0.0) || r.risky_area > r.total_area * (1 + 1e-12))
      problem << "overhang analysis: bad report; ";
  } catch (const std::invalid_argument& e) {
    check_refusal("overhang analysis", e, problem);
  }
}

// The domain's and the embedding's contracts (voxel_domain.h, embedding.h).
void check_domain_and_embedding(const FuzzCase& c, std::ostringstream& problem) {
  VoxelDomainOptions vo;
  vo.resolution = c.options.resolution;
  vo.max_bytes = kMemoryBudget;
  try {
    const Surface& s = c.surface;
    const VoxelDomain dom = voxel_domain(s, c.options.print.direction, vo);
    for (Eigen::Index t = 0; t < dom.mesh.T.rows(); ++t)
      if (!(tet_volume(dom.mesh.V, dom.mesh.T.row(t)) > 0.0)) {
        problem << "voxel domain: tet " << t << " is not positive; ";
        break;
      }
    const Embedding e = embed_surface(s, dom);
    for (Eigen::Index v = 0; v < s.V.rows(); ++v)
      if (std::abs(e.vertex_bary.row(v).sum() - 1.0) > 1e-9 || e.vertex_bary.row(v).minCoeff() < -1e-9) {
        problem << "embedding: vertex " << v << " has barycentric coordinates " << e.vertex_bary.row(v) << "; ";
        break;
      }
    Eigen::VectorXd pieces = Eigen::VectorXd::Zero(s.F.rows());
    for (Eigen::Index p = 0; p < e.tet_faces.size(); ++p) pieces(e.tet_faces(p)) += e.tet_face_areas(p);
    // The embedding works in grid units: below about 1e-13 of a cell's area a face's area is
    // rounding (a 1e5 mm sliver 1e-19 mm wide has none left), so that much may go missing.
    const Eigen::VectorXd areas = face_areas(s);
    const double cell_area = dom.grid.cell_size * dom.grid.cell_size;
    for (Eigen::Index f = 0; f < s.F.rows(); ++f)
      if (std::abs(pieces(f) - areas(f)) > 1e-5 * areas(f) + 1e-10 * cell_area) {
        problem << "embedding: the pieces of face " << f << " add up to " << pieces(f) << ", not " << areas(f) << "; ";
        break;
      }
  } catch (const std::invalid_argument& e) {
    check_refusal("domain or embedding", e, problem);
  }
}

// After the minimal rotation every face of the mesh is safe, if it is feasible at all.
void check_min_rotation(const FuzzCase& c, std::ostringstream& problem) {
  Eigen::Vector3d d;
  double tau;
  try {
    check_surface(c.surface);
    d = unit_print_direction(c.options.print.direction);
    tau = self_supporting_tau(c.options.print.alpha_max_deg);
  } catch (const std::invalid_argument&) {
    return;  // refused above already
  }
  const Eigen::Matrix3Xd normals = face_normals(c.surface).transpose();
  try {
    const MinRotation m = min_rotation(normals, d, tau);
    if (!m.rotation.allFinite() || !std::isfinite(m.angle)) problem << "min rotation: not finite; ";
    if (m.feasible)
      for (Eigen::Index i = 0; i < normals.cols(); ++i)
        if (normals.col(i).squaredNorm() > 0.0 && (m.rotation * normals.col(i)).dot(d) < -tau - 1e-9) {
          problem << "min rotation: face " << i << " is still risky after it; ";
          break;
        }
  } catch (const std::invalid_argument& e) {
    problem << "min rotation refused the mesh's own normals: " << e.what() << "; ";
  }
}

// Print Orientation (orientation.h) with the case's angle and threads, at the Fast effort: a
// refusal with a reason, or a rigid turn onto +Z that needs no more support than the pose as given
// and rests the part on z = 0.
void check_orientation(const FuzzCase& c, std::ostringstream& problem) {
  OrientationOptions o = with_effort(OrientationEffort::Fast);
  o.alpha_max_deg = c.options.print.alpha_max_deg;
  o.threads = c.options.threads;
  try {
    const OrientationResult r = optimize_orientation(c.surface, o);
    const Eigen::Matrix3d& R = r.rotation;
    if (!R.allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
        std::abs(R.determinant() - 1.0) > 1e-9)
      problem << "orientation: not a rotation; ";
    else if ((R * r.best.direction - Eigen::Vector3d::UnitZ()).norm() > 1e-9)
      problem << "orientation: the rotation does not take the best direction onto +Z; ";
    const double scale = std::max({1.0, std::abs(r.as_given.score), std::abs(r.best.score)});
    if (!std::isfinite(r.best.score) || r.best.score > r.as_given.score + 1e-9 * scale)
      problem << "orientation: the best pose scores worse than the pose as given; ";
    if (r.top.empty() || r.top.front().score != r.best.score) problem << "orientation: top does not start with the best; ";
    const Surface posed = apply_orientation(c.surface, R);
    const double extent = (c.surface.V.colwise().maxCoeff() - c.surface.V.colwise().minCoeff()).norm();
    if (!posed.V.allFinite() || std::abs(posed.V.col(2).minCoeff()) > 1e-9 * std::max(1.0, extent))
      problem << "orientation: the posed part does not rest on z = 0; ";
  } catch (const std::invalid_argument& e) {
    check_refusal("orientation", e, problem);
  } catch (const std::runtime_error& e) {
    check_refusal("orientation", e, problem);
  }
}

void check_slimming(const FuzzCase& c, std::ostringstream& problem) {
  SlimmingOptions o = c.options;
  o.guards.max_memory_bytes = kMemoryBudget;
  int reports = 0;
  if (c.cancel_after > 0) o.progress = [&](double, const std::string&) { return ++reports < c.cancel_after; };
  try {
    const SlimmingResult r = slim_supports(c.surface, o);
    problem << test::slimming_result_problem(c.surface, o, r);
  } catch (const Cancelled&) {
    if (c.cancel_after == 0 || reports != c.cancel_after) problem << "cancelled without being asked; ";
  } catch (const std::invalid_argument& e) {
    check_refusal("support slimming", e, problem);
  } catch (const std::runtime_error& e) {
    check_refusal("support slimming", e, problem);
  }
}

}  // namespace

FuzzCase decode(const std::uint8_t* data, size_t size) {
  Reader in(data, size);
  FuzzCase c;
  SlimmingOptions& o = c.options;
  const std::uint8_t flags = in.get<std::uint8_t>();
  o.domain = flags & kTetGen ? DomainKind::TetGen : DomainKind::Voxel;
  o.method = flags & kPaper ? SlimmingMethod::Paper : SlimmingMethod::Coherent;
  o.threads = flags & kTwoThreads ? 2 : 1;
  for (int a = 0; a < 3; ++a) o.print.direction(a) = in.get<float>();
  o.print.alpha_max_deg = in.get<float>();
  o.budget = DeviationBudget::from_percent(in.get<float>());
  const std::int32_t resolution = in.get<std::int32_t>(), iterations = in.get<std::int32_t>(), k = in.get<std::int32_t>();
  o.resolution = resolution >= 25 && resolution < kAbsurdResolution ? 1 + resolution % 24 : resolution;
  o.steps.max_iterations = iterations > 3 ? 1 + iterations % 3 : iterations;
  o.steps.max_k = k > 16 ? 1 + k % 16 : k;
  c.cancel_after = in.get<std::uint8_t>();

  const int nv = in.get<std::uint16_t>() % (kMaxVertices + 1);
  c.surface.V.resize(nv, 3);
  if (flags & kFloatCoordinates) {
    for (int v = 0; v < nv; ++v)
      for (int a = 0; a < 3; ++a) c.surface.V(v, a) = in.get<float>();
  } else {
    const double step = in.get<float>();
    Eigen::RowVector3d origin;
    for (int a = 0; a < 3; ++a) origin(a) = in.get<float>();
    for (int v = 0; v < nv; ++v)
      for (int a = 0; a < 3; ++a) c.surface.V(v, a) = origin(a) + step * in.get<std::int8_t>();
  }
  const int nf = in.get<std::uint16_t>() % (kMaxFaces + 1);
  c.surface.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f)
    for (int k3 = 0; k3 < 3; ++k3) c.surface.F(f, k3) = in.get<std::uint16_t>();
  if (flags & kRigid) {
    o.rigid_features.assign(static_cast<size_t>(nf), false);
    std::uint8_t bits = 0;
    for (int f = 0; f < nf; ++f) {
      if (f % 8 == 0) bits = in.get<std::uint8_t>();
      o.rigid_features[static_cast<size_t>(f)] = (bits >> (f % 8)) & 1;
    }
  }
  return c;
}

std::vector<std::uint8_t> encode(const FuzzCase& c) {
  const SlimmingOptions& o = c.options;
  Writer out;
  std::uint8_t flags = kFloatCoordinates;
  if (o.domain == DomainKind::TetGen) flags |= kTetGen;
  if (o.method == SlimmingMethod::Paper) flags |= kPaper;
  if (!o.rigid_features.empty()) flags |= kRigid;
  if (o.threads == 2) flags |= kTwoThreads;
  out.put(flags);
  for (int a = 0; a < 3; ++a) out.put(static_cast<float>(o.print.direction(a)));
  out.put(static_cast<float>(o.print.alpha_max_deg));
  out.put(static_cast<float>(o.budget.share_percent().value_or(0.0)));
  out.put(static_cast<std::int32_t>(o.resolution));
  out.put(static_cast<std::int32_t>(o.steps.max_iterations));
  out.put(static_cast<std::int32_t>(o.steps.max_k));
  out.put(static_cast<std::uint8_t>(c.cancel_after));
  out.put(static_cast<std::uint16_t>(c.surface.V.rows()));
  for (Eigen::Index v = 0; v < c.surface.V.rows(); ++v)
    for (int a = 0; a < 3; ++a) out.put(static_cast<float>(c.surface.V(v, a)));
  out.put(static_cast<std::uint16_t>(c.surface.F.rows()));
  for (Eigen::Index f = 0; f < c.surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.put(static_cast<std::uint16_t>(c.surface.F(f, k)));
  if (!o.rigid_features.empty())
    for (size_t f = 0; f < o.rigid_features.size(); f += 8) {
      std::uint8_t bits = 0;
      for (size_t b = 0; b < 8 && f + b < o.rigid_features.size(); ++b) bits |= o.rigid_features[f + b] << b;
      out.put(bits);
    }
  return out.out;
}

std::string run_fuzz_case(const FuzzCase& c) {
  std::ostringstream problem;
  check_analysis(c, problem);
  if (c.options.domain == DomainKind::Voxel) check_domain_and_embedding(c, problem);
  check_min_rotation(c, problem);
  check_orientation(c, problem);
  check_slimming(c, problem);
  return problem.str();
}

}  // namespace slim::fuzz
