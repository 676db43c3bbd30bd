#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "svm/kernel.hpp"
#include "svm/kernel_cache.hpp"

namespace svmp::svm {
namespace {

std::vector<Kernel> allKernels() {
  std::vector<Kernel> ks;
  Kernel k;
  k.type = KernelType::kLinear;
  ks.push_back(k);
  k.type = KernelType::kPolynomial;
  k.gamma = 0.7;
  k.coef0 = 1.0;
  k.degree = 3;
  ks.push_back(k);
  ks.push_back(Kernel::rbfFromSigma(0.8));
  k.type = KernelType::kSigmoid;
  k.gamma = 0.3;
  k.coef0 = -0.2;
  ks.push_back(k);
  k.type = KernelType::kRationalQuadratic;
  k.gamma = 2.0;
  ks.push_back(k);
  ks.push_back(Kernel::blockSum(Kernel::rbfFromSigma(0.5), 3));
  Kernel rq;
  rq.type = KernelType::kRationalQuadratic;
  rq.gamma = 1.5;
  ks.push_back(Kernel::blockSum(rq, 2));
  return ks;
}

TEST(Kernel, GradientMatchesCentralDifferences) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 0.6);
  const int d = 6;
  for (const Kernel& k : allKernels()) {
    ASSERT_EQ(k.validate(d), "") << kernelTypeName(k.type);
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> x(d), y(d), g(d);
      for (int i = 0; i < d; ++i) {
        x[i] = normal(rng);
        y[i] = normal(rng);
      }
      const double v = k.valueAndGradientWrtY(x.data(), y.data(), d, g.data());
      EXPECT_NEAR(v, k.value(x.data(), y.data(), d), 1e-14 * (1 + std::abs(v)));
      std::vector<double> g2(d);
      k.gradientWrtY(x.data(), y.data(), d, g2.data());
      const double h = 1e-6;
      for (int i = 0; i < d; ++i) {
        EXPECT_EQ(g[i], g2[i]);
        std::vector<double> yp = y, ym = y;
        yp[i] += h;
        ym[i] -= h;
        const double fd =
            (k.value(x.data(), yp.data(), d) - k.value(x.data(), ym.data(), d)) / (2 * h);
        EXPECT_NEAR(g[i], fd, 1e-6 * (1 + std::abs(fd)))
            << kernelTypeName(k.type) << " block " << k.block << " coordinate " << i;
      }
    }
  }
}

TEST(Kernel, ValuesFollowTheirDefinitions) {
  const double x[2] = {0.3, -1.2}, y[2] = {1.1, 0.4};
  const double dist2 = 0.8 * 0.8 + 1.6 * 1.6, dot = 0.33 - 0.48;
  const Kernel rbf = Kernel::rbfFromSigma(0.5);
  EXPECT_DOUBLE_EQ(rbf.gamma, 2.0);
  EXPECT_NEAR(rbf.value(x, y, 2), std::exp(-2.0 * dist2), 1e-16);
  Kernel rq;
  rq.type = KernelType::kRationalQuadratic;
  rq.gamma = 3.0;
  EXPECT_NEAR(rq.value(x, y, 2), std::pow(1 + 1.5 * dist2, -2), 1e-15);
  Kernel poly;
  poly.type = KernelType::kPolynomial;
  poly.gamma = 0.5;
  poly.coef0 = 2;
  poly.degree = 2;
  EXPECT_NEAR(poly.value(x, y, 2), std::pow(0.5 * dot + 2, 2), 1e-15);
  Kernel sig;
  sig.type = KernelType::kSigmoid;
  sig.gamma = 0.5;
  sig.coef0 = 0.1;
  EXPECT_NEAR(sig.value(x, y, 2), std::tanh(0.5 * dot + 0.1), 1e-15);
  const Kernel block = Kernel::blockSum(rbf, 1);
  EXPECT_NEAR(block.value(x, y, 2), std::exp(-2.0 * 0.64) + std::exp(-2.0 * 2.56), 1e-15);
}

TEST(Kernel, ExpNonPositiveIsAccurate) {
  double worst = 0;
  for (double x = -700; x <= 0; x += 0.01234) {
    const double ref = std::exp(x);
    worst = std::max(worst, std::abs(expNonPositive(x) - ref) / ref);
  }
  EXPECT_LT(worst, 4e-16);
  EXPECT_EQ(expNonPositive(0.0), 1.0);
  EXPECT_LT(expNonPositive(-1e6), 1e-300);
}

TEST(Kernel, BadParametersAreExplained) {
  EXPECT_THROW(Kernel::rbfFromSigma(0.0), std::invalid_argument);
  EXPECT_THROW(Kernel::rbfFromSigma(-1.0), std::invalid_argument);
  EXPECT_THROW(Kernel::rbfFromSigma(std::nan("")), std::invalid_argument);
  EXPECT_THROW(Kernel::rbf(0.0), std::invalid_argument);
  try {
    Kernel::rbfFromSigma(-2.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos);
  }
  EXPECT_NE(Kernel::blockSum(Kernel::rbfFromSigma(1), 4).validate(6).find("multiple"),
            std::string::npos);
  Kernel bad = Kernel::rbfFromSigma(1);
  bad.gamma = -1;
  EXPECT_NE(bad.validate(2).find("gamma"), std::string::npos);
}

TEST(KernelCache, KeepsColumnsAcrossSwapsAndEvicts) {
  // 4 samples, capacity of 2 columns: values encode (column, row) and must follow swaps.
  KernelCache cache(4, 0.0);
  std::vector<int> at = {0, 1, 2, 3};  // original sample at each position
  auto fill = [&](int i, int len) {
    int filled = 0;
    float* c = cache.request(i, len, &filled);
    for (int t = filled; t < len; ++t) c[t] = static_cast<float>(10 * at[i] + at[t]);
    return c;
  };
  fill(0, 4);
  fill(1, 2);
  cache.swapIndex(1, 3);
  std::swap(at[1], at[3]);
  const float* c0 = fill(0, 4);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(c0[t], 10 * at[0] + at[t]);
  const float* c3 = fill(3, 4);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(c3[t], 10 * at[3] + at[t]);
  fill(2, 4);  // evicts the oldest
  EXPECT_GT(cache.misses(), 3);
}

// A size beyond any memory is as large as a cache gets, not the least: 1e308 MB had overflowed the
// conversion to a count of floats and left room for two columns.
TEST(KernelCache, AHugeSizeIsTheLargestCache) {
  EXPECT_EQ(KernelCache(4, 0.0).capacityFloats(), 8);
  EXPECT_EQ(KernelCache(4, 1.0).capacityFloats(), (1 << 20) / 4);
  for (const double mb : {1e13, 1e300, 1e308}) EXPECT_EQ(KernelCache(4, mb).capacityFloats(), 1LL << 60) << mb;
}

}  // namespace
}  // namespace svmp::svm
