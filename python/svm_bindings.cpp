// svmp.train and svmp.Model: our SMO solver (svm/smo_solver.hpp) on NumPy arrays, and the trained
// decision function F with its gradient, by the full sum (svm/model.hpp) or the exp(-5)-truncated RBF
// evaluator (svm/truncated_evaluator.hpp), on one point or on rows of an array.
#include <pybind11/stl.h>

#include <limits>
#include <optional>

#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "svm/model.hpp"
#include "svm/smo_solver.hpp"
#include "svm/truncated_evaluator.hpp"

namespace svmp::python {
namespace {

struct Model {
  svm::BinaryModel model;
  std::optional<svm::TruncatedRbfEvaluator> truncated;
  svm::SolverResult solution;
  std::vector<long> support_indices;  // rows of the training X kept as support vectors, in their order

  // F (and grad F into `grad` when not null) at one point, exact or truncated (a model without support
  // vectors has no evaluator: F is the bias either way).
  double evaluate(const double* q, double* grad, bool use_truncated) const {
    if (use_truncated && truncated) return grad ? truncated->decisionAndGradient(q, grad) : truncated->decision(q);
    return grad ? model.decisionAndGradient(q, grad) : model.decision(q);
  }
};

// `x` of shape (d,) gives one value (and a (d,) gradient); (n, d) gives n values (and an (n, d) gradient).
py::object evaluate(const Model& m, const py::object& x, bool with_gradient, const py::handle& truncated_in) {
  const bool truncated = truthArgument(truncated_in, "truncated");
  const int d = m.model.dim();
  const DoubleArray a = DoubleArray::ensure(x);
  const int ndim = a ? static_cast<int>(a.ndim()) : 1;
  if (ndim != 1 && ndim != 2) throw py::value_error("x: expected shape (" + std::to_string(d) + ",) or (n, " + std::to_string(d) + ")");
  const DoubleArray points = checkedArray(x, "x", ndim, d);
  const py::ssize_t n = ndim == 1 ? 1 : points.shape(0);
  py::array_t<double> values(n), gradients({n, static_cast<py::ssize_t>(d)});
  const double* q = points.data();
  double *value = values.mutable_data(), *grad = with_gradient ? gradients.mutable_data() : nullptr;
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) value[i] = m.evaluate(q + i * d, grad ? grad + i * d : nullptr, truncated);
  }
  if (ndim == 1) {
    if (!with_gradient) return py::float_(values.at(0));
    return py::array_t<double>(d, gradients.data());
  }
  return with_gradient ? py::object(gradients) : py::object(values);
}

// An optional number argument: None, or a real number (numberArgument).
std::optional<double> optionalNumber(const py::object& value, const std::string& name) {
  if (value.is_none()) return std::nullopt;
  return numberArgument(value, name);
}

Model train(const py::object& X_in, const py::object& y_in, const py::object& C_in, const py::object& gamma_in,
            const py::object& sigma_in, const py::object& eps, const py::object& max_iterations_in,
            const py::object& cache_mb, const py::object& shrinking_in) {
  const bool shrinking = truthArgument(shrinking_in, "shrinking");
  const std::optional<double> gamma = optionalNumber(gamma_in, "gamma"), sigma = optionalNumber(sigma_in, "sigma");
  const long long max_iterations = integerArgument(integerValue(max_iterations_in, "max_iterations"), "max_iterations",
                                                   1, std::numeric_limits<long>::max(), "must be in [1, 2^63 - 1]");
  const Eigen::MatrixXd X = samplesFromArray(X_in, "X");
  const Eigen::VectorXd y = vectorFromArray(y_in, "y", X.cols());
  for (Eigen::Index i = 0; i < y.size(); ++i)
    if (y[i] != 1 && y[i] != -1)
      throw py::value_error("y[" + std::to_string(i) + "] is " + numberText(y[i]) + ": labels must be +1 or -1");
  if (C_in.is_none() || py::isinstance<py::str>(C_in) || py::isinstance<py::bytes>(C_in) ||
      py::isinstance<py::bool_>(C_in))
    throw py::value_error("C is " + py::repr(C_in).cast<std::string>() + ": give a positive number, or one per sample");
  Eigen::VectorXd C;
  const DoubleArray c = DoubleArray::ensure(C_in);
  const bool one_C = c && c.ndim() == 0;
  if (one_C) C = Eigen::VectorXd::Constant(X.cols(), *c.data());
  else C = vectorFromArray(C_in, "C", X.cols());
  for (Eigen::Index i = 0; i < C.size(); ++i)
    if (!(C[i] > 0 && std::isfinite(C[i])))
      throw py::value_error("C" + (one_C ? "" : "[" + std::to_string(i) + "]") + " is " + numberText(C[i]) +
                            ": must be positive and finite");
  if (gamma && sigma) throw py::value_error("gamma and sigma: give one of them (gamma = 1 / (2 sigma^2))");
  if (gamma && !(*gamma > 0 && *gamma <= svm::kMaxRbfGamma))
    throw py::value_error("gamma is " + numberText(*gamma) + ": must be positive and at most 1e300");
  if (sigma && !(*sigma > 0 && std::isfinite(*sigma)))
    throw py::value_error("sigma is " + numberText(*sigma) + ": must be positive and finite");
  if (const double g = sigma ? 1 / (2 * *sigma * *sigma) : 1; !(g > 0 && g <= svm::kMaxRbfGamma))
    throw py::value_error("sigma is " + numberText(*sigma) + ": gamma = 1 / (2 sigma^2) = " + numberText(g) +
                          " is beyond (0, 1e300]");
  const svm::Kernel kernel = sigma ? svm::Kernel::rbfFromSigma(*sigma) : svm::Kernel::rbf(gamma.value_or(1.0));
  svm::SolverOptions options;
  options.eps = numberArgument(eps, "eps");
  options.max_iterations = max_iterations;
  options.cache_mb = numberArgument(cache_mb, "cache_mb");
  options.shrinking = shrinking;
  if (const std::string why = options.validate(); !why.empty()) throw py::value_error("solver options: " + why);
  Model m;
  {
    py::gil_scoped_release release;
    m.solution = svm::solveBinary(X, y, C, kernel, options);
  }
  m.model = svm::BinaryModel::fromSolution(X, y, m.solution, kernel);
  if (m.model.numSupportVectors() > 0) m.truncated.emplace(m.model);
  for (Eigen::Index i = 0; i < X.cols(); ++i)
    if (m.solution.alpha[i] > 0) m.support_indices.push_back(static_cast<long>(i));
  // libsvm says so too; the model is still feasible, and `converged` tells it apart.
  if (m.solution.status != svm::SolverStatus::kOptimal &&
      PyErr_WarnEx(PyExc_RuntimeWarning,
                   ("svmp.train: stopped after " + std::to_string(m.solution.iterations) +
                    " iterations (max_iterations) before the optimality gap reached eps; the model is not optimal")
                       .c_str(),
                   1) != 0)
    throw py::error_already_set();
  return m;
}

}  // namespace

void bindSvm(py::module_& m) {
  py::class_<Model>(m, "Model", "A trained binary RBF SVM: F(q) = sum_i coef_i exp(-gamma |sv_i - q|^2) + bias.")
      .def_property_readonly("support_vectors", [](const Model& s) { return columnsToArray(s.model.supportVectors()); },
                             "(m, d) array, one support vector a row")
      .def_property_readonly("coefficients", [](const Model& s) { return vectorToArray(s.model.coefficients()); },
                             "(m,) array, y_i alpha_i")
      .def_property_readonly("support_indices", [](const Model& s) { return s.support_indices; },
                             "rows of the training X that are support vectors (alpha > 0), in order")
      .def_property_readonly("bias", [](const Model& s) { return s.model.bias(); })
      .def_property_readonly("gamma", [](const Model& s) { return s.model.kernel().gamma; })
      .def_property_readonly("dim", [](const Model& s) { return s.model.dim(); })
      .def_property_readonly("alpha", [](const Model& s) { return vectorToArray(s.solution.alpha); },
                             "(n,) dual variables in training order")
      .def_property_readonly("objective", [](const Model& s) { return s.solution.objective; },
                             "0.5 alpha'Q alpha - e'alpha, as libsvm reports it")
      .def_property_readonly("iterations", [](const Model& s) { return s.solution.iterations; })
      .def_property_readonly("converged", [](const Model& s) { return s.solution.status == svm::SolverStatus::kOptimal; })
      .def_property_readonly("truncation_bound", [](const Model& s) { return s.truncated ? s.truncated->truncationBound() : 0.0; },
                             "max |F_truncated - F| = sum |coef_i| exp(-5)")
      .def("decision", [](const Model& s, const py::object& x, const py::object& truncated) { return evaluate(s, x, false, truncated); },
           py::arg("x"), py::arg("truncated") = false,
           "F at x of shape (d,) (a float) or at each row of (n, d) (an (n,) array); truncated: only terms with "
           "exp(-gamma d^2) >= exp(-5)")
      .def("gradient", [](const Model& s, const py::object& x, const py::object& truncated) { return evaluate(s, x, true, truncated); },
           py::arg("x"), py::arg("truncated") = false, "grad F at x: shape (d,) for one point, (n, d) for rows")
      .def("__repr__", [](const Model& s) {
        return "<svmp.Model d=" + std::to_string(s.model.dim()) + " support_vectors=" +
               std::to_string(s.model.numSupportVectors()) + " gamma=" + numberText(s.model.kernel().gamma) + ">";
      });
  m.def("train", &train, py::arg("X"), py::arg("y"), py::arg("C") = 1.0, py::arg("gamma") = py::none(),
        py::arg("sigma") = py::none(), py::arg("eps") = 1e-3, py::arg("max_iterations") = 10'000'000L,
        py::arg("cache_mb") = 100.0, py::arg("shrinking") = true,
        "Trains a C-SVC with the RBF kernel by svmp's SMO solver. X: (n, d) float64, y: (n,) of +1/-1, C: a number or "
        "(n,) per-sample bounds; gamma or sigma (gamma = 1/(2 sigma^2); default gamma 1). Bad input: ValueError.");
}

}  // namespace svmp::python
