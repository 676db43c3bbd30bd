// The C++ SMO solver on a text file of samples, for the Python suite (tests/python/test_svm.py): the
// module's svmp.train must give this program's support set, objective and bias on the same data.
// Input: "n d gamma eps", then n lines "x_1 .. x_d y C". Output: objective, bias, then alpha_i one a line.
#include <cstdio>
#include <fstream>
#include <iostream>

#include "svm/smo_solver.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: svmp-solve-reference SAMPLES.txt\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  long n = 0, d = 0;
  double gamma = 0, eps = 0;
  if (!(in >> n >> d >> gamma >> eps) || n <= 0 || d <= 0) {
    std::cerr << argv[1] << ": bad header (expected n d gamma eps)\n";
    return 2;
  }
  Eigen::MatrixXd X(d, n);
  Eigen::VectorXd y(n), C(n);
  for (long i = 0; i < n; ++i) {
    for (long k = 0; k < d; ++k) in >> X(k, i);
    in >> y[i] >> C[i];
  }
  if (!in) {
    std::cerr << argv[1] << ": fewer samples than the header says\n";
    return 2;
  }
  svmp::svm::SolverOptions options;
  options.eps = eps;
  try {
    const auto result = svmp::svm::solveBinary(X, y, C, svmp::svm::Kernel::rbf(gamma), options);
    std::printf("%.17g\n%.17g\n", result.objective, result.bias);
    for (long i = 0; i < n; ++i) std::printf("%.17g\n", result.alpha[i]);
  } catch (const std::invalid_argument& e) {
    std::cerr << argv[1] << ": " << e.what() << "\n";
    return 2;
  }
  return 0;
}
