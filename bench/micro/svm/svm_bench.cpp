// svmp-bench-svm: SMO training (cold, warm, one-versus-rest) and decision evaluation, svmp against
// libsvm 3.24 on the synthetic ball problems of tests/svm/ball_problems.hpp (sigma = r/2, C = 10).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>
#include <tuple>

#include "svm/local_one_vs_rest.hpp"
#include "svm/model.hpp"
#include "svm/one_vs_rest.hpp"
#include "svm/smo_solver.hpp"
#include "svm/truncated_evaluator.hpp"
#include "tests/svm/ball_problems.hpp"
#include "tests/svm/libsvm_oracle.hpp"

namespace {

using namespace svmp::svm;
using svmp::svm::testing::BallProblem;

constexpr double kC = 10.0;
constexpr int kClasses = 3;

const BallProblem& problem(int d, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<BallProblem>> cache;
  auto& p = cache[{d, n}];
  if (!p) p = std::make_unique<BallProblem>(testing::makeBallProblem(d, n, kClasses, 1000 + d));
  return *p;
}
Kernel kernelFor(const BallProblem& p) { return Kernel::rbfFromSigma(p.ball_radius / 2); }

// Exact 0.5 a'Qa - e'a over the support vectors (same formula for both solvers).
double exactObjective(const BallProblem& p, const Eigen::VectorXd& y, const Eigen::VectorXd& a) {
  const Kernel k = kernelFor(p);
  std::vector<Eigen::Index> sv;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (a[i] > 0) sv.push_back(i);
  double quad = 0;
  for (Eigen::Index i : sv)
    for (Eigen::Index j : sv)
      quad += y[i] * y[j] * a[i] * a[j] * k.value(p.X.col(i).data(), p.X.col(j).data(), p.X.rows());
  return 0.5 * quad - a.sum();
}

void BM_TrainCold_svmp(benchmark::State& state) {
  const auto& p = problem(state.range(0), state.range(1));
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  SolverResult r;
  for (auto _ : state) r = solveBinary(p.X, y, C, kernelFor(p), SolverOptions());
  state.counters["objective"] = r.objective;
  state.counters["SV"] = r.support_vectors;
  state.counters["iterations"] = static_cast<double>(r.iterations);
  state.counters["entries"] = static_cast<double>(r.kernel_entries);
  state.counters["active"] = r.mean_active;
}

// Threads inside one solve, parallel at every active-set size (to find where it pays).
void BM_TrainParallel_svmp(benchmark::State& state) {
  const auto& p = problem(state.range(0), state.range(1));
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  SolverOptions opt;
  opt.threads = static_cast<int>(state.range(2));
  opt.parallel_min_samples = 8;
  SolverResult r;
  for (auto _ : state) r = solveBinary(p.X, y, C, kernelFor(p), opt);
  state.counters["objective"] = r.objective;
  state.counters["iterations"] = static_cast<double>(r.iterations);
  state.counters["active"] = r.mean_active;
}

void BM_TrainCold_libsvm(benchmark::State& state) {
  const auto& p = problem(state.range(0), state.range(1));
  const Eigen::VectorXd y = p.binary();
  testing::LibsvmProblem prob(p.X, y);
  testing::LibsvmResult r;
  for (auto _ : state) r = testing::libsvmTrain(prob, y, kernelFor(p).gamma, kC, 1e-3);
  state.counters["objective"] = exactObjective(p, y, r.alpha);
  state.counters["SV"] = r.support_vectors;
}

struct WarmCase {
  Eigen::MatrixXd X;
  Eigen::VectorXd y, C;
  WarmStart warm;
  std::vector<Eigen::Index> previous_index;
};

// 5% moved by a tenth of a ball radius, 5% removed, 5% added.
WarmCase makeWarmCase(int d, int n) {
  const auto& p = problem(d, n);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  const SolverResult first = solveBinary(p.X, y, C, kernelFor(p), SolverOptions());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(0, 1);
  std::normal_distribution<double> normal(0, 1);
  // Same seed, more samples: the same balls, and the first n samples are p's.
  const auto more = testing::makeBallProblem(d, n + n / 20, kClasses, 1000 + d);
  const Eigen::MatrixXd extra_X = more.X.rightCols(n / 20);
  const std::vector<int> extra_labels(more.labels.begin() + n, more.labels.end());
  std::vector<Eigen::Index> prev;
  std::vector<Eigen::VectorXd> cols;
  std::vector<double> labels;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = uni(rng);
    if (u < 0.05) continue;
    Eigen::VectorXd x = p.X.col(i);
    if (u < 0.10) {
      Eigen::VectorXd step(d);
      for (int k = 0; k < d; ++k) step[k] = normal(rng);
      x += 0.1 * p.ball_radius * step.normalized();
    }
    cols.push_back(x);
    labels.push_back(y[i]);
    prev.push_back(i);
  }
  for (Eigen::Index i = 0; i < extra_X.cols(); ++i) {
    cols.push_back(extra_X.col(i));
    labels.push_back(extra_labels[i] == 1 ? 1.0 : -1.0);
    prev.push_back(-1);
  }
  WarmCase w;
  w.X.resize(d, static_cast<Eigen::Index>(cols.size()));
  w.y.resize(w.X.cols());
  for (Eigen::Index i = 0; i < w.X.cols(); ++i) {
    w.X.col(i) = cols[i];
    w.y[i] = labels[i];
  }
  w.C = Eigen::VectorXd::Constant(w.y.size(), kC);
  w.warm = makeWarmStart(p.X, y, C, kernelFor(p), first, prev);
  w.previous_index = prev;
  return w;
}

void BM_TrainWarm_svmp(benchmark::State& state) {
  const WarmCase w = makeWarmCase(state.range(0), state.range(1));
  const Kernel k = kernelFor(problem(state.range(0), state.range(1)));
  SolverResult r;
  for (auto _ : state) r = solveBinary(w.X, w.y, w.C, k, SolverOptions(), &w.warm);
  state.counters["objective"] = r.objective;
  state.counters["iterations"] = static_cast<double>(r.iterations);
  state.counters["columns"] = static_cast<double>(r.warm.columns);
  state.counters["entries"] = static_cast<double>(r.kernel_entries);
  state.counters["active"] = r.mean_active;
}

// The retrain a planner does: the first solve ran in a workspace, which keeps its kernel columns.
void BM_TrainWarm_retained(benchmark::State& state) {
  const int d = state.range(0), n = state.range(1);
  const WarmCase w = makeWarmCase(d, n);
  const auto& p = problem(d, n);
  const Kernel k = kernelFor(p);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  SolverResult r;
  for (auto _ : state) {
    state.PauseTiming();
    SolverWorkspace workspace;
    const SolverResult first = solveBinary(p.X, y, C, k, SolverOptions(), nullptr, &workspace);
    const WarmStart warm = makeWarmStart(p.X, y, C, k, first, w.previous_index);
    state.ResumeTiming();
    r = solveBinary(w.X, w.y, w.C, k, SolverOptions(), &warm, &workspace);
  }
  state.counters["objective"] = r.objective;
  state.counters["iterations"] = static_cast<double>(r.iterations);
  state.counters["columns"] = static_cast<double>(r.warm.columns);
  state.counters["reused"] = static_cast<double>(r.warm.reused_columns);
  state.counters["entries"] = static_cast<double>(r.kernel_entries);
  state.counters["active"] = r.mean_active;
}

void BM_TrainOvr_svmp(benchmark::State& state) {
  const auto& p = problem(6, 20000);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        trainOneVsRest(p.X, p.labels, kernelFor(p), kC, {}, SolverOptions(), state.range(0)));
}

// libsvm's problems (its own input format, one per class) are made before timing: only the solves count.
std::vector<std::pair<Eigen::VectorXd, std::unique_ptr<testing::LibsvmProblem>>> libsvmProblems(const BallProblem& p,
                                                                                                 int classes) {
  std::vector<std::pair<Eigen::VectorXd, std::unique_ptr<testing::LibsvmProblem>>> out;
  for (int c = 1; c <= classes; ++c) {
    Eigen::VectorXd y = p.binary(c);
    auto prob = std::make_unique<testing::LibsvmProblem>(p.X, y);
    out.emplace_back(std::move(y), std::move(prob));
  }
  return out;
}

void BM_TrainOvr_libsvm(benchmark::State& state) {
  const auto& p = problem(6, 20000);
  const auto problems = libsvmProblems(p, kClasses);
  for (auto _ : state)
    for (const auto& [y, prob] : problems)
      benchmark::DoNotOptimize(testing::libsvmTrain(*prob, y, kernelFor(p).gamma, kC, 1e-3));
}

// Eight interleaved classes in 7-D, about 800 support vectors each (as panda_shelf's arm): the
// problems after the first share their kernel columns (svm/shared_columns.hpp) when the matrix fits
// in cache_mb (argument: 100, the default; 5 MB is too small, so each problem keeps its own cache).
const BallProblem& interleaved() {
  static const BallProblem p = testing::makeBallProblem(7, 1200, 8, 33, 4, 0.2);
  return p;
}
constexpr double kInterleavedSigma = 0.1, kInterleavedC = 100;

void BM_TrainOvrInterleaved_svmp(benchmark::State& state) {
  const auto& p = interleaved();
  SolverOptions opt;
  opt.cache_mb = static_cast<double>(state.range(0));
  OneVsRestModel m;
  for (auto _ : state) m = trainOneVsRest(p.X, p.labels, Kernel::rbfFromSigma(kInterleavedSigma), kInterleavedC, {}, opt, 1);
  long long entries = 0;
  for (const auto& s : m.solutions) entries += s.kernel_entries;
  state.counters["shared_columns"] = static_cast<double>(m.shared_columns);
  state.counters["cached_entries"] = static_cast<double>(entries);
}

void BM_TrainOvrInterleaved_libsvm(benchmark::State& state) {
  const auto& p = interleaved();
  const double gamma = Kernel::rbfFromSigma(kInterleavedSigma).gamma;
  const auto problems = libsvmProblems(p, 8);
  for (auto _ : state)
    for (const auto& [y, prob] : problems)
      benchmark::DoNotOptimize(testing::libsvmTrain(*prob, y, gamma, kInterleavedC, 1e-3));
}

// The same problem, each class on its neighbourhood with the bias fixed (svm/local_one_vs_rest.hpp,
// as SVMP trains on the arms): the neighbourhood search included, as svmp.training=auto pays it.
void BM_TrainOvrInterleaved_neighbourhood(benchmark::State& state) {
  const auto& p = interleaved();
  const Kernel k = Kernel::rbfFromSigma(kInterleavedSigma);
  std::vector<int> classes;
  for (int c = 1; c <= 8; ++c) classes.push_back(c);
  OneVsRestModel m;
  std::vector<std::vector<int>> hoods;
  for (auto _ : state) {
    hoods = classNeighbourhoods(p.X, p.labels, classes, k);
    m = trainOneVsRestLocal(p.X, p.labels, k, kInterleavedC, {}, SolverOptions(), 1, &hoods);
  }
  long long sv = 0, iterations = 0;
  for (const auto& s : m.solutions) sv += s.support_vectors, iterations += s.iterations;
  state.counters["share"] = neighbourhoodShare(hoods, p.X.cols());
  state.counters["SV"] = static_cast<double>(sv);
  state.counters["iterations"] = static_cast<double>(iterations);
}

struct EvalCase {
  BinaryModel model;
  Eigen::MatrixXd queries;
};

const EvalCase& evalCase(int d, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<EvalCase>> cache;
  auto& e = cache[{d, n}];
  if (!e) {
    const auto& p = problem(d, n);
    const Eigen::VectorXd y = p.binary();
    const SolverResult r = solveBinary(p.X, y, Eigen::VectorXd::Constant(n, kC), kernelFor(p), {});
    e = std::make_unique<EvalCase>(EvalCase{BinaryModel::fromSolution(p.X, y, r, kernelFor(p)),
                                            testing::nearQueries(p.X, 4096, p.ball_radius / 4, 3)});
  }
  return *e;
}

void BM_Eval_full(benchmark::State& state) {
  const EvalCase& e = evalCase(state.range(0), state.range(1));
  std::vector<double> g(e.model.dim());
  Eigen::Index s = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.model.decisionAndGradient(e.queries.col(s).data(), g.data()));
    s = (s + 1) % e.queries.cols();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["SV"] = e.model.numSupportVectors();
}

void BM_Eval_truncated(benchmark::State& state) {
  const EvalCase& e = evalCase(state.range(0), state.range(1));
  const TruncatedRbfEvaluator ev(e.model);
  std::vector<double> g(e.model.dim());
  Eigen::Index s = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ev.decisionAndGradient(e.queries.col(s).data(), g.data()));
    s = (s + 1) % e.queries.cols();
  }
  state.SetItemsProcessed(state.iterations());
}

// libsvm has no gradient: F only (svm_predict_values over all SVs).
void BM_Eval_libsvm(benchmark::State& state) {
  const int d = state.range(0), n = state.range(1);
  const auto& p = problem(d, n);
  const EvalCase& e = evalCase(d, n);
  const Eigen::VectorXd y = p.binary();
  testing::LibsvmProblem prob(p.X, y);
  testing::LibsvmModelPtr model;
  testing::libsvmTrain(prob, y, kernelFor(p).gamma, kC, 1e-3, true, {}, &model);
  Eigen::Index s = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(testing::libsvmDecision(model.get(), e.queries.col(s).data(), d));
    s = (s + 1) % e.queries.cols();
  }
  state.SetItemsProcessed(state.iterations());
}

void trainArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"d", "n"})->Unit(benchmark::kMillisecond)->UseRealTime();
  for (int d : {2, 6})
    for (int n : {2000, 10000, 20000}) b->Args({d, n});
}

}  // namespace

int main(int argc, char** argv) {
  testing::libsvmSilence();
  for (auto [name, fn] : {std::pair{"BM_TrainCold/svmp", &BM_TrainCold_svmp},
                          std::pair{"BM_TrainCold/libsvm", &BM_TrainCold_libsvm}}) {
    auto* b = benchmark::RegisterBenchmark(name, fn);
    trainArgs(b);
    b->Iterations(3);
  }
  for (auto [name, fn] : {std::pair{"BM_TrainWarm/svmp", &BM_TrainWarm_svmp},
                          std::pair{"BM_TrainWarm/retained", &BM_TrainWarm_retained}}) {
    benchmark::RegisterBenchmark(name, fn)
        ->ArgNames({"d", "n"})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(3)
        ->Args({2, 10000})
        ->Args({2, 20000})
        ->Args({6, 10000})
        ->Args({6, 20000});
  }
  auto* parallel = benchmark::RegisterBenchmark("BM_TrainParallel/svmp", BM_TrainParallel_svmp)
                       ->ArgNames({"d", "n", "threads"})
                       ->Unit(benchmark::kMillisecond)
                       ->UseRealTime()
                       ->Iterations(3);
  for (int d : {2, 6})
    for (int n : {2000, 5000, 10000, 20000})
      for (int t : {1, 2}) parallel->Args({d, n, t});
  benchmark::RegisterBenchmark("BM_TrainOvr/svmp/d:6/n:20000", BM_TrainOvr_svmp)
      ->ArgName("threads")
      ->Arg(1)
      ->Arg(2)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark("BM_TrainOvr/libsvm/d:6/n:20000", BM_TrainOvr_libsvm)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark("BM_TrainOvrInterleaved/svmp/d:7/n:1200", BM_TrainOvrInterleaved_svmp)
      ->ArgName("cache_mb")
      ->Arg(5)
      ->Arg(100)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("BM_TrainOvrInterleaved/libsvm/d:7/n:1200", BM_TrainOvrInterleaved_libsvm)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("BM_TrainOvrInterleaved/neighbourhood/d:7/n:1200",
                               BM_TrainOvrInterleaved_neighbourhood)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  for (auto [name, fn] : {std::pair{"BM_Eval/full", &BM_Eval_full},
                          std::pair{"BM_Eval/truncated", &BM_Eval_truncated},
                          std::pair{"BM_Eval/libsvm", &BM_Eval_libsvm}}) {
    benchmark::RegisterBenchmark(name, fn)
        ->ArgNames({"d", "n"})
        ->Args({2, 10000})
        ->Args({2, 20000})
        ->Args({6, 10000})
        ->Args({6, 20000})
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
