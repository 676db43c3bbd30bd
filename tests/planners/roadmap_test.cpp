// Graph search, union-find and nearest neighbours against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "planners/nearest_neighbors.hpp"
#include "planners/roadmap.hpp"

namespace svmp::planners {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct RandomGraph {
  Roadmap roadmap;
  std::vector<Eigen::VectorXd> positions;
  std::vector<std::vector<double>> best;  // cheapest direct edge, inf when none
};

// `metric`: edge costs are at least the Euclidean distance of the nodes' positions (so the distance to
// the target is an admissible heuristic); otherwise costs are arbitrary positive numbers.
RandomGraph randomGraph(std::mt19937_64& rng, int n, double density, bool metric) {
  std::uniform_real_distribution<double> unit(0, 1);
  RandomGraph g;
  g.best.assign(n, std::vector<double>(n, kInf));
  for (int i = 0; i < n; ++i) {
    g.positions.push_back(Eigen::Vector2d(unit(rng), unit(rng)));
    g.roadmap.addNode(g.positions.back());
  }
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      // Occasionally a parallel edge, to check that the cheaper one is used.
      const int copies = unit(rng) < density ? (unit(rng) < 0.1 ? 2 : 1) : 0;
      for (int c = 0; c < copies; ++c) {
        const double cost = metric ? (g.positions[a] - g.positions[b]).norm() * (1 + 2 * unit(rng))
                                   : 0.01 + unit(rng);
        g.roadmap.addEdge(a, b, cost);
        g.best[a][b] = g.best[b][a] = std::min(g.best[a][b], cost);
      }
    }
  return g;
}

std::vector<std::vector<double>> floydWarshall(const std::vector<std::vector<double>>& w) {
  const int n = static_cast<int>(w.size());
  auto d = w;
  for (int i = 0; i < n; ++i) d[i][i] = 0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
  return d;
}

void checkAllPairs(const RandomGraph& g, bool use_heuristic) {
  const int n = g.roadmap.numNodes();
  const auto dist = floydWarshall(g.best);
  for (int from = 0; from < n; ++from)
    for (int to = 0; to < n; ++to) {
      const auto path = g.roadmap.shortestPath(from, to, [&](int v) {
        return use_heuristic ? (g.positions[v] - g.positions[to]).norm() : 0.0;
      });
      SCOPED_TRACE(testing::Message() << "from " << from << " to " << to);
      if (dist[from][to] == kInf) {
        EXPECT_TRUE(path.empty());
        continue;
      }
      ASSERT_FALSE(path.empty());
      EXPECT_EQ(path.front(), from);
      EXPECT_EQ(path.back(), to);
      double cost = 0;
      for (size_t i = 0; i + 1 < path.size(); ++i) {
        ASSERT_LT(g.best[path[i]][path[i + 1]], kInf) << "no edge " << path[i] << "-" << path[i + 1];
        cost += g.best[path[i]][path[i + 1]];
      }
      EXPECT_NEAR(cost, dist[from][to], 1e-9);
    }
}

TEST(Roadmap, AStarWithAdmissibleHeuristicMatchesFloydWarshall) {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 12;
    checkAllPairs(randomGraph(rng, n, trial % 3 == 0 ? 0.15 : 0.4, true), true);
  }
}

TEST(Roadmap, AStarWithZeroHeuristicMatchesFloydWarshall) {
  std::mt19937_64 rng(2);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 12;
    checkAllPairs(randomGraph(rng, n, trial % 3 == 0 ? 0.15 : 0.4, false), false);
  }
}

TEST(Roadmap, CountsEdgesAndClears) {
  Roadmap r;
  r.addNode(Eigen::Vector2d(0, 0));
  r.addNode(Eigen::Vector2d(1, 0));
  r.addNode(Eigen::Vector2d(2, 0));
  r.addEdge(0, 1, 1.0);
  EXPECT_EQ(r.numEdges(), 1);
  EXPECT_TRUE(r.connected(0, 1));
  EXPECT_FALSE(r.connected(0, 2));
  r.addEdge(1, 2, 1.0);
  r.removeEdge(2, 1);
  EXPECT_TRUE(r.isBlocked(1, 2)) << "a removed pair is remembered, either way round";
  EXPECT_FALSE(r.isBlocked(0, 1));
  r.clear();
  EXPECT_EQ(r.numNodes(), 0);
  EXPECT_EQ(r.numEdges(), 0);
  r.addNode(Eigen::Vector2d(0, 0));
  r.addNode(Eigen::Vector2d(1, 0));
  EXPECT_FALSE(r.connected(0, 1)) << "components survived clear()";
  r.addNode(Eigen::Vector2d(2, 0));
  EXPECT_FALSE(r.isBlocked(1, 2)) << "blocked pairs survived clear()";
}

// Lazy edges: unchecked until marked; dropping them keeps checked and certified edges and the
// components they make.
TEST(Roadmap, DropsOnlyUncheckedEdges) {
  Roadmap r;
  for (int i = 0; i < 4; ++i) r.addNode(Eigen::Vector2d(i, 0));
  r.addEdge(0, 1, 1.0);
  r.addEdge(1, 2, 1.0, false);
  r.addEdge(2, 3, 1.0, false);
  r.markCertified(2, 3);
  EXPECT_TRUE(r.isChecked(0, 1));
  EXPECT_FALSE(r.isChecked(1, 2));
  EXPECT_TRUE(r.isChecked(3, 2)) << "certified implies checked, both directions";
  EXPECT_TRUE(r.connected(0, 3)) << "components count unchecked edges";
  const auto dropped = r.dropUnchecked();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].first, 1);
  EXPECT_EQ(dropped[0].second.to, 2);
  EXPECT_EQ(r.numEdges(), 2);
  EXPECT_FALSE(r.hasEdge(2, 1));
  EXPECT_TRUE(r.connected(0, 1));
  EXPECT_TRUE(r.connected(2, 3));
  EXPECT_FALSE(r.connected(1, 2));
  EXPECT_TRUE(r.dropUnchecked().empty());
}

// Dropped edges come back, unchecked, only between nodes one component already holds, and never twice.
TEST(Roadmap, RestoresUncheckedEdgesOnlyWithinComponents) {
  Roadmap r;
  for (int i = 0; i < 4; ++i) r.addNode(Eigen::Vector2d(i, 0));
  r.addEdge(0, 1, 1.0);
  r.addEdge(1, 2, 1.0);
  Edge e;
  e.checked = false;
  std::vector<std::pair<int, Edge>> dropped;
  for (auto [a, b] : {std::pair{0, 2}, {0, 3}, {1, 2}}) {
    e.to = b;
    e.cost = std::abs(a - b);
    dropped.emplace_back(a, e);
  }
  r.restoreWithinComponents(dropped);
  EXPECT_TRUE(r.hasEdge(2, 0));
  EXPECT_FALSE(r.isChecked(0, 2));
  EXPECT_FALSE(r.hasEdge(0, 3)) << "0 and 3 lie in different components";
  EXPECT_FALSE(r.connected(0, 3));
  EXPECT_EQ(r.numEdges(), 3) << "1-2 is there already";
  EXPECT_TRUE(r.isChecked(1, 2));
}

std::vector<int> bfsComponents(int n, const std::vector<std::pair<int, int>>& edges) {
  std::vector<std::vector<int>> adj(n);
  for (auto [a, b] : edges) adj[a].push_back(b), adj[b].push_back(a);
  std::vector<int> comp(n, -1);
  for (int s = 0; s < n; ++s) {
    if (comp[s] >= 0) continue;
    std::queue<int> q;
    q.push(s);
    comp[s] = s;
    while (!q.empty()) {
      const int u = q.front();
      q.pop();
      for (int v : adj[u])
        if (comp[v] < 0) comp[v] = s, q.push(v);
    }
  }
  return comp;
}

TEST(UnionFind, ComponentsMatchBreadthFirstSearch) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 40;
    std::uniform_int_distribution<int> node(0, n - 1);
    const int m = std::uniform_int_distribution<int>(0, 2 * n)(rng);
    UnionFind uf(n);
    Roadmap roadmap;
    for (int i = 0; i < n; ++i) roadmap.addNode(Eigen::Vector2d::Zero());
    std::vector<std::pair<int, int>> edges;
    for (int e = 0; e < m; ++e) {
      const int a = node(rng), b = node(rng);
      // unite() reports whether the edge merged two components.
      const auto before = bfsComponents(n, edges);
      EXPECT_EQ(uf.unite(a, b), before[a] != before[b]);
      edges.emplace_back(a, b);
      roadmap.addEdge(a, b, 1.0);
    }
    const auto comp = bfsComponents(n, edges);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        ASSERT_EQ(uf.same(a, b), comp[a] == comp[b]) << "trial " << trial << " nodes " << a << ", " << b;
        ASSERT_EQ(roadmap.connected(a, b), comp[a] == comp[b]);
      }
  }
}

TEST(UnionFind, GrowsWithNewSingletons) {
  UnionFind uf(3);
  uf.unite(0, 2);
  uf.resize(5);
  EXPECT_TRUE(uf.same(0, 2));
  EXPECT_FALSE(uf.same(3, 4));
  EXPECT_FALSE(uf.same(0, 3));
  EXPECT_EQ(uf.size(), 5);
}

TEST(NearestNeighbors, MatchesBruteForceInWeightedMetric) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int dim : {2, 3, 6}) {
    Eigen::VectorXd weights(dim);
    for (int d = 0; d < dim; ++d) weights[d] = 0.05 + 10.0 * std::abs(unit(rng));
    const Eigen::VectorXd scale = weights.cwiseSqrt();
    for (int n : {1, 7, 300}) {
      std::vector<Eigen::VectorXd> points(n, Eigen::VectorXd(dim));
      for (auto& p : points)
        for (int d = 0; d < dim; ++d) p[d] = unit(rng);
      const NearestNeighbors nn(points, scale);
      ASSERT_EQ(nn.size(), n);
      for (int query = 0; query < 30; ++query) {
        Eigen::VectorXd q(dim);
        for (int d = 0; d < dim; ++d) q[d] = 1.2 * unit(rng);
        auto dist = [&](int i) { return std::sqrt(((points[i] - q).array().square() * weights.array()).sum()); };
        std::vector<int> order(n);
        for (int i = 0; i < n; ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](int a, int b) { return dist(a) < dist(b); });
        // Within a radius: the nearest when it lies no farther, else none (radii about the nearest
        // distance, so both sides are asked).
        for (double factor : {0.5, 0.999, 1.001, 2.0}) {
          const double radius = factor * dist(order[0]);
          const int within = nn.nearestWithin(q, radius);
          if (dist(order[0]) < radius) {
            ASSERT_GE(within, 0) << "dim " << dim << " n " << n << " factor " << factor;
            EXPECT_NEAR(dist(within), dist(order[0]), 1e-12);
          } else {
            EXPECT_EQ(within, -1) << "dim " << dim << " n " << n << " factor " << factor;
          }
        }
        EXPECT_EQ(nn.nearestWithin(q, 0.0), -1);
        EXPECT_GE(nn.nearestWithin(q, std::numeric_limits<double>::infinity()), 0);
        for (int k : {1, 5, n, n + 3}) {
          const auto got = nn.nearest(q, k);
          const int expected = std::min(k, n);
          ASSERT_EQ(static_cast<int>(got.size()), expected) << "dim " << dim << " n " << n << " k " << k;
          for (int i = 0; i < expected; ++i)
            EXPECT_NEAR(dist(got[i]), dist(order[i]), 1e-12) << "rank " << i << " dim " << dim << " k " << k;
        }
      }
    }
  }
}

// Points added at the end (NearestNeighbors::extend), in steps that leave some unindexed and some
// that force a rebuild: every answer is the brute force's, as from a tree built over all of them.
TEST(NearestNeighbors, ExtendedSetAnswersAsBruteForce) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Eigen::Vector3d weights(0.3, 2.0, 1.0);
  std::vector<Eigen::VectorXd> points;
  auto add = [&](int n) {
    for (int i = 0; i < n; ++i) points.push_back(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
  };
  add(5);
  NearestNeighbors nn({}, weights.cwiseSqrt());
  nn.extend(points);  // from empty
  for (int step : {3, 40, 1, 7, 200, 2}) {
    add(step);
    nn.extend(points);
    ASSERT_EQ(nn.size(), static_cast<int>(points.size()));
    for (int query = 0; query < 20; ++query) {
      const Eigen::Vector3d q(1.2 * unit(rng), 1.2 * unit(rng), 1.2 * unit(rng));
      auto dist = [&](int i) { return std::sqrt(((points[i] - q).array().square() * weights.array()).sum()); };
      std::vector<int> order(points.size());
      for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
      std::sort(order.begin(), order.end(), [&](int a, int b) { return dist(a) < dist(b); });
      const auto got = nn.nearest(q, 6);
      ASSERT_EQ(got.size(), std::min<size_t>(6, points.size()));
      for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(dist(got[i]), dist(order[i]), 1e-12) << "rank " << i;
      const int within = nn.nearestWithin(q, 1.001 * dist(order[0]));
      ASSERT_GE(within, 0);
      EXPECT_NEAR(dist(within), dist(order[0]), 1e-12);
      EXPECT_EQ(nn.nearestWithin(q, 0.999 * dist(order[0])), -1);
    }
  }
}

TEST(NearestNeighbors, EmptySetAndMovedTreeStillAnswer) {
  const NearestNeighbors empty({}, Eigen::Vector2d::Ones());
  EXPECT_TRUE(empty.nearest(Eigen::Vector2d::Zero(), 3).empty());
  EXPECT_EQ(empty.nearestWithin(Eigen::Vector2d::Zero(), 1.0), -1);
  std::vector<Eigen::VectorXd> pts = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 3)};
  NearestNeighbors a(pts, Eigen::Vector2d(1, 0.01));  // y barely counts: (0,3) is at distance 0.3
  NearestNeighbors b = std::move(a);
  const auto got = b.nearest(Eigen::Vector2d(0, 0.1), 3);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], 0);
  EXPECT_EQ(got[1], 2);
  EXPECT_EQ(got[2], 1);
  EXPECT_EQ(b.nearestWithin(Eigen::Vector2d(1, 0), 0.0), 1);  // at the radius counts
  EXPECT_EQ(b.nearestWithin(Eigen::Vector2d(0.5, 0), 0.49), -1);
  EXPECT_EQ(b.nearestWithin(Eigen::Vector2d(0.5, 0), -1.0), -1);
}

// The grid must give exactly what the scan over every kept point gives, in order: in 1, 2, 3 and 7
// dimensions with unequal weights (so the widest coordinates are not the first), points drawn in
// clusters (many in a cell) and radius 0 (everything kept).
TEST(NearDuplicateFilter, KeepsWhatTheScanOverEveryKeptPointKeeps) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int dim : {1, 2, 3, 7})
    for (double radius : {0.0, 0.01, 0.08, 0.5}) {
      const Eigen::VectorXd lower = -Eigen::VectorXd::Ones(dim), upper = 2 * Eigen::VectorXd::Ones(dim);
      Eigen::VectorXd weights(dim);
      for (int d = 0; d < dim; ++d) weights[d] = 0.2 + 3 * unit(rng);
      const cspace::ConfigurationSpace space(lower, upper, weights);
      std::vector<Eigen::VectorXd> points;
      for (int c = 0; c < 20; ++c) {
        Eigen::VectorXd centre(dim);
        space.sampleUniform(rng, centre);
        for (int i = 0; i < 40; ++i)
          points.push_back(centre + 0.1 * Eigen::VectorXd::NullaryExpr(dim, [&] { return unit(rng) - 0.5; }));
      }
      const int seeded = 30;  // the first ones are added unconditionally, as a roadmap's nodes are
      NearDuplicateFilter filter(space, radius, static_cast<int>(points.size()));
      std::vector<Eigen::VectorXd> kept;
      int dropped = 0;
      for (size_t i = 0; i < points.size(); ++i) {
        bool near = false;
        for (const auto& k : kept) near = near || space.distance(k, points[i]) < radius;
        if (static_cast<int>(i) < seeded) {
          filter.add(points[i]);
          kept.push_back(points[i]);
          continue;
        }
        ASSERT_EQ(filter.addUnlessNear(points[i]), !near) << "dim " << dim << " radius " << radius << " point " << i;
        if (near) {
          ++dropped;
        } else {
          kept.push_back(points[i]);
        }
      }
      if (radius == 0) {
        EXPECT_EQ(dropped, 0);
      } else if (radius >= 0.08) {
        EXPECT_GT(dropped, 100) << "dim " << dim << ": the test must drop points to mean anything";
      }
    }
}

}  // namespace
}  // namespace svmp::planners
