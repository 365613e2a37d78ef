// The two sweeps of the supernodal back-substitution (supernodal_solve.h), one supernode at a
// time, for the right-hand sides held side by side in N lanes (N = 4: up to four columns, one AVX
// register or two SSE2 ones; N = 8: up to eight, two AVX registers).
//
// Storage: X and W are row-major with N doubles per row (lane c of row r is column c of row r;
// the unused lanes carry zeros through). X is #n rows, W is the supernode's #rows.
//   forward_supernode<N>(f, s, X, W, shared_slot, shared): L y = b through supernode s. The
//     updates to the rows below its columns go to X, except rows with a shared slot when `shared`
//     is given: those accumulate there (the caller adds them to X in a fixed order).
//   backward_supernode<N>(f, s, X, W): L^T x = y through supernode s; it reads the rows below its
//     columns, which the sweep has already finished (they belong to its ancestors).
// Private to supernodal_solve.cpp, which builds them into its baseline and AVX2 sweeps; the
// functions are always inlined there, so the vector types never cross an interface.
#pragma once

#include <algorithm>
#include <cstddef>

#include "core/solver/supernodal_solve.h"

// The lanes are only ever passed between inlined helpers, so the ABI note GCC gives for 32-byte
// vectors without AVX does not concern any interface.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace slim::sweeps {

typedef double Lanes __attribute__((vector_size(32)));

[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, Lanes v) { __builtin_memcpy(p, &v, sizeof v); }

// A row of N lanes is N / 4 registers, each loop over them unrolled: the row as one struct or as a
// 64-byte vector went through the stack piece by piece, and a solve of more columns slowed out of
// proportion to them.
template <int N>
struct Row {
  static constexpr int kParts = N / 4;
  Lanes part[kParts];
};

template <int N>
[[gnu::always_inline]] inline Row<N> load_row(const double* p) {
  Row<N> r;
  for (int q = 0; q < Row<N>::kParts; ++q) r.part[q] = load(p + 4 * q);
  return r;
}
template <int N>
[[gnu::always_inline]] inline void store_row(double* p, const Row<N>& r) {
  for (int q = 0; q < Row<N>::kParts; ++q) store(p + 4 * q, r.part[q]);
}
// p -= s * y (a row of W or X less a multiple of a solved row).
template <int N>
[[gnu::always_inline]] inline void subtract_multiple(double* p, double s, const Row<N>& y) {
  for (int q = 0; q < Row<N>::kParts; ++q) store(p + 4 * q, load(p + 4 * q) - s * y.part[q]);
}
template <int N>
[[gnu::always_inline]] inline void add_row(double* p, const double* from) {
  for (int q = 0; q < Row<N>::kParts; ++q) store(p + 4 * q, load(p + 4 * q) + load(from + 4 * q));
}

constexpr int kPanel = 8;  // columns of L streamed together

template <int N>
[[gnu::always_inline]] inline void forward_supernode(const SupernodalFactor& f, int s, double* X, double* W,
                                                     const int* shared_slot, double* shared) {
  constexpr int P = Row<N>::kParts;
  const int c0 = f.first_column[s], nc = f.first_column[s + 1] - c0, nr = f.row_start[s + 1] - f.row_start[s];
  const int* rows = f.rows + f.row_start[s];
  const double* block = f.values + f.value_start[s];
  for (int i = 0; i < nc; ++i) store_row<N>(W + N * i, load_row<N>(X + N * (c0 + i)));
  for (int i = nc; i < nr; ++i) store_row<N>(W + N * i, Row<N>{});
  for (int j0 = 0; j0 < nc; j0 += kPanel) {
    const int width = std::min(kPanel, nc - j0), end = j0 + width;
    for (int j = j0; j < end; ++j) {  // the panel's own triangle
      const double* col = block + static_cast<size_t>(j) * nr;
      Row<N> y = load_row<N>(W + N * j);
      for (int q = 0; q < P; ++q) y.part[q] /= col[j];
      store_row<N>(W + N * j, y);
      for (int i = j + 1; i < end; ++i) subtract_multiple<N>(W + N * i, col[i], y);
    }
    if (width == kPanel) {  // every row below the panel, eight columns in one pass
      const double* l[kPanel];
      Lanes y[P][kPanel];
      for (int k = 0; k < kPanel; ++k) {
        l[k] = block + static_cast<size_t>(j0 + k) * nr;
        for (int q = 0; q < P; ++q) y[q][k] = load(W + N * (j0 + k) + 4 * q);
      }
      for (int i = end; i < nr; ++i)
        for (int q = 0; q < P; ++q) {
          const Lanes a = l[0][i] * y[q][0] + l[1][i] * y[q][1] + l[2][i] * y[q][2] + l[3][i] * y[q][3];
          const Lanes b = l[4][i] * y[q][4] + l[5][i] * y[q][5] + l[6][i] * y[q][6] + l[7][i] * y[q][7];
          store(W + N * i + 4 * q, load(W + N * i + 4 * q) - (a + b));
        }
    } else {
      for (int j = j0; j < end; ++j) {
        const double* col = block + static_cast<size_t>(j) * nr;
        const Row<N> y = load_row<N>(W + N * j);
        for (int i = end; i < nr; ++i) subtract_multiple<N>(W + N * i, col[i], y);
      }
    }
  }
  for (int i = 0; i < nc; ++i) store_row<N>(X + N * (c0 + i), load_row<N>(W + N * i));
  for (int i = nc; i < nr; ++i) {
    const int r = rows[i];
    add_row<N>(shared && shared_slot[r] >= 0 ? shared + N * shared_slot[r] : X + N * r, W + N * i);
  }
}

// The sums of one full panel of L^T against the rows below it, for the lanes [4q, 4q + 4).
[[gnu::always_inline]] inline void backward_panel_sums(const double* const (&l)[kPanel], const double* W, int stride,
                                                       int end, int nr, Lanes (&sum)[kPanel]) {
  Lanes s0 = {}, s1 = {}, s2 = {}, s3 = {}, s4 = {}, s5 = {}, s6 = {}, s7 = {};
  for (int i = end; i < nr; ++i) {
    const Lanes w = load(W + stride * i);
    s0 += l[0][i] * w;
    s1 += l[1][i] * w;
    s2 += l[2][i] * w;
    s3 += l[3][i] * w;
    s4 += l[4][i] * w;
    s5 += l[5][i] * w;
    s6 += l[6][i] * w;
    s7 += l[7][i] * w;
  }
  sum[0] = s0, sum[1] = s1, sum[2] = s2, sum[3] = s3, sum[4] = s4, sum[5] = s5, sum[6] = s6, sum[7] = s7;
}

template <int N>
[[gnu::always_inline]] inline void backward_supernode(const SupernodalFactor& f, int s, double* X, double* W) {
  constexpr int P = Row<N>::kParts;
  const int c0 = f.first_column[s], nc = f.first_column[s + 1] - c0, nr = f.row_start[s + 1] - f.row_start[s];
  const int* rows = f.rows + f.row_start[s];
  const double* block = f.values + f.value_start[s];
  for (int i = 0; i < nc; ++i) store_row<N>(W + N * i, load_row<N>(X + N * (c0 + i)));
  for (int i = nc; i < nr; ++i) store_row<N>(W + N * i, load_row<N>(X + N * rows[i]));
  const int last = nc % kPanel == 0 ? kPanel : nc % kPanel;  // the last panel may be narrower
  for (int j0 = nc - last; j0 >= 0; j0 -= kPanel) {
    const int width = std::min(kPanel, nc - j0), end = j0 + width;
    for (int q = 0; q < P; ++q) {  // each register's lanes through the panel in turn
      double* Wq = W + 4 * q;
      Lanes sum[kPanel] = {};
      if (width == kPanel) {
        const double* l[kPanel];
        for (int k = 0; k < kPanel; ++k) l[k] = block + static_cast<size_t>(j0 + k) * nr;
        backward_panel_sums(l, Wq, N, end, nr, sum);
      } else {
        for (int j = j0; j < end; ++j) {
          const double* col = block + static_cast<size_t>(j) * nr;
          Lanes acc = {};
          for (int i = end; i < nr; ++i) acc += col[i] * load(Wq + N * i);
          sum[j - j0] = acc;
        }
      }
      for (int j = end - 1; j >= j0; --j) {  // the panel's own triangle
        const double* col = block + static_cast<size_t>(j) * nr;
        Lanes acc = sum[j - j0];
        for (int i = j + 1; i < end; ++i) acc += col[i] * load(Wq + N * i);
        store(Wq + N * j, (load(Wq + N * j) - acc) / col[j]);
      }
    }
  }
  for (int i = 0; i < nc; ++i) store_row<N>(X + N * (c0 + i), load_row<N>(W + N * i));
}

}  // namespace slim::sweeps
