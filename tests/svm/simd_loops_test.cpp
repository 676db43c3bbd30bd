// The vectorised SMO loops (whichever of AVX-512, AVX2 or SSE2 this machine runs) against one-at-a-time
// references, at every length from 0 to 70 (the 8- and 16-entry steps and their tails), with ties.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "svm/box_loops.hpp"
#include "svm/simd_loops.hpp"

namespace svmp::svm::loops {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Entries {
  std::vector<double> yG, low, up, diag;
  std::vector<float> Ki, Kj;
};

// Random entries; `tied`: values drawn from a handful, so equal maxima and objectives occur.
Entries randomEntries(int m, bool tied, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> few(0, 3);
  const auto draw = [&] { return tied ? 0.25 * few(rng) : u(rng); };
  Entries e;
  for (int t = 0; t < m; ++t) {
    e.yG.push_back(draw());
    e.low.push_back(few(rng) == 0 ? kInf : 0.0);
    e.up.push_back(few(rng) == 0 ? -kInf : 0.0);
    e.diag.push_back(1.0);
    e.Ki.push_back(static_cast<float>(tied ? 0.25 * few(rng) : 0.5 * (u(rng) + 1)));
    e.Kj.push_back(static_cast<float>(0.5 * (u(rng) + 1)));
  }
  return e;
}

TEST(SimdLoops, SelectJIsTheSmallestObjectiveWithTheSmallestIndexOnTies) {
  std::mt19937_64 rng(3);
  for (bool tied : {false, true})
    for (int m = 0; m <= 70; ++m)
      for (int rep = 0; rep < 5; ++rep) {
        const Entries e = randomEntries(m, tied, rng);
        const double kii = 1.0, gmax = 0.3, tau = 1e-12;
        double gmax2 = -kInf, best = kInf;
        int j = -1;
        for (int t = 0; t < m; ++t) {
          if (e.low[t] == 0.0) gmax2 = std::max(gmax2, e.yG[t]);
          const double diff = gmax + e.yG[t];
          double quad = kii + e.diag[t] - 2.0 * static_cast<double>(e.Ki[t]);
          if (quad <= 0) quad = tau;
          if (e.low[t] == 0.0 && diff > 0 && -(diff * diff) / quad < best) best = -(diff * diff) / quad, j = t;
        }
        const SelectJ r = selectJ(m, e.low.data(), e.yG.data(), e.diag.data(), e.Ki.data(), kii, gmax, tau);
        ASSERT_EQ(r.j, j) << "m " << m << " tied " << tied;
        EXPECT_EQ(r.gmax2, gmax2);
        if (j >= 0) {
          EXPECT_DOUBLE_EQ(r.obj_min, best);
        }
      }
}

TEST(SimdLoops, UpdateGradientSelectIUpdatesEveryEntryAndFindsTheFirstMaximum) {
  std::mt19937_64 rng(4);
  for (bool tied : {false, true})
    for (int m = 0; m <= 70; ++m)
      for (int rep = 0; rep < 5; ++rep) {
        Entries e = randomEntries(m, tied, rng);
        const double wi = tied ? 0.0 : 0.7, wj = tied ? 0.0 : -0.4;  // tied: the update keeps the ties
        std::vector<double> expected = e.yG;
        double value = -kInf;
        int index = -1;
        for (int t = 0; t < m; ++t) {
          expected[t] += wi * static_cast<double>(e.Ki[t]) + wj * static_cast<double>(e.Kj[t]);
          if (e.up[t] - expected[t] > value) value = e.up[t] - expected[t], index = t;
        }
        const ArgMax r = updateGradientSelectI(m, e.yG.data(), e.Ki.data(), e.Kj.data(), wi, wj, e.up.data());
        for (int t = 0; t < m; ++t) ASSERT_NEAR(e.yG[t], expected[t], 1e-15) << "entry " << t << " of " << m;
        ASSERT_EQ(r.index, index) << "m " << m << " tied " << tied;
        if (index >= 0) {
          EXPECT_NEAR(r.value, value, 1e-15);
        }
      }
}

// The fixed-bias solver's loop (one entry per coordinate) against the SMO loop over the doubled
// entries it replaced (G and -G, K and -K): the same gradient and the same index, ties included.
TEST(SimdLoops, UpdateGradientSelectBoxAgreesWithTheDoubledEntries) {
  std::mt19937_64 rng(5);
  for (bool tied : {false, true})
    for (int m = 0; m <= 70; ++m)
      for (int rep = 0; rep < 5; ++rep) {
        Entries e = randomEntries(m, tied, rng), f = randomEntries(m, tied, rng);
        const double w = tied ? 0.0 : -0.9;
        std::vector<double> yG(2 * m), up(2 * m);
        std::vector<float> K(2 * m);
        for (int t = 0; t < m; ++t) {
          yG[t] = e.yG[t], yG[m + t] = -e.yG[t];
          up[t] = e.up[t], up[m + t] = f.up[t];
          K[t] = e.Ki[t], K[m + t] = -e.Ki[t];
        }
        const ArgMax doubled = updateGradientSelectI(2 * m, yG.data(), K.data(), K.data(), w, 0.0, up.data());
        const ArgMax box = updateGradientSelectBox(m, e.yG.data(), e.Ki.data(), w, e.up.data(), f.up.data());
        for (int t = 0; t < m; ++t) ASSERT_EQ(e.yG[t], yG[t]) << "entry " << t << " of " << m;
        ASSERT_EQ(box.index, doubled.index) << "m " << m << " tied " << tied;
        if (box.index >= 0) {
          EXPECT_EQ(box.value, doubled.value);
        }
        const ArgMax unchanged = updateGradientSelectBox(m, e.yG.data(), nullptr, w, e.up.data(), f.up.data());
        EXPECT_EQ(unchanged.index, box.index);
      }
}

}  // namespace
}  // namespace svmp::svm::loops
