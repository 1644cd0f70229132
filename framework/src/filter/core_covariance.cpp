#include "stochnav/filter/core_covariance.hpp"

namespace stochnav {
namespace {

constexpr int kNav = 9;    // position, velocity, attitude
constexpr int kBias = 6;   // accelerometer and gyro biases
constexpr int kCore = 15;  // kNav + kBias
// Rows of T and P'_nn are computed in columns padded from 9 to 12: whole SIMD registers, no
// scalar tail (the 3 extra rows, read from Phi's rows 9..11, are never used).
constexpr int kPadded = 12;
// Three 4-lane vectors hold a padded column of 12 doubles (GCC's vector extension: one AVX2
// register each, two SSE2 registers in the default clone). Loads and stores through a type that
// may alias doubles at any 8-byte alignment.
using Lanes = double __attribute__((vector_size(32)));
using UnalignedLanes = double __attribute__((vector_size(32), aligned(8), may_alias));

// Three columns of a product at once, out(:, c) = sum_k column(k)(:) * scalar(k, c) over k < N,
// each entry summed in k order (the same bits as one column at a time): each entry is a chain
// of N dependent additions, and one column's three register-wide chains leave the adder idle
// for most of each addition's latency; three columns fill it (9 accumulators, 3 loads and a
// broadcast: 13 of the 16 AVX2 registers).
template <int N, typename Column, typename Scalar>
[[gnu::always_inline]] inline void three_columns(Column column, Scalar scalar, double* out0,
                                                 double* out1, double* out2) {
  Lanes s00{}, s01{}, s02{}, s10{}, s11{}, s12{}, s20{}, s21{}, s22{};
  for (int k = 0; k < N; ++k) {
    const auto* c = reinterpret_cast<const UnalignedLanes*>(column(k));
    const Lanes f0 = c[0], f1 = c[1], f2 = c[2];
    double x = scalar(k, 0);
    Lanes b = {x, x, x, x};
    s00 += f0 * b;
    s01 += f1 * b;
    s02 += f2 * b;
    x = scalar(k, 1);
    b = Lanes{x, x, x, x};
    s10 += f0 * b;
    s11 += f1 * b;
    s12 += f2 * b;
    x = scalar(k, 2);
    b = Lanes{x, x, x, x};
    s20 += f0 * b;
    s21 += f1 * b;
    s22 += f2 * b;
  }
  for (const auto& [out, first, second, third] :
       {std::tuple{out0, s00, s01, s02}, std::tuple{out1, s10, s11, s12},
        std::tuple{out2, s20, s21, s22}}) {
    auto* lanes = reinterpret_cast<UnalignedLanes*>(out);
    lanes[0] = first;
    lanes[1] = second;
    lanes[2] = third;
  }
}

// x86-64: an AVX2 clone chosen at load time where the CPU has it (4 doubles per instruction),
// the baseline SSE2 code elsewhere. Neither contracts to FMA (AVX2 does not imply it), and each
// entry is summed in the same order by both: bit-identical results on every machine. No clones
// under the thread sanitizer: their IFUNC resolver would run, instrumented, before libtsan is
// initialised (stats/vector_clones.hpp). The kernels are templates on the state size, inlined
// into one cloned function per size (GCC clones functions, not templates).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_THREAD__)
#define STOCHNAV_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define STOCHNAV_SIMD_CLONES
#endif

// The kernel of propagate_nav_diagonal_covariance on column-major storage: phi and q with N rows
// per column, p with `p_stride`.
template <int N>
[[gnu::always_inline]] inline void propagate_nav_diagonal_body(const double* phi, const double* q,
                                                               double* p, long p_stride) {
  static_assert(N >= kPadded);
  static_assert(N % 3 == 0 && kNav % 3 == 0);
  // T = [A B] P (9 x N), column j = sum_k Phi(:, k) P(k, j).
  alignas(32) double t[N][kPadded];
  for (int j = 0; j < N; j += 3) {
    three_columns<N>([phi](int k) { return phi + k * N; },
                     [p, p_stride, j](int k, int c) { return p[(j + c) * p_stride + k]; }, t[j],
                     t[j + 1], t[j + 2]);
  }
  // P'_nn - Q_nn = T [A B]^T (9 x 9), column j = sum_k T(:, k) Phi(j, k).
  alignas(32) double next_nn[kNav][kPadded];
  for (int j = 0; j < kNav; j += 3) {
    three_columns<N>([&t](int k) { return t[k]; },
                     [phi, j](int k, int c) { return phi[k * N + j + c]; }, next_nn[j],
                     next_nn[j + 1], next_nn[j + 2]);
  }
  // P' from the lower triangles, mirrored: P'_nn, then P'_bn = D T_b^T + Q_bn, then
  // D P_bb D + Q_bb.
  const auto set = [p, p_stride](int i, int j, double value) {
    p[j * p_stride + i] = value;
    p[i * p_stride + j] = value;
  };
  const auto d = [phi](int i) { return phi[i * N + i]; };
  for (int j = 0; j < kNav; ++j) {
    for (int i = j; i < kNav; ++i) set(i, j, next_nn[j][i] + q[j * N + i]);
  }
  for (int j = 0; j < kNav; ++j) {
    for (int i = kNav; i < N; ++i) set(i, j, d(i) * t[i][j] + q[j * N + i]);
  }
  for (int j = kNav; j < N; ++j) {
    for (int i = j; i < N; ++i) set(i, j, d(i) * p[j * p_stride + i] * d(j) + q[j * N + i]);
  }
}

// out += F^2 / 2 on F's first 9 rows (F's last N - 9 rows are zero): column j of F^2 is
// sum_{k < 9} F(:, k) F(k, j), over the nonzero F(k, j) only (about half: F's first column,
// most of the position rows and the bias columns are zero). f and out column-major, N rows
// per column.
template <int N>
[[gnu::always_inline]] inline void add_half_square_body(const double* f, double* out) {
  for (int j = 0; j < N; ++j) {
    alignas(32) double column[kPadded] = {};
    for (int k = 0; k < kNav; ++k) {
      const double f_kj = f[j * N + k];
      if (f_kj == 0.0) continue;
      const double* f_k = f + k * N;
      for (int i = 0; i < kPadded; ++i) column[i] += f_k[i] * f_kj;
    }
    // All 12 lanes stored and read back (rows 9..11 of F^2 are zero, F's trailing rows being
    // zero): with only 9 of them live the compiler would keep the sums in scalar registers.
    double* out_j = out + j * N;
    for (int i = 0; i < kNav; ++i) out_j[i] += 0.5 * column[i];
    for (int i = kNav; i < kPadded; ++i) out_j[i] += 0.5 * column[i];
  }
}

// One cloned entry point per supported size.
#define STOCHNAV_NAV_DIAGONAL_KERNELS(N)                                                         \
  STOCHNAV_SIMD_CLONES void propagate_nav_diagonal_kernel_##N(const double* phi, const double* q, \
                                                              double* p, long p_stride) {         \
    propagate_nav_diagonal_body<N>(phi, q, p, p_stride);                                          \
  }                                                                                               \
  STOCHNAV_SIMD_CLONES void add_half_square_##N(const double* f, double* out) {                  \
    add_half_square_body<N>(f, out);                                                              \
  }
STOCHNAV_NAV_DIAGONAL_KERNELS(15)
STOCHNAV_NAV_DIAGONAL_KERNELS(18)
STOCHNAV_NAV_DIAGONAL_KERNELS(21)
STOCHNAV_NAV_DIAGONAL_KERNELS(24)
STOCHNAV_NAV_DIAGONAL_KERNELS(27)
#undef STOCHNAV_NAV_DIAGONAL_KERNELS

template <int N>
void propagate_nav_diagonal_kernel(const double* phi, const double* q, double* p, long stride) {
  static_assert(kHasNavDiagonalKernel<N>);
  if constexpr (N == 15) propagate_nav_diagonal_kernel_15(phi, q, p, stride);
  if constexpr (N == 18) propagate_nav_diagonal_kernel_18(phi, q, p, stride);
  if constexpr (N == 21) propagate_nav_diagonal_kernel_21(phi, q, p, stride);
  if constexpr (N == 24) propagate_nav_diagonal_kernel_24(phi, q, p, stride);
  if constexpr (N == 27) propagate_nav_diagonal_kernel_27(phi, q, p, stride);
}

template <int N>
void add_half_square(const double* f, double* out) {
  static_assert(kHasNavDiagonalKernel<N>);
  if constexpr (N == 15) add_half_square_15(f, out);
  if constexpr (N == 18) add_half_square_18(f, out);
  if constexpr (N == 21) add_half_square_21(f, out);
  if constexpr (N == 24) add_half_square_24(f, out);
  if constexpr (N == 27) add_half_square_27(f, out);
}

}  // namespace

bool has_constant_bias_rows(const Eigen::Ref<const CoreMatrix>& phi) {
  return phi.bottomLeftCorner<kBias, kNav>().cwiseAbs().sum() == 0.0 &&
         phi.bottomRightCorner<kBias, kBias>() == Eigen::Matrix<double, kBias, kBias>::Identity();
}

template <int N>
bool has_diagonal_trailing_rows(const NavDiagonalMatrix<N>& phi) {
  constexpr int kTrailing = N - kNav;
  Eigen::Matrix<double, kTrailing, N> off_diagonal = phi.template bottomRows<kTrailing>();
  off_diagonal.template rightCols<kTrailing>().diagonal().setZero();
  return off_diagonal.cwiseAbs().sum() == 0.0;
}

void propagate_core_covariance(const CoreMatrix& phi, const CoreMatrix& q_d,
                               Eigen::Ref<CoreMatrix> p) {
  propagate_nav_diagonal_covariance<kCore>(phi, q_d, p);
}

template <int N>
void propagate_nav_diagonal_covariance(const NavDiagonalMatrix<N>& phi,
                                       const NavDiagonalMatrix<N>& q_d,
                                       Eigen::Ref<NavDiagonalMatrix<N>> p) {
  propagate_nav_diagonal_kernel<N>(phi.data(), q_d.data(), p.data(),
                                   static_cast<long>(p.outerStride()));
}

CoreMatrix second_order_transition_increment(const CoreMatrix& f) {
  return second_order_transition_increment<kCore>(f);
}

template <int N>
NavDiagonalMatrix<N> second_order_transition_increment(const NavDiagonalMatrix<N>& f) {
  NavDiagonalMatrix<N> increment = f;
  add_half_square<N>(f.data(), increment.data());
  return increment;
}

#define STOCHNAV_INSTANTIATE_NAV_DIAGONAL(N)                                                    \
  template bool has_diagonal_trailing_rows<N>(const NavDiagonalMatrix<N>&);                     \
  template void propagate_nav_diagonal_covariance<N>(                                           \
      const NavDiagonalMatrix<N>&, const NavDiagonalMatrix<N>&, Eigen::Ref<NavDiagonalMatrix<N>>); \
  template NavDiagonalMatrix<N> second_order_transition_increment<N>(const NavDiagonalMatrix<N>&);
STOCHNAV_INSTANTIATE_NAV_DIAGONAL(15)
STOCHNAV_INSTANTIATE_NAV_DIAGONAL(18)
STOCHNAV_INSTANTIATE_NAV_DIAGONAL(21)
STOCHNAV_INSTANTIATE_NAV_DIAGONAL(24)
STOCHNAV_INSTANTIATE_NAV_DIAGONAL(27)
#undef STOCHNAV_INSTANTIATE_NAV_DIAGONAL

}  // namespace stochnav
