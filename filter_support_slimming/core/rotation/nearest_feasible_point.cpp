#include "core/rotation/nearest_feasible_point.h"

#include "core/geometry/convex_hull.h"
#include "core/rotation/min_rotation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace slim {

namespace {

// Candidates are screened against the best angle so far with this slack (in units of cos(angle)),
// so rounding in the screening arithmetic never throws the true answer away.
constexpr double kScreenSlack = 1e-9;
// From this many normals on, crossings come from the hull edges rather than from all pairs.
constexpr Eigen::Index kHullFrom = 24;  // measured crossover
// Where the hull cannot be trusted: the constraints an active set starts with (those most violated
// at d) and the most it adds a round (those most violated at its answer).
constexpr Eigen::Index kActiveSetStart = 16;
constexpr size_t kActiveSetStep = 8;
// Rounds of the active set tried before the hull: a patch of one surface (normals within a few
// tens of degrees) is settled in one or two; a wide one (normals all round the lower hemisphere)
// takes many, and the hull does it faster.
constexpr int kActiveSetFirstRounds = 3;
// The constraints an active set takes in come from different directions: among normals closer
// than this (a chord; 0.006°) it takes the most violated only, and the rest only if its next answer
// violates them. A dense surface (a million faces, a scan, a subdivided part) puts many normals
// in a tet, in groups of near-copies far closer than this (vertices stored as floats); taking a
// whole group at once spent the rounds on one direction, and many patches were still undecided
// when the rounds ran out (docs/history/speed.md).
constexpr double kActiveSetApart = 1e-4;

// Why only hull edges can cross at a feasible point: at a feasible crossing p of circles i and j,
// the plane x·p = -tau has every normal on the side x·p >= -tau and n_i, n_j on it, so it supports
// the hull of the normals along the edge (i, j). (The hull is the spherical Delaunay triangulation
// of the cap centres; its edges are O(m), against O(m²) pairs.) Heights in the strict hull are
// 6 x tetrahedron volumes of unit vectors, computed to within ~1e-16: beyond this their sign is
// certain; closer, the hull gives up and every pair is tried instead.
constexpr double kTrustedHullTest = 1e-12;

// Nearest point of H = { p : n_i·p >= -tau } to d, by enumerating every point that can be it.
class NearestFeasiblePoint {
 public:
  NearestFeasiblePoint(const Eigen::Matrix3Xd& n, const Eigen::Vector3d& d, double tau,
                       const Eigen::Vector3d& tie, double tie_tolerance)
      : n_(n), d_(d), tau_(tau), tie_(tie), tie_tolerance_(tie_tolerance) {}

  enum class Outcome { kFound, kEmpty, kUndecided };

  // kEmpty when H is empty. kUndecided: many normals whose hull cannot be trusted, and all_pairs
  // false: nothing found, the caller narrows the constraints (nearest_by_active_set).
  Outcome solve(Eigen::Vector3d& closest, bool all_pairs) {
    if (is_feasible(d_)) {
      closest = d_;
      return Outcome::kFound;
    }
    offer_circle_points();
    const bool many = n_.cols() >= kHullFrom;
    if (!many || !offer_hull_crossings()) {
      if (many && !all_pairs) return Outcome::kUndecided;
      offer_all_pair_crossings();
    }
    if (kept_.empty()) return Outcome::kEmpty;
    closest = tie_broken_choice();
    return Outcome::kFound;
  }

 private:
  struct Kept {
    Eigen::Vector3d p;
    double angle;
  };
  struct Candidate {
    Eigen::Vector3d p;
    double cos_angle;  // d·p
  };

  // Offers candidates nearest first: past the first feasible one only ties can still matter, so
  // a heap (O(c) to build, O(log c) per candidate looked at) beats sorting them all.
  void offer_nearest_first(const std::vector<Candidate>& candidates) {
    std::vector<std::pair<double, int>> heap(candidates.size());  // (d·p, -index): ties go to the first
    for (size_t k = 0; k < candidates.size(); ++k) heap[k] = {candidates[k].cos_angle, -static_cast<int>(k)};
    std::make_heap(heap.begin(), heap.end());
    while (!heap.empty() && heap.front().first >= screen_) {
      offer(candidates[static_cast<size_t>(-heap.front().second)].p);
      std::pop_heap(heap.begin(), heap.end());
      heap.pop_back();
    }
  }

  // n_k·p >= -tau - tolerance for all k; starts with the constraint that failed last time, which
  // rejects most of the many infeasible candidates at the first test.
  bool is_feasible(const Eigen::Vector3d& p) {
    const double bound = -tau_ - kMinRotationFeasibilityTolerance;
    if (n_.cols() == 0) return true;
    if (n_.col(last_violated_).dot(p) < bound) return false;
    for (Eigen::Index k = 0; k < n_.cols(); ++k) {
      if (n_.col(k).dot(p) < bound) {
        last_violated_ = k;
        return false;
      }
    }
    return true;
  }

  // A unit candidate point: kept when feasible and within tie_tolerance of the best angle so far.
  void offer(const Eigen::Vector3d& p) {
    if (d_.dot(p) >= screen_ && is_feasible(p)) keep(p);
  }

  // A feasible point, unit up to rounding: kept when within tie_tolerance of the best angle so far.
  void keep(const Eigen::Vector3d& p) {
    const double angle = std::atan2(p.cross(d_).norm(), d_.dot(p));
    if (angle > best_angle_ + tie_tolerance_) return;
    kept_.push_back({p.normalized(), angle});
    if (angle < best_angle_) {
      best_angle_ = angle;
      const double limit = best_angle_ + tie_tolerance_;
      kept_.erase(std::remove_if(kept_.begin(), kept_.end(), [&](const Kept& k) { return k.angle > limit; }),
                  kept_.end());
      screen_ = std::cos(std::min(limit, M_PI)) - kScreenSlack;
    }
  }

  // On each boundary circle n_i·p = -tau (centre -tau n_i, radius sqrt(1 - tau²)) the point
  // nearest to d. When d is (nearly) on the circle's axis the whole circle is (nearly) equally
  // near, so its point in the tie-break direction is offered as well.
  void offer_circle_points() {
    const double radius = std::sqrt(1.0 - tau_ * tau_);
    const double whole_circle_ties = std::sin(0.5 * std::min(tie_tolerance_, M_PI));
    std::vector<Candidate> points;
    auto add = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& direction) {
      const Eigen::Vector3d p = (centre + radius * direction).normalized();
      points.push_back({p, d_.dot(p)});
    };
    for (Eigen::Index i = 0; i < n_.cols(); ++i) {
      const Eigen::Vector3d ni = n_.col(i);
      const Eigen::Vector3d centre = -tau_ * ni;
      const Eigen::Vector3d off_axis = d_ - d_.dot(ni) * ni;
      const double off_axis_length = off_axis.norm();
      if (off_axis_length > 0.0) add(centre, off_axis / off_axis_length);
      if (off_axis_length <= whole_circle_ties) {
        const Eigen::Vector3d w = tie_ - tie_.dot(ni) * ni;
        if (w.norm() > 0.5) add(centre, w.normalized());  // tie_ ⟂ d and ni ≈ ±d: |w| ≈ 1
      }
    }
    offer_nearest_first(points);
  }

  // The crossings of every two boundary circles. With S = n_i + n_j and D = n_j - n_i (S ⟂ D),
  // the crossings are p = p0 ± h u, p0 = -2 tau S / |S|², u = S × D / |S × D|,
  // h = sqrt(1 - 4 tau² / |S|²); they exist when |S| >= 2 tau. S × D = 2 n_i × n_j, but keeps
  // full relative precision for near-duplicate and near-antipodal normals.
  void offer_all_pair_crossings() {
    const Eigen::Index m = n_.cols();
    // Structure of arrays in one block, so that the screening loop below vectorises. Columns:
    // n_i (x, y, z), d·n_i, d × n_i (as (d × n_i)·n_j = d·(n_i × n_j)), the screen's verdicts.
    Eigen::Matrix<double, Eigen::Dynamic, 8> columns(m, 8);
    columns.leftCols<3>() = n_.transpose();
    columns.col(3) = n_.transpose() * d_;
    for (Eigen::Index i = 0; i < m; ++i) columns.row(i).segment<3>(4) = d_.cross(n_.col(i)).transpose();
    const double *px = &columns(0, 0), *py = &columns(0, 1), *pz = &columns(0, 2), *pa = &columns(0, 3);
    const double *ex = &columns(0, 4), *ey = &columns(0, 5), *ez = &columns(0, 6);
    double* out = &columns(0, 7);  // > 0: the pair survives (double, so that it vectorises)
    const double four_tau2 = 4.0 * tau_ * tau_, two_tau = 2.0 * tau_;
    for (Eigen::Index i = 0; i < m; ++i) {
      // Screen without sqrt or division: |S|² d·p± = -2 tau (a_i + a_j) ± 2 t sqrt((|S|² - 4 tau²) / |D|²)
      // with a = d·n and t = d·(n_i × n_j). A pair survives when its caps touch and its nearer
      // crossing is not beyond the screen. Branch-free, so that it vectorises. (Only for normals
      // a few ulps apart is the screen unreliable; their circles coincide within the tolerance.)
      const double xi = px[i], yi = py[i], zi = pz[i], ai = pa[i], exi = ex[i], eyi = ey[i], ezi = ez[i];
      const double screen = screen_;
      for (Eigen::Index j = i + 1; j < m; ++j) {
        const double sx = xi + px[j], sy = yi + py[j], sz = zi + pz[j];
        const double dx = px[j] - xi, dy = py[j] - yi, dz = pz[j] - zi;
        const double s2 = sx * sx + sy * sy + sz * sz, d2 = dx * dx + dy * dy + dz * dz;
        const double t = exi * px[j] + eyi * py[j] + ezi * pz[j];
        const double L = screen * s2 + two_tau * (ai + pa[j]);
        const double room = s2 - four_tau2;
        const double caps_touch = room >= 0.0 ? 1.0 : 0.0;
        const double near_enough = (L <= 0.0 ? 1.0 : 0.0) + (4.0 * t * t * room > L * L * d2 ? 1.0 : 0.0);
        out[j] = caps_touch * near_enough;
      }
      for (Eigen::Index j = i + 1; j < m; ++j)
        if (out[j] > 0.0) offer_crossing_pair(n_.col(i), n_.col(j));
    }
  }

  // The crossings p0 ± hu of circles i and j (see offer_all_pair_crossings); false when there are none
  // or infinitely many (identical or antipodal circles), h = 0 when they touch.
  bool crossing_frame(const Eigen::Vector3d& ni, const Eigen::Vector3d& nj, Eigen::Vector3d& p0,
                      Eigen::Vector3d& hu, double& h) const {
    const Eigen::Vector3d S = ni + nj, D = nj - ni, c = S.cross(D);
    const double s2 = S.squaredNorm();
    if (s2 < 4.0 * tau_ * tau_) return false;
    // Not sqrt(|S|² |D|²): for normals a few ulps apart S·D is as large as |D| and |S × D| < |S| |D|.
    const double c_length = c.norm();
    if (c_length == 0.0) return false;
    const double inverse_s2 = 1.0 / s2;
    p0 = (-2.0 * tau_ * inverse_s2) * S;
    h = std::sqrt(std::max(0.0, 1.0 - 4.0 * tau_ * tau_ * inverse_s2));
    hu = (h / c_length) * c;
    return true;
  }

  void offer_crossing_pair(const Eigen::Vector3d& ni, const Eigen::Vector3d& nj) {
    Eigen::Vector3d p0, hu;
    double h;
    if (!crossing_frame(ni, nj, p0, hu, h)) return;
    // Both crossings against the screen, then against every constraint in one sweep.
    const double p0_d = p0.dot(d_), hu_d = hu.dot(d_);
    bool plus = p0_d + hu_d >= screen_, minus = p0_d - hu_d >= screen_ && h > 0.0;
    if (!plus && !minus) return;
    const double bound = -tau_ - kMinRotationFeasibilityTolerance;
    auto test = [&](Eigen::Index k) {
      const double centre = n_.col(k).dot(p0), offset = n_.col(k).dot(hu);
      plus = plus && centre + offset >= bound;
      minus = minus && centre - offset >= bound;
      return plus || minus;
    };
    if (!test(last_violated_)) return;
    for (Eigen::Index k = 0; k < n_.cols(); ++k) {
      if (!test(k)) {
        last_violated_ = k;
        return;
      }
    }
    if (plus) keep(p0 + hu);
    if (minus) keep(p0 - hu);
  }

  // With many normals only the crossings of hull edges (see kTrustedHullTest).
  // False when the hull cannot be trusted; nothing has been offered then.
  bool offer_hull_crossings() {
    // Exact duplicates are one constraint, and would make the hull degenerate.
    std::vector<std::array<double, 3>> sorted(static_cast<size_t>(n_.cols()));
    for (Eigen::Index i = 0; i < n_.cols(); ++i) sorted[static_cast<size_t>(i)] = {n_(0, i), n_(1, i), n_(2, i)};
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (sorted.size() < 4) return false;
    const Eigen::Matrix3Xd distinct =
        Eigen::Map<const Eigen::Matrix3Xd>(sorted.front().data(), 3, static_cast<Eigen::Index>(sorted.size()));

    ConvexHullOptions strict;
    strict.eps = kTrustedHullTest;
    strict.strict = true;
    ConvexHull hull;
    if (!convex_hull(Points(distinct.transpose()), strict, hull)) return false;
    const std::vector<HullEdge> edges = hull_edges(hull);
    // A crossing of edge (i, j) can only be feasible if the two vertices k and l facing the edge
    // leave it alone (and then it nearly always is: it lies on the Voronoi edge of i and j). That
    // O(1) test rejects almost every infeasible candidate before the full O(n) check.
    const double bound = -tau_ - kMinRotationFeasibilityTolerance;
    for (const auto& e : edges) {
      Eigen::Vector3d p0, hu;
      double h;
      if (!crossing_frame(distinct.col(e.i), distinct.col(e.j), p0, hu, h)) continue;
      for (const Eigen::Vector3d& p : {Eigen::Vector3d(p0 + hu), Eigen::Vector3d(p0 - hu)}) {
        if (d_.dot(p) >= screen_ && distinct.col(e.k).dot(p) >= bound && distinct.col(e.l).dot(p) >= bound)
          offer(p);
        if (h == 0.0) break;  // touching circles: one point
      }
    }
    return true;
  }

  // Among the kept points within tie_tolerance of the minimal angle: the one whose tangent at d
  // best matches the tie-break direction; then the smaller angle; then the first found.
  Eigen::Vector3d tie_broken_choice() const {
    const double limit = best_angle_ + tie_tolerance_;
    const Kept* choice = nullptr;
    double choice_alignment = 0.0;
    for (const Kept& k : kept_) {
      if (k.angle > limit) continue;
      const Eigen::Vector3d tangent = k.p - k.p.dot(d_) * d_;
      const double length = tangent.norm();
      const double alignment = length > kTinyTangent ? tangent.dot(tie_) / length : -2.0;
      if (!choice || alignment > choice_alignment ||
          (alignment == choice_alignment && k.angle < choice->angle)) {
        choice = &k;
        choice_alignment = alignment;
      }
    }
    return choice->p;
  }

  const Eigen::Matrix3Xd& n_;
  const Eigen::Vector3d d_;
  const double tau_;
  const Eigen::Vector3d tie_;
  const double tie_tolerance_;
  Eigen::Index last_violated_ = 0;
  std::vector<Kept> kept_;
  double best_angle_ = M_PI + 1.0;  // no feasible point yet
  double screen_ = -2.0;            // below every cos(angle): screens nothing yet
};

// The nearest point of H by an active set (nearest_feasible_point.h): subsets of the constraints,
// most violated first, until the subset's answer violates none. run() goes on from where the last
// call stopped.
class ActiveSet {
 public:
  ActiveSet(const Eigen::Matrix3Xd& n, const Eigen::Vector3d& d, double tau, const Eigen::Vector3d& tie,
            double tie_tolerance)
      : n_(n), d_(d), tau_(tau), tie_(tie), tie_tolerance_(tie_tolerance), chosen_(static_cast<size_t>(n.cols()), 0) {
    // The kActiveSetStart most violated at d (ties to the first), kActiveSetApart apart.
    std::vector<std::pair<double, Eigen::Index>> at_d(static_cast<size_t>(n.cols()));
    for (Eigen::Index i = 0; i < n.cols(); ++i) at_d[static_cast<size_t>(i)] = {d.dot(n.col(i)), i};
    choose_apart(at_d, static_cast<size_t>(kActiveSetStart));
  }

  // kUndecided after max_rounds rounds (< 0: no limit).
  NearestFeasiblePoint::Outcome run(int max_rounds, Eigen::Vector3d& closest) {
    const Eigen::Index m = n_.cols();
    const double bound = -tau_ - kMinRotationFeasibilityTolerance;
    for (int round = 0; round != max_rounds; ++round) {
      // The subset in the normals' own order, so that ties fall as they would among them.
      Eigen::Matrix3Xd subset(3, std::count(chosen_.begin(), chosen_.end(), 1));
      for (Eigen::Index i = 0, k = 0; i < m; ++i)
        if (chosen_[static_cast<size_t>(i)]) subset.col(k++) = n_.col(i);
      Eigen::Vector3d p;
      NearestFeasiblePoint solver(subset, d_, tau_, tie_, tie_tolerance_);
      if (solver.solve(p, true) == NearestFeasiblePoint::Outcome::kEmpty) return NearestFeasiblePoint::Outcome::kEmpty;
      violated_.clear();
      const Eigen::RowVectorXd at_p = p.transpose() * n_;
      for (Eigen::Index i = 0; i < m; ++i)
        if (at_p(i) < bound) violated_.push_back({at_p(i), i});
      if (violated_.empty()) {
        closest = p;
        return NearestFeasiblePoint::Outcome::kFound;
      }
      choose_apart(violated_, kActiveSetStep);
    }
    return NearestFeasiblePoint::Outcome::kUndecided;
  }

 private:
  // Takes in up to `most` of the constraints `by_violation` lists ((n·p, constraint), sorted here
  // most violated first, ties to the first constraint), none within kActiveSetApart of another
  // taken in this call. The most violated always: each round grows the set. Only the most violated
  // 4 × `most` are looked at, sorted `most` at a time as they are reached.
  void choose_apart(std::vector<std::pair<double, Eigen::Index>>& by_violation, size_t most) {
    const auto first = by_violation.begin();
    const size_t looked_at = std::min(by_violation.size(), 4 * most);
    size_t sorted = 0;
    taken_.clear();
    for (size_t k = 0; k < looked_at && taken_.size() < most; ++k) {
      if (k == sorted) {
        sorted = std::min(looked_at, sorted + most);
        std::partial_sort(first + static_cast<std::ptrdiff_t>(k), first + static_cast<std::ptrdiff_t>(sorted), by_violation.end());
      }
      const auto entry = first + static_cast<std::ptrdiff_t>(k);
      const auto n_i = n_.col(entry->second);
      const bool near = std::any_of(taken_.begin(), taken_.end(), [&](Eigen::Index j) {
        return (n_i - n_.col(j)).squaredNorm() < kActiveSetApart * kActiveSetApart;
      });
      if (near) continue;
      taken_.push_back(entry->second);
      chosen_[static_cast<size_t>(entry->second)] = 1;
    }
  }

  const Eigen::Matrix3Xd& n_;
  const Eigen::Vector3d d_;
  const double tau_;
  const Eigen::Vector3d tie_;
  const double tie_tolerance_;
  std::vector<Eigen::Index> taken_;                         // choose_apart's, this call
  std::vector<char> chosen_;                                // per constraint: in the subset
  std::vector<std::pair<double, Eigen::Index>> violated_;  // (n·p, constraint) at the last answer
};

}  // namespace

bool nearest_feasible_point(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau,
                            const Eigen::Vector3d& tie, double tie_tolerance, Eigen::Vector3d& closest) {
  using Outcome = NearestFeasiblePoint::Outcome;
  if (normals.cols() < kHullFrom) return NearestFeasiblePoint(normals, d, tau, tie, tie_tolerance).solve(closest, true) == Outcome::kFound;
  ActiveSet active(normals, d, tau, tie, tie_tolerance);
  Outcome outcome = active.run(kActiveSetFirstRounds, closest);
  if (outcome == Outcome::kUndecided) outcome = NearestFeasiblePoint(normals, d, tau, tie, tie_tolerance).solve(closest, false);
  if (outcome == Outcome::kUndecided) outcome = active.run(-1, closest);
  return outcome == Outcome::kFound;
}

}  // namespace slim
