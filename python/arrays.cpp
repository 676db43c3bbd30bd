#include "python/arrays.hpp"

#include <cmath>

namespace svmp::python {

std::string numberText(double v) { return py::repr(py::float_(v)); }

double numberArgument(const py::handle& value, const std::string& name) {
  const py::object real = py::module_::import("numbers").attr("Real");
  if (py::isinstance<py::bool_>(value) || !py::isinstance(value, real))
    throw py::value_error(name + " is " + py::repr(value).cast<std::string>() + ": expected a real number");
  return value.cast<double>();
}

long long integerArgument(const py::int_& value, const std::string& name, long long lo, long long hi,
                          const std::string& why) {
  if (value < py::int_(lo) || value > py::int_(hi))
    throw py::value_error(name + " is " + py::str(static_cast<const py::object&>(value)).cast<std::string>() + ": " + why);
  return value.cast<long long>();
}

DoubleArray checkedArray(const py::handle& object, const std::string& name, int ndim, long cols) {
  // forcecast would drop an imaginary part with only NumPy's warning.
  if (const py::array raw = py::array::ensure(object); raw && raw.dtype().kind() == 'c')
    throw py::value_error(name + ": expected real numbers, got an array of complex numbers");
  DoubleArray a = DoubleArray::ensure(object);
  if (!a) throw py::value_error(name + ": expected an array of numbers, got " + std::string(py::str(py::type::of(object))));
  const std::string shape = ndim == 2 ? "(n, " + (cols >= 0 ? std::to_string(cols) : std::string("d")) + ")"
                                      : "(" + (cols >= 0 ? std::to_string(cols) : std::string("n")) + ",)";
  std::string got = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) got += (k ? ", " : "") + std::to_string(a.shape(k));
  got += a.ndim() == 1 ? ",)" : ")";
  if (a.ndim() != ndim || (cols >= 0 && a.shape(ndim - 1) != cols))
    throw py::value_error(name + ": expected shape " + shape + ", got " + got);
  const double* data = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(data[i])) {
      const std::string where = ndim == 2 ? "[" + std::to_string(i / a.shape(1)) + ", " + std::to_string(i % a.shape(1)) + "]"
                                          : "[" + std::to_string(i) + "]";
      throw py::value_error(name + where + " is " + numberText(data[i]) + ": entries must be finite");
    }
  return a;
}

Eigen::MatrixXd samplesFromArray(const py::handle& object, const std::string& name, long cols) {
  const DoubleArray a = checkedArray(object, name, 2, cols);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(a.data(), a.shape(0), a.shape(1)).transpose();
}

Eigen::VectorXd vectorFromArray(const py::handle& object, const std::string& name, long size) {
  const DoubleArray a = checkedArray(object, name, 1, size);
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

py::array_t<double> pointsToArray(const std::vector<Eigen::VectorXd>& points, int d) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), static_cast<py::ssize_t>(d)});
  auto view = out.mutable_unchecked<2>();
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < d; ++k) view(i, k) = points[i][k];
  return out;
}

py::array_t<double> vectorToArray(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array_t<double> columnsToArray(const Eigen::MatrixXd& columns) {
  py::array_t<double> out({static_cast<py::ssize_t>(columns.cols()), static_cast<py::ssize_t>(columns.rows())});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < columns.cols(); ++i)
    for (Eigen::Index k = 0; k < columns.rows(); ++k) view(i, k) = columns(k, i);
  return out;
}

}  // namespace svmp::python
