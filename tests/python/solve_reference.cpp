// The C++ SMO solver on a text file of samples, for the Python suite (tests/python/test_svm.py): the
// module's svmp.train must give this program's support set, objective and bias on the same data.
// Input: "n d gamma eps", then n lines "x_1 .. x_d y C". Output: objective, bias, then alpha_i one a line.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "svm/smo_solver.hpp"

int main(int argc, char** argv) {
  const char* usage = "usage: svmp-solve-reference SAMPLES.txt  (\"n d gamma eps\", then n lines \"x_1 .. x_d y C\")\n";
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << usage;
    return 0;
  }
  if (argc != 2) {
    std::cerr << usage;
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in || std::filesystem::is_directory(argv[1])) {
    std::cerr << argv[1] << ": cannot open" << (in ? ": it is a directory" : "") << "\n";
    return 2;
  }
  // Read line by line, so a short or long line is named rather than shifting the rest of the file;
  // the header's sizes are bounded before anything is allocated (a test tool's data: at most 1e6
  // values).
  std::string line;
  long n = 0, d = 0;
  double gamma = 0, eps = 0;
  std::getline(in, line);
  std::string extra;
  if (std::istringstream header(line); !(header >> n >> d >> gamma >> eps) || header >> extra || n <= 0 || d <= 0 ||
                                         n > 1000000 || d > 1000000 / n || !(eps > 0 && eps <= 1)) {
    std::cerr << argv[1] << ": line 1: bad header '" << line
              << "' (expected n d gamma eps, n x d at most 1e6, eps in (0, 1])\n";
    return 2;
  }
  Eigen::MatrixXd X(d, n);
  Eigen::VectorXd y(n), C(n);
  for (long i = 0; i < n; ++i) {
    if (!std::getline(in, line)) {
      std::cerr << argv[1] << ": " << i << " samples, the header says " << n << "\n";
      return 2;
    }
    std::istringstream values(line);
    for (long k = 0; k < d; ++k) values >> X(k, i);
    values >> y[i] >> C[i];
    if (!values || values >> extra || !X.col(i).allFinite() || !std::isfinite(y[i]) || !std::isfinite(C[i])) {
      std::cerr << argv[1] << ": line " << i + 2 << ": expected " << d << " finite coordinates, y and C, got '"
                << line << "'\n";
      return 2;
    }
  }
  if (std::getline(in, line) && line.find_first_not_of(" \t\r") != std::string::npos) {
    std::cerr << argv[1] << ": line " << n + 2 << ": more samples than the header says\n";
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
