// The vectorised SMO loops (whichever of AVX-512, AVX2 or SSE2 this machine runs) against one-at-a-time
// references, at every length from 0 to 70 (the 8- and 16-entry steps and their tails), with ties.
// Values are compared bit for bit where the loops promise the same bits on every instruction set (ctest
// runs these tests on all three): the references fuse a multiply and an add where the loops do (fma)
// and round every other operation alone (-ffp-contract=off for both, tests/svm/CMakeLists.txt). The
// exception is selectJ's choice between near-equal objectives (below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "svm/box_loops.hpp"
#include "svm/fast_exp.hpp"
#include "svm/fastron_loops.hpp"
#include "svm/simd_loops.hpp"

namespace svmp::svm::loops {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The exponential's Horner step as the loops take it: one rounding.
struct Fused {
  double operator()(double p, double r, double c) const { return std::fma(p, r, c); }
};
double fusedExp(double x) { return expNonPositiveOf<12, double, long long>(x, Fused{}); }

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

// Exact ties only: objectives within a rounding of each other may be chosen differently by width
// (within a lane the loops compare cross-products num * quad', across lanes the quotients), the one
// place where the instruction sets may part (docs/architecture.md, "Determinism").
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
        for (int t = 0; t < m; ++t) ASSERT_EQ(e.yG[t], expected[t]) << "entry " << t << " of " << m;
        ASSERT_EQ(r.index, index) << "m " << m << " tied " << tied;
        if (index >= 0) {
          EXPECT_EQ(r.value, value);
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

// Every entry of a kernel column is the scalar exponential of the same distance, whatever lane or tail
// computes it: degree 12 in double, degree 8 rounded to float, the squares summed and the polynomial
// stepped by fused multiply-adds.
TEST(SimdLoops, RbfColumnEntriesAreTheScalarExponentialBitForBit) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int d : {1, 3, 7})
    for (int len = 0; len <= 40; ++len) {
      std::vector<double> coords(static_cast<size_t>(d) * len), z(d), column(len);
      std::vector<float> column_f(len);
      for (double& c : coords) c = u(rng);
      for (double& c : z) c = u(rng);
      const double neg_gamma = -3.7;
      rbfColumn(coords.data(), len, d, z.data(), neg_gamma, len, column.data());
      rbfColumn(coords.data(), len, d, z.data(), neg_gamma, len, column_f.data());
      for (int t = 0; t < len; ++t) {
        double dist = 0.0;
        for (int k = 0; k < d; ++k) {
          const double diff = coords[static_cast<size_t>(k) * len + t] - z[k];
          dist = std::fma(diff, diff, dist);
        }
        ASSERT_EQ(column[t], fusedExp(neg_gamma * dist)) << "d " << d << " entry " << t;
        ASSERT_EQ(column_f[t], static_cast<float>(expNonPositiveOf<8, double, long long>(neg_gamma * dist, Fused{})));
      }
    }
}

// The truncated sum and its gradient: the terms within the radius summed into eight lanes (support
// vector s into lane s mod 8; the gradient's terms fused), the lanes added in order, bit for bit, on
// the fixed dimensions (2, 3, 6, 7) and the run-time ones.
TEST(SimdLoops, TruncatedRbfSumAddsTheTermsInEightLanesBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int d : {2, 3, 5, 6, 7, 9}) {
    const int block = 32, blocks = 3, n = block * blocks;
    std::vector<double> xs(static_cast<size_t>(d) * n), coef(n), lo(d * blocks), hi(d * blocks);
    std::vector<double> centre(d * blocks), radius(blocks);
    for (int s = 0; s < n; ++s) {
      coef[s] = s % block >= block - 3 ? 0.0 : u(rng);  // the last three of each block: padding
      for (int k = 0; k < d; ++k) xs[static_cast<size_t>(k) * n + s] = 0.6 * u(rng) + (s / block) * 0.5;
    }
    for (int b = 0; b < blocks; ++b) {
      double r2 = 0.0;
      for (int k = 0; k < d; ++k) {
        const auto first = xs.begin() + static_cast<long>(k) * n + b * block;
        const auto [mn, mx] = std::minmax_element(first, first + block);
        lo[k * blocks + b] = *mn, hi[k * blocks + b] = *mx, centre[k * blocks + b] = 0.5 * (*mn + *mx);
        r2 += 0.25 * (*mx - *mn) * (*mx - *mn);
      }
      radius[b] = std::sqrt(r2) * (1 + 1e-9);
    }
    const BlockedSupportVectors sv{d, blocks, block, n, xs.data(), coef.data(), lo.data(), hi.data(),
                                   centre.data(), radius.data()};
    const double gamma = 2.5, r2 = 0.6;
    for (int rep = 0; rep < 20; ++rep) {
      std::vector<double> q(d), grad(d);
      for (double& c : q) c = 0.8 * u(rng) + 0.4;
      const double f = truncatedRbfSum(sv, q.data(), gamma, r2, grad.data());
      double lanes[8] = {}, grad_lanes[8][9] = {};
      int inside = 0;
      for (int s = 0; s < n; ++s) {
        double dist = 0.0;
        for (int k = 0; k < d; ++k) {
          const double c = q[k] - xs[static_cast<size_t>(k) * n + s];
          dist = std::fma(c, c, dist);
        }
        if (!(dist < r2)) continue;
        ++inside;
        const double term = coef[s] * fusedExp(-gamma * dist);
        lanes[s % 8] += term;
        for (int k = 0; k < d; ++k)
          grad_lanes[s % 8][k] = std::fma(term, xs[static_cast<size_t>(k) * n + s], grad_lanes[s % 8][k]);
      }
      double sum = 0.0;
      for (double lane : lanes) sum += lane;
      ASSERT_EQ(f, sum) << "d " << d << " rep " << rep << ", " << inside << " terms inside";
      for (int k = 0; k < d; ++k) {
        double gk = 0.0;
        for (const auto& lane : grad_lanes) gk += lane[k];
        ASSERT_EQ(grad[k], 2.0 * gamma * (gk - q[k] * sum)) << "d " << d << " coordinate " << k;
      }
      EXPECT_EQ(truncatedRbfSum(sv, q.data(), gamma, r2, nullptr), f);
    }
  }
}

// The Fastron's loops (svm/fastron_loops.cpp), the same way: every operation rounded alone (no fused
// multiply-add on any width), a kernel column's entries and the model's value summed into 16 lanes
// (point j into lane j mod 16), 1 / t^2 exactly divided, the lanes added in order; on one block and
// on blocks of 3 (the FK kernel), up to 60 coordinates (the loops once stopped at 48).
TEST(SimdLoops, FastronColumnAndSumAreTheReferencesBitForBit) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<float> u(-1, 1);
  for (const auto& [dim, block] : {std::pair{3, 3}, {7, 7}, {15, 3}, {60, 3}}) {
    for (int n = 0; n <= 70; n += 7) {
      const long stride = (n + 15) / 16 * 16;
      std::vector<float> xs(static_cast<size_t>(dim) * stride, 0.f), w(stride, 0.f), z(dim), column(n);
      for (int j = 0; j < n; ++j) {
        w[j] = u(rng);
        for (int k = 0; k < dim; ++k) xs[k * stride + j] = u(rng);
      }
      for (float& c : z) c = u(rng);
      const float hg = 1.7f;
      const fastron_loops::PointsSoA points{xs.data(), stride, dim, block, n};
      fastron_loops::kernelColumn(points, z.data(), hg, column.data());
      float lanes[16] = {};
      for (int j = 0; j < stride; ++j) {
        float k = 0.f;
        for (int b = 0; b < dim; b += block) {
          float t = 0.f;
          for (int c = b; c < b + block; ++c) {
            const float d = xs[c * stride + j] - z[c];
            t += d * d;
          }
          t = 1.f + hg * t;
          k += 1.f / (t * t);
        }
        if (j < n) {
          ASSERT_EQ(column[j], k) << "dim " << dim << " point " << j;
        }
        lanes[j % 16] += w[j] * k;
      }
      double sum = 0.0;
      for (float lane : lanes) sum += lane;
      ASSERT_EQ(fastron_loops::weightedSum(points, w.data(), z.data(), hg), sum) << "dim " << dim << " n " << n;
    }
  }
}

}  // namespace
}  // namespace svmp::svm::loops
