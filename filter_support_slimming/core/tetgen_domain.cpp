#include "core/tetgen_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/overhang.h"

#ifdef SLIM_HAVE_TETGEN
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tetgen.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <cstdint>
#include <cstring>
#endif

namespace slim {

namespace {

using V3 = Eigen::Vector3d;

// ---- geometric predicates (plain double: exact zeros come from exactly coplanar data) --------

int sign(double x) { return (x > 0) - (x < 0); }

int orient3d(const V3& a, const V3& b, const V3& c, const V3& d) { return sign((b - a).dot((c - a).cross(d - a))); }

// The 2D plane that drops the dominant axis of n.
struct Plane2 {
  int u, v;
  explicit Plane2(const V3& n) {
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(n(a)) > std::abs(n(drop))) drop = a;
    u = (drop + 1) % 3;
    v = (drop + 2) % 3;
  }
  int orient(const V3& a, const V3& b, const V3& c) const {
    return sign((b(u) - a(u)) * (c(v) - a(v)) - (b(v) - a(v)) * (c(u) - a(u)));
  }
  bool on_segment(const V3& p, const V3& a, const V3& b) const {  // p collinear with a, b
    return std::min(a(u), b(u)) <= p(u) && p(u) <= std::max(a(u), b(u)) && std::min(a(v), b(v)) <= p(v) &&
           p(v) <= std::max(a(v), b(v));
  }
  bool segments_meet(const V3& p, const V3& q, const V3& a, const V3& b) const {
    const int o1 = orient(p, q, a), o2 = orient(p, q, b), o3 = orient(a, b, p), o4 = orient(a, b, q);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && on_segment(a, p, q)) || (o2 == 0 && on_segment(b, p, q)) || (o3 == 0 && on_segment(p, a, b)) ||
           (o4 == 0 && on_segment(q, a, b));
  }
  bool in_triangle(const V3& p, const V3& a, const V3& b, const V3& c) const {
    const int s1 = orient(a, b, p), s2 = orient(b, c, p), s3 = orient(c, a, p);
    return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
  }
  bool segment_meets_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) const {
    return in_triangle(p, a, b, c) || segments_meet(p, q, a, b) || segments_meet(p, q, b, c) || segments_meet(p, q, c, a);
  }
};

// Closed segment pq against closed triangle abc.
bool segment_meets_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp == sq && sp != 0) return false;
  if (sp == 0 && sq == 0) return Plane2((b - a).cross(c - a)).segment_meets_triangle(p, q, a, b, c);
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
}

using Tri = std::array<V3, 3>;

// Two closed triangles with no common vertex.
bool triangles_meet(const Tri& A, const Tri& B) {
  std::array<int, 3> sa{}, sb{};
  for (size_t i = 0; i < 3; ++i) {
    sa[i] = orient3d(B[0], B[1], B[2], A[i]);
    sb[i] = orient3d(A[0], A[1], A[2], B[i]);
  }
  auto one_side = [](const std::array<int, 3>& s) { return (s[0] == s[1] && s[1] == s[2] && s[0] != 0); };
  if (one_side(sa) || one_side(sb)) return false;
  if (sa == std::array<int, 3>{0, 0, 0}) {  // coplanar
    const Plane2 P((A[1] - A[0]).cross(A[2] - A[0]));
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        if (P.segments_meet(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3])) return true;
    return P.in_triangle(A[0], B[0], B[1], B[2]) || P.in_triangle(B[0], A[0], A[1], A[2]);
  }
  // Not coplanar: the intersection, if any, ends on an edge of one of them.
  for (size_t i = 0; i < 3; ++i)
    if (segment_meets_triangle(A[i], A[(i + 1) % 3], B[0], B[1], B[2]) ||
        segment_meets_triangle(B[i], B[(i + 1) % 3], A[0], A[1], A[2]))
      return true;
  return false;
}

// Ray v->x inside the closed wedge of triangle (v, a1, a2) at v (x in its plane).
bool in_wedge(const V3& v, const V3& a1, const V3& a2, const V3& x) {
  const V3 n = (a1 - v).cross(a2 - v), u = x - v;
  return (a1 - v).cross(u).dot(n) >= 0 && u.cross(a2 - v).dot(n) >= 0;
}

// Triangles (v, a1, a2) and (v, b1, b2) that share only v: do they meet anywhere else?
bool fan_triangles_meet(const V3& v, const V3& a1, const V3& a2, const V3& b1, const V3& b2) {
  if (segment_meets_triangle(a1, a2, v, b1, b2) || segment_meets_triangle(b1, b2, v, a1, a2)) return true;
  for (const V3* x : {&b1, &b2})
    if (orient3d(v, a1, a2, *x) == 0 && in_wedge(v, a1, a2, *x)) return true;
  for (const V3* x : {&a1, &a2})
    if (orient3d(v, b1, b2, *x) == 0 && in_wedge(v, b1, b2, *x)) return true;
  return false;
}

// Faces f and g (distinct) meet where they should not.
bool faces_meet_improperly(const Surface& s, Eigen::Index f, Eigen::Index g) {
  std::array<int, 3> F{s.F(f, 0), s.F(f, 1), s.F(f, 2)}, G{s.F(g, 0), s.F(g, 1), s.F(g, 2)};
  int shared = 0;
  std::array<int, 3> at_f{-1, -1, -1};  // at_f[i]: the corner of G equal to corner i of F
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      if (F[i] == G[j]) {
        at_f[i] = static_cast<int>(j);
        ++shared;
      }
  auto P = [&](int v) -> V3 { return s.V.row(v).transpose(); };
  if (shared == 0) return triangles_meet({P(F[0]), P(F[1]), P(F[2])}, {P(G[0]), P(G[1]), P(G[2])});
  if (shared >= 3) return true;  // the same triangle twice
  if (shared == 1) {
    const size_t i = static_cast<size_t>(std::find_if(at_f.begin(), at_f.end(), [](int j) { return j >= 0; }) - at_f.begin());
    const size_t j = static_cast<size_t>(at_f[i]);
    return fan_triangles_meet(P(F[i]), P(F[(i + 1) % 3]), P(F[(i + 2) % 3]), P(G[(j + 1) % 3]), P(G[(j + 2) % 3]));
  }
  // Two shared vertices: an edge u-v. Only a fold (coplanar, both on the same side) is wrong.
  size_t lone_f = 0, lone_g = 0;
  for (size_t i = 0; i < 3; ++i)
    if (at_f[i] < 0) lone_f = i;
  for (size_t j = 0; j < 3; ++j)
    if (std::find(at_f.begin(), at_f.end(), static_cast<int>(j)) == at_f.end()) lone_g = j;
  const V3 u = P(F[(lone_f + 1) % 3]), v = P(F[(lone_f + 2) % 3]), a = P(F[lone_f]), b = P(G[lone_g]);
  if (orient3d(u, v, a, b) != 0) return false;
  return (v - u).cross(a - u).dot((v - u).cross(b - u)) > 0;
}

void check_orientation_and_closure(const Surface& s) {
  const EdgeTopology edges = edge_topology(s);
  if (edges.open_edges > 0)
    throw std::invalid_argument("the mesh is not closed: " + std::to_string(edges.open_edges) +
                                " edge(s) belong to one face only, e.g. edge " + edges.first_open +
                                "; TetGen needs a closed surface (use the voxel domain)");
  if (edges.nonmanifold_edges > 0)
    throw std::invalid_argument("the mesh is not manifold: " + std::to_string(edges.nonmanifold_edges) +
                                " edge(s), e.g. edge " + edges.first_nonmanifold +
                                "; TetGen needs every edge shared by exactly two faces (use the voxel domain)");
  if (edges.flipped_edges > 0)
    throw std::invalid_argument("the mesh is not consistently oriented: " + edges.first_flipped + " (" +
                                std::to_string(edges.flipped_edges) + " such edge(s))");
}

void check_self_intersections(const Surface& s) {
  const Eigen::Index nf = s.F.rows();
  Points lo(nf, 3), hi(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    lo.row(f) = s.V.row(s.F(f, 0)).cwiseMin(s.V.row(s.F(f, 1))).cwiseMin(s.V.row(s.F(f, 2)));
    hi.row(f) = s.V.row(s.F(f, 0)).cwiseMax(s.V.row(s.F(f, 1))).cwiseMax(s.V.row(s.F(f, 2)));
  }
  // A uniform grid with about one cell per face; each pair is tested in the cell holding the
  // low corner of the overlap of its two boxes, so exactly once.
  const Eigen::RowVector3d glo = lo.colwise().minCoeff(), ghi = hi.colwise().maxCoeff();
  const double diag = (ghi - glo).norm();
  const Eigen::RowVector3d extent = (ghi - glo) + Eigen::RowVector3d::Constant(1e-9 * diag + 1e-300);
  const double side = std::cbrt(extent.prod() / static_cast<double>(nf));
  Eigen::Vector3i dims;
  for (int a = 0; a < 3; ++a) dims(a) = std::clamp(static_cast<int>(std::ceil(extent(a) / side)), 1, 256);
  auto cell = [&](const Eigen::RowVector3d& p) {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a)
      c(a) = std::clamp(static_cast<int>(std::floor((p(a) - glo(a)) / extent(a) * dims(a))), 0, dims(a) - 1);
    return c;
  };
  auto index = [&](const Eigen::Vector3i& c) {
    return static_cast<size_t>(c(0)) + static_cast<size_t>(dims(0)) * (static_cast<size_t>(c(1)) + static_cast<size_t>(dims(1)) * static_cast<size_t>(c(2)));
  };
  const size_t ncells = static_cast<size_t>(dims.prod());
  std::vector<size_t> offsets(ncells + 1, 0);
  auto for_cells = [&](Eigen::Index f, auto&& visit) {
    const Eigen::Vector3i a = cell(lo.row(f)), b = cell(hi.row(f));
    for (int k = a(2); k <= b(2); ++k)
      for (int j = a(1); j <= b(1); ++j)
        for (int i = a(0); i <= b(0); ++i) visit(index(Eigen::Vector3i(i, j, k)));
  };
  for (Eigen::Index f = 0; f < nf; ++f) for_cells(f, [&](size_t c) { ++offsets[c + 1]; });
  for (size_t c = 0; c < ncells; ++c) offsets[c + 1] += offsets[c];
  std::vector<int> faces(offsets[ncells]);
  {
    std::vector<size_t> fill(offsets.begin(), offsets.end() - 1);
    for (Eigen::Index f = 0; f < nf; ++f) for_cells(f, [&](size_t c) { faces[fill[c]++] = static_cast<int>(f); });
  }
  // The lexicographically smallest offending pair, whatever the thread count.
  std::int64_t worst = std::numeric_limits<std::int64_t>::max();
  const std::int64_t n64 = nf;
#pragma omp parallel for schedule(dynamic, 64) if (nf > 8192)
  for (std::int64_t c = 0; c < static_cast<std::int64_t>(ncells); ++c) {
    const size_t b = offsets[static_cast<size_t>(c)], e = offsets[static_cast<size_t>(c) + 1];
    for (size_t x = b; x < e; ++x)
      for (size_t y = x + 1; y < e; ++y) {
        const int f = faces[x], g = faces[y];
        if ((lo.row(f).array() > hi.row(g).array()).any() || (lo.row(g).array() > hi.row(f).array()).any()) continue;
        if (index(cell(lo.row(f).cwiseMax(lo.row(g)))) != static_cast<size_t>(c)) continue;
        if (!faces_meet_improperly(s, f, g)) continue;
        const std::int64_t key = std::min(f, g) * n64 + std::max(f, g);
#pragma omp critical(slim_tetgen_check)
        worst = std::min(worst, key);
      }
  }
  if (worst != std::numeric_limits<std::int64_t>::max())
    throw std::invalid_argument("the mesh intersects itself: faces " + std::to_string(worst / n64) + " and " +
                                std::to_string(worst % n64) +
                                " meet where they share no edge; TetGen would crash on it (use the voxel domain)");
}

}  // namespace

void check_tetgen_input(const Surface& s) {
  check_surface(s);
  if (s.F.rows() == 0) throw std::invalid_argument("the mesh has no faces");
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const V3 a = s.V.row(s.F(f, 0)).transpose(), b = s.V.row(s.F(f, 1)).transpose(), c = s.V.row(s.F(f, 2)).transpose();
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (s.F(f, 0) == s.F(f, 1) || s.F(f, 1) == s.F(f, 2) || s.F(f, 0) == s.F(f, 2) ||
        !((b - a).cross(c - a).norm() > 1e-12 * longest))
      throw std::invalid_argument("face " + std::to_string(f) +
                                  " has zero area (a degenerate triangle); TetGen cannot take it");
  }
  check_orientation_and_closure(s);
  check_self_intersections(s);
}

#ifndef SLIM_HAVE_TETGEN

bool tetgen_available() { return false; }

TetgenDomain tetgen_domain(const Surface&, const Eigen::Vector3d&, const TetgenOptions&) {
  throw std::runtime_error(
      "this build of support-slimming was built without TetGen (SLIM_WITH_TETGEN=OFF or libtet missing): "
      "use the voxel domain");
}

#else

namespace {

// What the child writes before the arrays.
struct ResultHeader {
  std::uint32_t magic;
  std::int32_t status;  // 0 = success, else TetGen's error code (1 = out of memory)
  std::int32_t points, tets, corners;
};
constexpr std::uint32_t kMagic = 0x534c494d;  // "SLIM"

bool write_all(int fd, const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    bytes -= static_cast<size_t>(n);
  }
  return true;
}

// The address space this process maps now (VmSize), in bytes; 0 if unknown. The child starts as
// a copy of it, and a GUI host can map gigabytes it never touches, so the child's limit is this
// plus what it may add.
double mapped_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) return 1024.0 * std::atof(line.c_str() + 7);
  return 0.0;
}

// address_limit: RLIMIT_AS for the child in bytes, 0 = none (computed before the fork).
[[noreturn]] void child_main(int fd, tetgenbehavior& behaviour, tetgenio& in, const TetgenOptions& o,
                             double address_limit) {
  // Default actions for the fatal signals, in case the host process installed crash handlers:
  // those belong to the parent and must not run in this copy of it.
  struct sigaction dfl;
  std::memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(sig, &dfl, nullptr);
  if (address_limit > 0) {
    struct rlimit limit;
    limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(address_limit);
    setrlimit(RLIMIT_AS, &limit);
  }
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) dup2(devnull, STDOUT_FILENO);  // TetGen's chatter stays out of the host's log
  if (o.test_fault == TetgenChildFault::crash) raise(SIGSEGV);
  if (o.test_fault == TetgenChildFault::hang)
    for (;;) pause();

  ResultHeader h{kMagic, 0, 0, 0, 0};
  tetgenio out;
  try {
    tetrahedralize(&behaviour, &in, &out);
  } catch (int code) {
    h.status = code == 0 ? 2 : code;
  } catch (...) {
    h.status = 1;  // std::bad_alloc under the memory limit
  }
  if (h.status == 0) {
    h.points = out.numberofpoints;
    h.tets = out.numberoftetrahedra;
    h.corners = out.numberofcorners;
  }
  bool ok = write_all(fd, &h, sizeof h);
  if (ok && h.status == 0) {
    ok = write_all(fd, out.pointlist, sizeof(REAL) * 3 * static_cast<size_t>(h.points)) &&
         write_all(fd, out.tetrahedronlist, sizeof(int) * static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets));
  }
  _exit(ok ? 0 : 3);
}

double now_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string tetgen_error(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 3: return "TetGen found a self-intersection in the surface";
    case 4: return "TetGen found a very small input feature (nearly touching faces)";
    case 5: return "TetGen found two very close input facets";
    case 10: return "TetGen found an input error";
    default: return "TetGen failed with an internal error (code " + std::to_string(code) + ")";
  }
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV, a segmentation fault";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT, an abort";
    case SIGKILL: return "SIGKILL, probably the out-of-memory killer";
    default: return "signal " + std::to_string(sig);
  }
}

// Runs TetGen in a child process; returns its raw output (header and arrays).
std::vector<char> run_child(tetgenbehavior& behaviour, tetgenio& in, const TetgenOptions& o) {
  const double address_limit = o.child_memory_bytes > 0 ? mapped_bytes() + o.child_memory_bytes : 0.0;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("could not create a pipe for TetGen: " + std::string(std::strerror(errno)));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("could not start a process for TetGen: " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    close(fds[0]);
    child_main(fds[1], behaviour, in, o, address_limit);
  }
  close(fds[1]);

  std::vector<char> data;
  const double deadline = now_seconds() + o.timeout_seconds;
  bool timed_out = false, eof = false;
  char buffer[1 << 16];
  while (!eof) {
    const double left = deadline - now_seconds();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(std::min(left * 1000.0 + 1.0, 1000.0)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) eof = true;
    else data.insert(data.end(), buffer, buffer + n);
  }
  close(fds[0]);
  // The child closes the pipe only by exiting; give it until the deadline to be reaped.
  int status = 0;
  pid_t reaped = 0;
  while (!timed_out) {
    reaped = waitpid(pid, &status, WNOHANG);
    if (reaped == pid || (reaped < 0 && errno != EINTR)) break;
    if (now_seconds() > deadline) timed_out = true;
    else usleep(1000);
  }
  if (timed_out) {
    kill(pid, SIGKILL);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    std::ostringstream msg;
    msg << "TetGen did not finish within " << o.timeout_seconds
        << " s and was stopped; use the voxel domain or a larger timeout";
    throw std::runtime_error(msg.str());
  }
  // reaped < 0: the host reaps its children itself (SIGCHLD ignored); the result then speaks
  // for itself, since a crashed child cannot have written a complete one.
  if (reaped == pid && WIFSIGNALED(status))
    throw std::runtime_error("TetGen crashed (" + signal_name(WTERMSIG(status)) +
                             ") on this mesh; its process was separate, so nothing else was lost. Use the voxel domain");
  if (reaped == pid && (!WIFEXITED(status) || WEXITSTATUS(status) != 0)) {
    // An allocator that dies at the address-space limit instead of throwing (AddressSanitizer's,
    // a C library's) ends the child this way: say that it may have been memory.
    std::ostringstream msg;
    msg << "TetGen's process ended abnormally (exit status " << WEXITSTATUS(status) << ")";
    if (address_limit > 0)
      msg << "; it may have run out of memory (limited to " << o.child_memory_bytes / 1e9
          << " GB more than this process maps); use the voxel domain";
    throw std::runtime_error(msg.str());
  }
  return data;
}

}  // namespace

bool tetgen_available() { return true; }

TetgenDomain tetgen_domain(const Surface& surface, const Eigen::Vector3d& print_direction, const TetgenOptions& o) {
  const Eigen::Vector3d d = unit_print_direction(print_direction);
  if (!(o.timeout_seconds > 0)) throw std::invalid_argument("the TetGen timeout must be positive");
  if (!(o.max_tet_volume >= 0)) throw std::invalid_argument("the maximum tet volume must be >= 0");
  check_tetgen_input(surface);

  // Only referenced vertices go to TetGen (a stray point would end up outside the surface).
  TetgenDomain dom;
  dom.surface_vertex = Eigen::VectorXi::Constant(surface.V.rows(), -1);
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) dom.surface_vertex(surface.F(f, k)) = 0;
  std::vector<int> input_vertex;
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    if (dom.surface_vertex(v) == 0) {
      dom.surface_vertex(v) = static_cast<int>(input_vertex.size());
      input_vertex.push_back(static_cast<int>(v));
    }

  // Input and switches are prepared here, so the child allocates as little as possible.
  tetgenio in;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(input_vertex.size());
  in.pointlist = new REAL[3 * input_vertex.size()];
  for (size_t i = 0; i < input_vertex.size(); ++i)
    for (int a = 0; a < 3; ++a) in.pointlist[3 * i + static_cast<size_t>(a)] = surface.V(input_vertex[i], a);
  in.numberoffacets = static_cast<int>(surface.F.rows());
  in.facetlist = new tetgenio::facet[static_cast<size_t>(surface.F.rows())];
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = dom.surface_vertex(surface.F(f, k));
  }
  std::string switches = o.switches + "zQ";
  if (o.max_tet_volume > 0) switches += "a" + std::to_string(o.max_tet_volume);
  tetgenbehavior behaviour;
  if (!behaviour.parse_commandline(switches.data()))
    throw std::invalid_argument("TetGen does not accept the switches \"" + o.switches + "\"");

  const std::vector<char> data = run_child(behaviour, in, o);
  ResultHeader h{};
  if (data.size() < sizeof h) throw std::runtime_error("TetGen's process returned no result");
  std::memcpy(&h, data.data(), sizeof h);
  if (h.magic != kMagic) throw std::runtime_error("TetGen's process returned garbage");
  if (h.status != 0) throw std::runtime_error(tetgen_error(h.status) + "; use the voxel domain");
  const size_t point_bytes = sizeof(REAL) * 3 * static_cast<size_t>(h.points);
  const size_t tet_bytes = sizeof(int) * static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets);
  if (h.points < in.numberofpoints || h.tets <= 0 || h.corners < 4 || data.size() != sizeof h + point_bytes + tet_bytes)
    throw std::runtime_error("TetGen's process returned an incomplete result");

  // Copied out, not cast: the points start right after the 20-byte header, so a REAL* into the
  // buffer would be misaligned (undefined behaviour; UBSan flagged it).
  std::vector<REAL> P(3 * static_cast<size_t>(h.points));
  std::memcpy(P.data(), data.data() + sizeof h, point_bytes);
  dom.mesh.V.resize(h.points, 3);
  for (Eigen::Index i = 0; i < h.points; ++i)
    for (int a = 0; a < 3; ++a) dom.mesh.V(i, a) = P[static_cast<size_t>(3 * i + a)];
  // With "Y" TetGen keeps the input points first and unchanged; the embedding relies on it.
  for (size_t i = 0; i < input_vertex.size(); ++i)
    if (dom.mesh.V.row(static_cast<Eigen::Index>(i)) != surface.V.row(input_vertex[i]))
      throw std::runtime_error("TetGen moved or renumbered the surface vertices (do not drop \"Y\")");
  std::vector<int> T(static_cast<size_t>(h.corners) * static_cast<size_t>(h.tets));
  std::memcpy(T.data(), data.data() + sizeof h + point_bytes, tet_bytes);
  dom.mesh.T.resize(h.tets, 4);
  for (Eigen::Index t = 0; t < h.tets; ++t) {
    for (int c = 0; c < 4; ++c) {
      const int v = T[static_cast<size_t>(t * h.corners + c)];
      if (v < 0 || v >= h.points) throw std::runtime_error("TetGen's result refers to a vertex it does not have");
      dom.mesh.T(t, c) = v;
    }
    const double vol = tet_volume(dom.mesh.V, dom.mesh.T.row(t));
    if (vol == 0.0) throw std::runtime_error("TetGen produced a flat tet");
    if (vol < 0.0) std::swap(dom.mesh.T(t, 2), dom.mesh.T(t, 3));
  }

  const Eigen::VectorXd height = dom.mesh.V * d;
  dom.plate_height = height.minCoeff();
  const double diag = (dom.mesh.V.colwise().maxCoeff() - dom.mesh.V.colwise().minCoeff()).norm();
  dom.on_plate = height.array() <= dom.plate_height + 1e-9 * diag;
  return dom;
}

#endif

}  // namespace slim
