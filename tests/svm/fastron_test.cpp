// Fastron (svm/fastron.hpp): the model's value against a brute-force double sum through svm::Kernel
// (rational quadratic, plain and block-sum), Algorithm 1's guarantees (positive margin on every
// training point, no redundant support point left), warm start, limits and bad input.
#include <gtest/gtest.h>

#include <random>

#include "svm/fastron.hpp"
#include "svm/kernel.hpp"

namespace svmp::svm {
namespace {

struct Data {
  std::vector<float> x;
  std::vector<std::int8_t> y;
};

// n points in [-1, 1]^dim, in collision (+1) inside a ball around (centre, ..., centre).
Data ballData(int n, int dim, std::uint64_t seed, double centre = 0.3) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  Data d;
  for (int i = 0; i < n; ++i) {
    double r2 = 0;
    for (int k = 0; k < dim; ++k) {
      const float v = u(rng);
      d.x.push_back(v);
      r2 += (v - centre) * (v - centre);
    }
    d.y.push_back(r2 < 0.36 * dim / 2 ? 1 : -1);
  }
  return d;
}

// f(q) in double; `magnitude` gets sum |alpha_i| k(x_i, q), the scale of float rounding errors.
double bruteForce(const Data& d, const std::vector<double>& alpha, int dim, int block, double gamma,
                  const float* q, double* magnitude = nullptr) {
  Kernel base;
  base.type = KernelType::kRationalQuadratic;
  base.gamma = gamma;
  const Kernel k = block == dim ? base : Kernel::blockSum(base, block);
  std::vector<double> qd(q, q + dim), xi(dim);
  double f = 0, m = 0;
  for (size_t i = 0; i < alpha.size(); ++i) {
    if (alpha[i] == 0) continue;
    for (int c = 0; c < dim; ++c) xi[c] = d.x[i * dim + c];
    const double term = alpha[i] * k.value(xi.data(), qd.data(), dim);
    f += term;
    m += std::abs(term);
  }
  if (magnitude) *magnitude = m;
  return f;
}

class FastronKernels : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(FastronKernels, ConvergesAndEvaluatesAsTheBruteForceSum) {
  const auto [dim, block] = GetParam();
  const Data d = ballData(1500, dim, 3);
  FastronOptions o;
  o.gamma = 5;
  o.beta = 2;
  FastronModel model(dim, block, o);
  std::vector<double> alpha(d.y.size(), 0.0);
  const FastronTrainStats s = model.train(d.x, d.y, alpha);
  ASSERT_TRUE(s.converged) << "min margin " << s.min_margin << " after " << s.steps << " steps";
  EXPECT_GT(s.support, 10);
  EXPECT_LT(s.support, 1500);
  EXPECT_EQ(s.support, model.size());
  const double kii = dim / block;
  for (size_t i = 0; i < d.y.size(); ++i) {
    const double f = model.value(&d.x[i * dim]);
    double magnitude = 0;
    const double exact = bruteForce(d, alpha, dim, block, o.gamma, &d.x[i * dim], &magnitude);
    ASSERT_NEAR(f, exact, 1e-5 * magnitude + 1e-9) << "point " << i;
    EXPECT_GT(d.y[i] * exact, 0) << "training point " << i << " misclassified";
    // No redundant support point left: without its own weight a support point would be wrong.
    if (alpha[i] != 0) {
      EXPECT_LE(d.y[i] * (exact - alpha[i] * kii), 1e-9) << "support point " << i;
    }
  }
  // Off the training set too.
  const Data q = ballData(37, dim, 99);
  for (int b = 0; b < 37; ++b) {
    double magnitude = 0;
    const double exact = bruteForce(d, alpha, dim, block, o.gamma, &q.x[b * dim], &magnitude);
    EXPECT_NEAR(model.value(&q.x[b * dim]), exact, 1e-5 * magnitude + 1e-9);
  }
}

// (dim, block): Fastron RBF on 7 joints; the FK kernel on 5 control points; one odd block size.
INSTANTIATE_TEST_SUITE_P(Kernels, FastronKernels,
                         ::testing::Values(std::pair{7, 7}, std::pair{15, 3}, std::pair{6, 2}, std::pair{2, 2}));

TEST(Fastron, WarmStartFromAConvergedModelDoesNothing) {
  const Data d = ballData(800, 3, 5);
  FastronModel model(3, 3, FastronOptions{});
  std::vector<double> alpha(d.y.size(), 0.0);
  ASSERT_TRUE(model.train(d.x, d.y, alpha).converged);
  const std::vector<double> before = alpha;
  const FastronTrainStats again = model.train(d.x, d.y, alpha);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(again.steps, 0);
  EXPECT_EQ(alpha, before);
}

// Starting from the old weights is not always fewer steps (the old support must be moved or removed),
// but it must end with every new label learned.
TEST(Fastron, WarmStartAfterTheObstacleMovedLearnsTheNewLabels) {
  const Data before = ballData(2000, 3, 6, 0.3), after = ballData(2000, 3, 6, 0.35);  // same points, ball moved
  FastronModel warm(3, 3, FastronOptions{}), cold(3, 3, FastronOptions{});
  std::vector<double> alpha(before.y.size(), 0.0), zeros(before.y.size(), 0.0);
  ASSERT_TRUE(warm.train(before.x, before.y, alpha).converged);
  const FastronTrainStats w = warm.train(after.x, after.y, alpha);
  const FastronTrainStats c = cold.train(after.x, after.y, zeros);
  ASSERT_TRUE(w.converged);
  ASSERT_TRUE(c.converged);
  EXPECT_GT(w.removed + w.adjusted, 0);  // the old support was revised, not just added to
  for (size_t i = 0; i < after.y.size(); ++i) EXPECT_GT(after.y[i] * warm.value(&after.x[i * 3]), 0) << i;
}

TEST(Fastron, LimitsAndAStopBoundStepsAndSupport) {
  const Data d = ballData(1000, 3, 7);
  FastronOptions o;
  o.max_support = 10;
  FastronModel small(3, 3, o);
  std::vector<double> alpha(d.y.size(), 0.0);
  EXPECT_LE(small.train(d.x, d.y, alpha).support, 10);
  o = FastronOptions{};
  o.max_updates = 5;
  FastronModel brief(3, 3, o);
  std::fill(alpha.begin(), alpha.end(), 0.0);
  const FastronTrainStats s = brief.train(d.x, d.y, alpha);
  EXPECT_LE(s.steps, 5);
  EXPECT_FALSE(s.converged);
  // The caller's stop ends the updates where they are: after exactly as many as it allowed.
  FastronModel stopped(3, 3, FastronOptions{});
  std::fill(alpha.begin(), alpha.end(), 0.0);
  int polls = 0;
  const FastronTrainStats t = stopped.train(d.x, d.y, alpha, [&] { return ++polls > 7; });
  EXPECT_TRUE(t.stopped);
  EXPECT_FALSE(t.converged);
  EXPECT_EQ(t.steps, 7);
  EXPECT_EQ(t.support, stopped.size());
}

TEST(Fastron, BadInputIsRefused) {
  FastronOptions o;
  o.gamma = -1;
  EXPECT_THROW(FastronModel(3, 3, o), std::invalid_argument);
  EXPECT_THROW(FastronModel(4, 3, FastronOptions{}), std::invalid_argument);  // 4 is not a multiple of 3
  FastronModel model(2, 2, FastronOptions{});
  std::vector<float> x = {0, 0, 1, 1};
  std::vector<std::int8_t> y = {1, 2};
  std::vector<double> alpha(2, 0.0);
  EXPECT_THROW(model.train(x, y, alpha), std::invalid_argument);
  y = {1, -1};
  x[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(model.train(x, y, alpha), std::invalid_argument);
  x[3] = 1;
  alpha.resize(3);
  EXPECT_THROW(model.train(x, y, alpha), std::invalid_argument);
}

}  // namespace
}  // namespace svmp::svm
