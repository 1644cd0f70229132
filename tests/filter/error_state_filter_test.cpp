// The structured covariance operations of ErrorStateFilter against dense references computed in
// long double: propagation by blocks against Phi P Phi^T + Q, the expanded Joseph update against
// the textbook (I - K H) P (I - K H)^T + K R K^T, on random SPD covariances with random
// block-diagonal tails of mixed block sizes (1, 2, 3), for dense heads of 15 and 21 states.

#include "stochnav/filter/error_state_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace stochnav {
namespace {

using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& engine) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = normal(engine);
  }
  return m;
}

// Symmetric positive definite with eigenvalues spread over a few decades, like a covariance
// mixing metres and radians.
Eigen::MatrixXd random_spd(Eigen::Index n, std::mt19937_64& engine) {
  const Eigen::MatrixXd a = random_matrix(n, n, engine);
  Eigen::VectorXd scale(n);
  std::uniform_real_distribution<double> exponent(-3.0, 1.0);
  for (Eigen::Index i = 0; i < n; ++i) scale(i) = std::pow(10.0, exponent(engine));
  const Eigen::MatrixXd spd =
      a * a.transpose() / static_cast<double>(n) + 0.1 * Eigen::MatrixXd::Identity(n, n);
  return scale.asDiagonal() * spd * scale.asDiagonal();
}

// One augmented group: a random block-diagonal tail of blocks of 1, 2 or 3 states.
struct RandomSegment {
  int offset = 0;
  BlockDiagonalStructure blocks;
  Eigen::MatrixXd phi, q, coupling;
  BlockDiagonalMatrix transition, noise;  // phi and q on blocks
  Eigen::Matrix3d gain;                   // coupling = gain * map
  Eigen::MatrixXd map;                    // 3 x size, one or two nonzeros per column
  SparseMap sparse_map;
  int coupling_row = 0;
};

RandomSegment random_segment(int offset, int size, int head_size, std::mt19937_64& engine) {
  RandomSegment segment;
  segment.offset = offset;
  Eigen::MatrixXd pattern = Eigen::MatrixXd::Zero(size, size);
  std::uniform_int_distribution<int> block_size(1, 3);
  for (int i = 0; i < size;) {
    const int b = std::min(block_size(engine), size - i);
    pattern.block(i, i, b, b).setOnes();
    i += b;
  }
  segment.blocks = BlockDiagonalStructure(size).cover(pattern);
  segment.phi = random_matrix(size, size, engine).cwiseProduct(pattern);
  segment.phi.diagonal().array() += 1.0;
  segment.q = Eigen::MatrixXd::Zero(size, size);
  for (const auto& block : segment.blocks.blocks()) {
    if (block.diagonal) {
      segment.q.diagonal().segment(block.offset, block.size) =
          random_matrix(block.size, 1, engine).cwiseAbs();
    } else {
      segment.q.block(block.offset, block.offset, block.size, block.size) =
          random_spd(block.size, engine);
    }
  }
  segment.transition.assign(segment.blocks, segment.phi);
  segment.noise.assign(segment.blocks, segment.q);
  segment.gain = random_matrix(3, 3, engine);
  segment.map = Eigen::MatrixXd::Zero(3, size);
  std::uniform_int_distribution<int> axis(0, 2);
  for (int j = 0; j < size; ++j) {
    segment.map(axis(engine), j) = 1.0 + random_matrix(1, 1, engine)(0, 0);
    if (j % 5 == 0) segment.map(axis(engine), j) = 0.5;  // a state driving two axes
  }
  segment.sparse_map = SparseMap(segment.map);
  segment.coupling = segment.gain * segment.map;
  segment.coupling_row = std::uniform_int_distribution<int>(0, head_size - 3)(engine);
  return segment;
}

struct RandomTransition {
  Eigen::MatrixXd head_phi, head_q;
  std::vector<RandomSegment> segments;
  Eigen::MatrixXd dense_phi, dense_q;  // n x n
};

RandomTransition random_transition(int head_size, const std::vector<int>& segment_sizes,
                                   std::mt19937_64& engine) {
  RandomTransition t;
  int n = head_size;
  for (int size : segment_sizes) n += size;
  t.head_phi = Eigen::MatrixXd::Identity(head_size, head_size) +
               0.1 * random_matrix(head_size, head_size, engine);
  t.head_q = random_spd(head_size, engine);
  t.dense_phi = Eigen::MatrixXd::Zero(n, n);
  t.dense_q = Eigen::MatrixXd::Zero(n, n);
  t.dense_phi.topLeftCorner(head_size, head_size) = t.head_phi;
  t.dense_q.topLeftCorner(head_size, head_size) = t.head_q;
  int offset = head_size;
  for (int size : segment_sizes) {
    RandomSegment s = random_segment(offset, size, head_size, engine);
    t.dense_phi.block(offset, offset, size, size) = s.phi;
    t.dense_q.block(offset, offset, size, size) = s.q;
    t.dense_phi.block(s.coupling_row, offset, 3, size) = s.coupling;
    t.segments.push_back(std::move(s));
    offset += size;
  }
  return t;
}

double relative_error(const Eigen::MatrixXd& value, const MatrixL& reference) {
  const MatrixL difference = value.cast<long double>() - reference;
  return static_cast<double>(difference.norm() / reference.norm());
}

struct Case {
  int head_size;
  std::vector<int> segment_sizes;
};

class StructuredCovariance : public ::testing::TestWithParam<Case> {};

TEST_P(StructuredCovariance, PropagationEqualsTheDenseProducts) {
  const Case& c = GetParam();
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    std::mt19937_64 engine(seed);
    const RandomTransition t = random_transition(c.head_size, c.segment_sizes, engine);
    const Eigen::MatrixXd p = random_spd(t.dense_phi.rows(), engine);
    std::vector<TailSegment> tail;
    for (const RandomSegment& s : t.segments) {
      tail.push_back(
          TailSegment{s.offset, s.transition, s.noise, s.coupling_row, s.gain, s.sparse_map});
    }
    ErrorStateFilter filter(p);
    filter.propagate(BlockTransition{t.head_phi, t.head_q, tail});
    // Twice: the second time from the propagated (no longer random) P and reused scratch.
    filter.propagate(BlockTransition{t.head_phi, t.head_q, tail});

    const MatrixL phi = t.dense_phi.cast<long double>();
    const MatrixL q = t.dense_q.cast<long double>();
    MatrixL reference = p.cast<long double>();
    for (int i = 0; i < 2; ++i) reference = phi * reference * phi.transpose() + q;
    EXPECT_LT(relative_error(filter.covariance(), reference), 1e-12) << "seed " << seed;
    EXPECT_EQ(filter.covariance(), filter.covariance().transpose());
    EXPECT_TRUE(filter.health().ok());

    ErrorStateFilter dense(p);
    dense.propagate(t.dense_phi, t.dense_q);
    dense.propagate(t.dense_phi, t.dense_q);
    EXPECT_LT(relative_error(dense.covariance(), reference), 1e-12) << "seed " << seed;
  }
}

TEST_P(StructuredCovariance, ExpandedJosephUpdateEqualsTheTextbookJosephForm) {
  const Case& c = GetParam();
  int n = c.head_size;
  for (int size : c.segment_sizes) n += size;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    std::mt19937_64 engine(100 + seed);
    const Eigen::MatrixXd p = random_spd(n, engine);
    const int m = 6;
    const Eigen::MatrixXd h = random_matrix(m, c.head_size, engine);  // head columns only
    const Eigen::MatrixXd r = random_spd(m, engine);
    const Eigen::VectorXd z = random_matrix(m, 1, engine);

    ErrorStateFilter filter(p);
    Eigen::VectorXd correction = Eigen::VectorXd::Zero(n);
    const UpdateOutcome outcome = filter.update(z, h, r, INFINITY, correction);
    ASSERT_TRUE(outcome.accepted);

    MatrixL h_full = MatrixL::Zero(m, n);
    h_full.leftCols(c.head_size) = h.cast<long double>();
    const MatrixL pl = p.cast<long double>();
    const MatrixL s = h_full * pl * h_full.transpose() + r.cast<long double>();
    const MatrixL k = pl * h_full.transpose() * s.inverse();
    MatrixL i_kh = -k * h_full;
    i_kh.diagonal().array() += 1.0L;
    const MatrixL reference =
        i_kh * pl * i_kh.transpose() + k * r.cast<long double>() * k.transpose();
    EXPECT_LT(relative_error(filter.covariance(), reference), 1e-12) << "seed " << seed;
    EXPECT_LT(relative_error(correction, k * z.cast<long double>()), 1e-12) << "seed " << seed;
    EXPECT_LT(relative_error(filter.last_gain(), k), 1e-12) << "seed " << seed;
    const long double nis = z.cast<long double>().dot(s.inverse() * z.cast<long double>());
    EXPECT_NEAR(outcome.nis, static_cast<double>(nis), 1e-12 * static_cast<double>(nis));
    EXPECT_EQ(filter.covariance(), filter.covariance().transpose());

    // The textbook product form through the same call gives the same result.
    ErrorStateFilter product(p);
    Eigen::VectorXd product_correction = Eigen::VectorXd::Zero(n);
    product.update(z, h, r, INFINITY, product_correction, JosephForm::kProduct);
    EXPECT_LT(relative_error(product.covariance(), reference), 1e-12) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(HeadSizes, StructuredCovariance,
                         ::testing::Values(Case{15, {}}, Case{15, {40, 30}}, Case{21, {50, 1}},
                                           Case{21, {0, 37}}, Case{15, {100}}),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           std::string name = "head" + std::to_string(param_info.param.head_size);
                           for (int size : param_info.param.segment_sizes) {
                             name += "_tail" + std::to_string(size);
                           }
                           return name;
                         });

TEST(ErrorStateFilter, NonFiniteStructuredPropagationResetsToTheInitialCovariance) {
  std::mt19937_64 engine(6);
  RandomTransition t = random_transition(15, {10, 8}, engine);
  const Eigen::MatrixXd p = random_spd(33, engine);
  ErrorStateFilter filter(p);
  t.head_phi(4, 2) = std::numeric_limits<double>::infinity();
  std::vector<TailSegment> tail;
  for (const RandomSegment& s : t.segments) {
    tail.push_back(
        TailSegment{s.offset, s.transition, s.noise, s.coupling_row, s.gain, s.sparse_map});
  }
  filter.propagate(BlockTransition{t.head_phi, t.head_q, tail});
  EXPECT_EQ(filter.health().non_finite, 1u);
  EXPECT_EQ(filter.covariance(), p);
}

TEST(ErrorStateFilter, SingularInnovationIsCountedAndSkipped) {
  std::mt19937_64 engine(7);
  const Eigen::MatrixXd p = random_spd(20, engine);
  ErrorStateFilter filter(p);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 15);
  h(0, 0) = 1.0;
  h(1, 0) = 1.0;  // S singular with R = 0
  Eigen::VectorXd correction = Eigen::VectorXd::Zero(20);
  const UpdateOutcome outcome =
      filter.update(Eigen::Vector2d(1.0, 1.0), h, Eigen::Matrix2d::Zero(), INFINITY, correction);
  EXPECT_TRUE(outcome.singular);
  EXPECT_FALSE(outcome.accepted);
  EXPECT_TRUE(std::isnan(outcome.nis));
  EXPECT_EQ(filter.health().singular_innovations, 1u);
  EXPECT_EQ(filter.covariance(), p);
  EXPECT_TRUE(correction.isZero(0.0));
}

TEST(ErrorStateFilter, GatedUpdateLeavesCovarianceAndCorrectionUnchanged) {
  std::mt19937_64 engine(8);
  const Eigen::MatrixXd p = random_spd(18, engine);
  ErrorStateFilter filter(p);
  const Eigen::MatrixXd h = Eigen::MatrixXd::Identity(3, 15);
  Eigen::VectorXd correction = Eigen::VectorXd::Constant(18, 2.0);
  const UpdateOutcome outcome = filter.update(Eigen::Vector3d(100.0, 100.0, 100.0), h,
                                              Eigen::Matrix3d::Identity(), 10.0, correction);
  EXPECT_FALSE(outcome.accepted);
  EXPECT_GT(outcome.nis, 10.0);
  EXPECT_EQ(filter.covariance(), p);
  EXPECT_EQ(correction, Eigen::VectorXd::Constant(18, 2.0));
  EXPECT_TRUE(filter.last_gain().isZero(0.0));
}

// A consider state (Schmidt-Kalman): never corrected, its variance unchanged by an update, and
// P is the covariance of the errors the suboptimal gain leaves: checked against the Joseph
// product with that gain in long double, and by Monte Carlo (the optimal filter's P - K S K^T
// with the gain's row zeroed would understate the errors; the Monte-Carlo check sees that).
TEST(ErrorStateFilter, ConsiderStateIsNeverCorrectedAndPIsTheErrorsCovariance) {
  std::mt19937_64 engine(9);
  constexpr int kStates = 6;
  constexpr int kConsidered = 2;
  const Eigen::MatrixXd p = random_spd(kStates, engine);
  Eigen::MatrixXd h = random_matrix(2, kStates, engine);
  const Eigen::Matrix2d r = Eigen::Vector2d(0.3, 0.7).asDiagonal() * p.diagonal().mean();
  ErrorStateFilter filter(p);
  filter.consider(kConsidered);
  Eigen::VectorXd correction = Eigen::VectorXd::Zero(kStates);
  const Eigen::Vector2d z = random_matrix(2, 1, engine);
  ASSERT_TRUE(filter.update(z, h, r, INFINITY, correction).accepted);
  EXPECT_EQ(correction(kConsidered), 0.0);
  EXPECT_TRUE(filter.last_gain().row(kConsidered).isZero(0.0));
  EXPECT_NEAR(filter.covariance()(kConsidered, kConsidered), p(kConsidered, kConsidered),
              1e-12 * p(kConsidered, kConsidered));

  // The Joseph product with the optimal gain's considered row zeroed, in long double.
  const MatrixL pl = p.cast<long double>();
  const MatrixL hl = h.cast<long double>();
  const MatrixL s = hl * pl * hl.transpose() + r.cast<long double>();
  MatrixL k = pl * hl.transpose() * s.inverse();
  k.row(kConsidered).setZero();
  const MatrixL i_kh = MatrixL::Identity(kStates, kStates) - k * hl;
  const MatrixL expected =
      i_kh * pl * i_kh.transpose() + k * r.cast<long double>() * k.transpose();
  EXPECT_LT((filter.covariance().cast<long double>() - expected).norm(), 1e-12L * pl.norm());
  // The estimated states' gains are the optimal ones.
  const MatrixL optimal = pl * hl.transpose() * s.inverse();
  for (int i = 0; i < kStates; ++i) {
    if (i == kConsidered) continue;
    EXPECT_LT((filter.last_gain().row(i).cast<long double>() - optimal.row(i)).norm(),
              1e-12L * optimal.norm());
  }

  // Monte Carlo: errors x - K (H x + v) over draws of x ~ N(0, P), v ~ N(0, R).
  const Eigen::LLT<Eigen::MatrixXd> p_factor(p);
  const Eigen::LLT<Eigen::Matrix2d> r_factor(r);
  const Eigen::MatrixXd gain = filter.last_gain();
  constexpr int kDraws = 40000;
  Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(kStates, kStates);
  for (int draw = 0; draw < kDraws; ++draw) {
    const Eigen::VectorXd x = p_factor.matrixL() * random_matrix(kStates, 1, engine);
    const Eigen::Vector2d v = r_factor.matrixL() * random_matrix(2, 1, engine);
    const Eigen::VectorXd error = x - gain * (h * x + v);
    scatter += error * error.transpose();
  }
  scatter /= kDraws;
  for (int i = 0; i < kStates; ++i) {
    // The sample variance of kDraws Gaussian draws: relative sigma sqrt(2 / kDraws) = 0.7 %.
    EXPECT_NEAR(scatter(i, i) / filter.covariance()(i, i), 1.0, 0.04) << "state " << i;
  }
}

}  // namespace
}  // namespace stochnav
