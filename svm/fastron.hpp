// Fastron (Das & Yip 2019, sec. III-B and Algorithm 1; the model of their earlier Fastron paper): a
// kernel perceptron f(x) = sum_i alpha_i k(x_i, x), x predicted in collision when f(x) > 0, trained by
// greedy coordinate descent. Each step takes the training point with the most negative margin
// y_i f(x_i) <= 0 and sets f there to its target, beta for a point in collision ("conditional bias",
// beta > 1 makes the model conservative) and -1 for a free one; when every margin is positive, a
// support point that stays correct without its own weight is removed, and training ends when none is
// left. Kernel columns are computed lazily (only for points that get a weight) into the SMO solver's
// LRU kernel cache. A training call starts from given weights, so an update after the workspace
// changed starts from the previous model. Limits on steps and on the size of the support set bound
// update times and model size.
//
// Kernel (svm/fastron_loops.hpp): the rational quadratic (1 + (gamma/2)|x - y|^2)^-2 on whole
// feature vectors (block = dim: Fastron RBF on joints scaled to [-1, 1]) or summed over blocks of 3
// (block = 3: the FK kernel on control-point positions, eq. 4). The features are the caller's
// (cspace/fastron_checker.hpp maps configurations to them).
//
// Reading of Algorithm 1 where the text lost it: with k(x, x) = b blocks (the FK kernel sums b base
// kernels), the step that sets f(x_i) to its target moves alpha_i by (target - f(x_i)) / k(x_i, x_i),
// which is the paper's rule when k(x, x) = 1.
// Thread safety: a trained model's const methods may run concurrently; train() is not.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace svmp::svm {

struct FastronOptions {
  double gamma = 10;        // kernel width
  double beta = 1;          // conditional bias: target of f at points in collision
  int max_updates = 10000;  // coordinate-descent steps per training call
  int max_support = 5000;   // support points at most
  double cache_mb = 64;     // lazy kernel columns

  // "" when usable, else what is wrong (names the field and value).
  std::string validate() const;
  bool operator==(const FastronOptions&) const = default;
};

struct FastronTrainStats {
  int steps = 0;           // weight changes (added + adjusted) and removals
  int added = 0, adjusted = 0, removed = 0;
  int support = 0;         // support points after training
  long long kernel_columns = 0;  // columns computed (cache misses)
  bool converged = false;  // every training point has a positive margin
  bool stopped = false;    // the caller's stop fired before the updates ended
  double min_margin = 0;   // y_i f(x_i) over the training set
};

class FastronModel {
 public:
  // dim: feature length; block: coordinates per kernel block (dim for one block). Throws
  // std::invalid_argument on a bad dimension or options.
  FastronModel(int dim, int block, FastronOptions options);

  // Trains on n = y.size() points (features row-major, n x dim) with labels +1 (in collision) or -1
  // (free), starting from `alpha` (size n: zeros for a cold start, the previous model's weights for
  // its support points in a warm one). On return alpha holds the weights (the support set is its
  // nonzero entries), and the model answers queries with that support set. Throws
  // std::invalid_argument on mismatched sizes, a label other than +-1 or a non-finite value.
  // `stop`, when set, is polled before every update.
  FastronTrainStats train(const std::vector<float>& features, const std::vector<std::int8_t>& labels,
                          std::vector<double>& alpha, const std::function<bool()>& stop = {});

  // f(x) for one feature vector of dim floats.
  double value(const float* x) const;
  bool inCollision(const float* x) const { return value(x) > 0; }

  int dim() const { return dim_; }
  int block() const { return block_; }
  int size() const { return support_; }
  const FastronOptions& options() const { return options_; }
  // Indices (into the last training set) of the support points, in storage order.
  const std::vector<int>& supportIndices() const { return support_index_; }

 private:
  void storeSupport(const std::vector<float>& features, const std::vector<double>& alpha);

  int dim_, block_;
  FastronOptions options_;
  // Support set, structure of arrays: coordinate k of point j at coords_[k * stride_ + j].
  std::vector<float> coords_, weights_;
  long stride_ = 0;
  int support_ = 0;
  std::vector<int> support_index_;
};

}  // namespace svmp::svm
