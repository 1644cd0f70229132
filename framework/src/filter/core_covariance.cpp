#include "stochnav/filter/core_covariance.hpp"

namespace stochnav {
namespace {

constexpr int kNav = 9;    // position, velocity, attitude
constexpr int kBias = 6;   // accelerometer and gyro biases
constexpr int kCore = 15;  // kNav + kBias
// Rows of T and P'_nn are computed in columns padded from 9 to 12: whole SIMD registers, no
// scalar tail (the 3 extra rows, read from Phi's rows 9..11, are never used).
constexpr int kPadded = 12;

// x86-64: an AVX2 clone chosen at load time where the CPU has it (4 doubles per instruction),
// the baseline SSE2 code elsewhere. Neither contracts to FMA (AVX2 does not imply it), and each
// entry is summed in the same order by both: bit-identical results on every machine. No clones
// under the thread sanitizer: their IFUNC resolver would run, instrumented, before libtsan is
// initialised (stats/vector_clones.hpp).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_THREAD__)
#define STOCHNAV_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define STOCHNAV_SIMD_CLONES
#endif

// The kernel of propagate_core_covariance on column-major storage: phi and q with 15 rows per
// column, p with `p_stride`.
STOCHNAV_SIMD_CLONES void propagate_core_kernel(const double* phi, const double* q, double* p,
                                                long p_stride) {
  // T = [A B] P (9 x 15), column j = sum_k Phi(:, k) P(k, j).
  alignas(32) double t[kCore][kPadded];
  for (int j = 0; j < kCore; ++j) {
    double column[kPadded] = {};
    for (int k = 0; k < kCore; ++k) {
      const double p_kj = p[j * p_stride + k];
      const double* phi_k = phi + k * kCore;
      for (int i = 0; i < kPadded; ++i) column[i] += phi_k[i] * p_kj;
    }
    for (int i = 0; i < kPadded; ++i) t[j][i] = column[i];
  }
  // P'_nn - Q_nn = T [A B]^T (9 x 9), column j = sum_k T(:, k) Phi(j, k).
  alignas(32) double next_nn[kNav][kPadded];
  for (int j = 0; j < kNav; ++j) {
    double column[kPadded] = {};
    for (int k = 0; k < kCore; ++k) {
      const double phi_jk = phi[k * kCore + j];
      for (int i = 0; i < kPadded; ++i) column[i] += t[k][i] * phi_jk;
    }
    for (int i = 0; i < kPadded; ++i) next_nn[j][i] = column[i];
  }
  // P' from the lower triangles, mirrored: P'_nn, then P'_bn = T_b^T + Q_bn, then P_bb + Q_bb.
  const auto set = [p, p_stride](int i, int j, double value) {
    p[j * p_stride + i] = value;
    p[i * p_stride + j] = value;
  };
  for (int j = 0; j < kNav; ++j) {
    for (int i = j; i < kNav; ++i) set(i, j, next_nn[j][i] + q[j * kCore + i]);
  }
  for (int j = 0; j < kNav; ++j) {
    for (int i = kNav; i < kCore; ++i) set(i, j, t[i][j] + q[j * kCore + i]);
  }
  for (int j = kNav; j < kCore; ++j) {
    for (int i = j; i < kCore; ++i) set(i, j, p[j * p_stride + i] + q[j * kCore + i]);
  }
}

// out += F^2 / 2 on F's first 9 rows (F's last 6 rows are zero): column j of F^2 is
// sum_{k < 9} F(:, k) F(k, j), over the nonzero F(k, j) only (about half: F's first column,
// most of the position rows and the bias columns are zero). f and out column-major, 15 rows
// per column.
STOCHNAV_SIMD_CLONES void add_half_square(const double* f, double* out) {
  for (int j = 0; j < kCore; ++j) {
    alignas(32) double column[kPadded] = {};
    for (int k = 0; k < kNav; ++k) {
      const double f_kj = f[j * kCore + k];
      if (f_kj == 0.0) continue;
      const double* f_k = f + k * kCore;
      for (int i = 0; i < kPadded; ++i) column[i] += f_k[i] * f_kj;
    }
    // All 12 lanes stored and read back (rows 9..11 of F^2 are zero, F's bias rows being zero):
    // with only 9 of them live the compiler would keep the sums in scalar registers.
    double* out_j = out + j * kCore;
    for (int i = 0; i < kNav; ++i) out_j[i] += 0.5 * column[i];
    for (int i = kNav; i < kPadded; ++i) out_j[i] += 0.5 * column[i];
  }
}

}  // namespace

bool has_constant_bias_rows(const Eigen::Ref<const CoreMatrix>& phi) {
  return phi.bottomLeftCorner<kBias, kNav>().cwiseAbs().sum() == 0.0 &&
         phi.bottomRightCorner<kBias, kBias>() == Eigen::Matrix<double, kBias, kBias>::Identity();
}

void propagate_core_covariance(const CoreMatrix& phi, const CoreMatrix& q_d,
                               Eigen::Ref<CoreMatrix> p) {
  propagate_core_kernel(phi.data(), q_d.data(), p.data(), static_cast<long>(p.outerStride()));
}

CoreMatrix second_order_transition_increment(const CoreMatrix& f) {
  CoreMatrix increment = f;
  add_half_square(f.data(), increment.data());
  return increment;
}

}  // namespace stochnav
