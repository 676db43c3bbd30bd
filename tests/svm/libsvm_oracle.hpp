// Thin wrapper over libsvm 3.24's C API (svm_train) for tests and benchmarks: C-SVC, RBF.
#pragma once

#include <svm.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <vector>

namespace svmp::svm::testing {

struct LibsvmResult {
  Eigen::VectorXd alpha;  // in sample order, our labels' convention
  double bias = 0;        // -rho in our sign convention (+1 = label +1)
  double objective = 0;   // 0.5 a'Qa - e'a, recomputed by the caller if needed
  int support_vectors = 0;
};

inline void libsvmSilence() {
  svm_set_print_string_function([](const char*) {});
}

// Dense data as libsvm nodes: d entries + terminator per sample (index 1..d).
class LibsvmProblem {
 public:
  LibsvmProblem(const Eigen::MatrixXd& X, const Eigen::VectorXd& y)
      : d_(static_cast<int>(X.rows())),
        n_(static_cast<int>(X.cols())),
        nodes_(static_cast<size_t>(n_) * (d_ + 1)),
        rows_(n_),
        labels_(y.data(), y.data() + n_) {
    for (int i = 0; i < n_; ++i) {
      svm_node* row = &nodes_[static_cast<size_t>(i) * (d_ + 1)];
      for (int k = 0; k < d_; ++k) row[k] = svm_node{k + 1, X(k, i)};
      row[d_] = svm_node{-1, 0.0};
      rows_[i] = row;
    }
    prob_.l = n_;
    prob_.y = labels_.data();
    prob_.x = rows_.data();
  }
  const svm_problem* get() const { return &prob_; }
  int size() const { return n_; }

 private:
  int d_, n_;
  std::vector<svm_node> nodes_;
  std::vector<svm_node*> rows_;
  std::vector<double> labels_;
  svm_problem prob_{};
};

struct LibsvmModelDeleter {
  void operator()(svm_model* m) const { svm_free_and_destroy_model(&m); }
};
using LibsvmModelPtr = std::unique_ptr<svm_model, LibsvmModelDeleter>;

inline svm_parameter libsvmParameters(double gamma, double C, double eps, bool shrinking,
                                      const std::map<int, double>& weights) {
  svm_parameter p{};
  p.svm_type = C_SVC;
  p.kernel_type = RBF;
  p.gamma = gamma;
  p.C = C;
  p.eps = eps;
  p.cache_size = 100;
  p.shrinking = shrinking ? 1 : 0;
  p.probability = 0;
  p.nr_weight = static_cast<int>(weights.size());
  static thread_local std::vector<int> labels;
  static thread_local std::vector<double> values;
  labels.clear();
  values.clear();
  for (const auto& [l, w] : weights) {
    labels.push_back(l);
    values.push_back(w);
  }
  p.weight_label = labels.empty() ? nullptr : labels.data();
  p.weight = values.empty() ? nullptr : values.data();
  return p;
}

// Trains and extracts alpha / bias in our convention (libsvm makes its first-seen label +1).
inline LibsvmResult libsvmTrain(const LibsvmProblem& prob, const Eigen::VectorXd& y, double gamma,
                                double C, double eps, bool shrinking = true,
                                const std::map<int, double>& weights = {},
                                LibsvmModelPtr* keep = nullptr) {
  libsvmSilence();
  svm_parameter param = libsvmParameters(gamma, C, eps, shrinking, weights);
  LibsvmModelPtr model(svm_train(prob.get(), &param));
  LibsvmResult r;
  const int n = prob.size();
  r.alpha = Eigen::VectorXd::Zero(n);
  const double sign = model->label[0] == 1 ? 1.0 : -1.0;
  std::vector<int> idx(model->l);
  svm_get_sv_indices(model.get(), idx.data());
  for (int s = 0; s < model->l; ++s) {
    const int i = idx[s] - 1;                         // 1-based
    r.alpha[i] = model->sv_coef[0][s] * y[i] * sign;  // sv_coef = y_lib alpha
  }
  r.bias = -sign * model->rho[0];
  r.support_vectors = model->l;
  if (keep) *keep = std::move(model);
  return r;
}

// libsvm decision value in our sign convention. The query's nodes are kept per thread: benchmarks
// time this call against our evaluator, which allocates nothing per query.
inline double libsvmDecision(const svm_model* model, const double* q, int d) {
  thread_local std::vector<svm_node> x;
  x.resize(d + 1);
  for (int k = 0; k < d; ++k) x[k] = svm_node{k + 1, q[k]};
  x[d] = svm_node{-1, 0.0};
  double v = 0;
  svm_predict_values(model, x.data(), &v);
  return model->label[0] == 1 ? v : -v;
}

}  // namespace svmp::svm::testing
