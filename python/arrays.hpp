#pragma once
// NumPy <-> Eigen at the module's boundary (python/). Every argument is checked here, so bad input is a
// ValueError naming the argument, the expected shape and what came instead, never a crash inside the
// library: shapes, sizes and NaN or infinite entries.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace svmp::python {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A number as Python prints it (shortest round-trip digits; nan, inf), for error messages.
std::string numberText(double v);

// `object` as a C-contiguous float64 array with `ndim` dimensions and, when >= 0, `cols` columns
// (ndim 2) or `cols` entries (ndim 1); every entry finite.
DoubleArray checkedArray(const py::handle& object, const std::string& name, int ndim, long cols = -1);

// A number argument (a Python or NumPy real number or 0-d array, a Decimal; not text, a truth value or
// a complex number): a ValueError naming the argument otherwise, not pybind11's TypeError that prints
// every argument.
double numberArgument(const py::handle& value, const std::string& name);
// A truth argument: True, False, a NumPy bool or a 0-d bool array; "no", 1 or None are a
// ValueError naming it.
bool truthArgument(const py::handle& value, const std::string& name);
// A file name, as os.fspath takes it: a str, bytes or an os.PathLike.
std::string pathArgument(const py::handle& value, const std::string& name);
// An integer argument, as Python's operator.index takes it (not a float, text or truth value).
py::int_ integerValue(const py::handle& value, const std::string& name);
// An integer argument in [lo, hi], compared as a Python integer: 2**63 is a ValueError naming the
// argument, not pybind11's TypeError about the signature.
long long integerArgument(const py::int_& value, const std::string& name, long long lo, long long hi,
                          const std::string& why);

// An n x d array of samples as Eigen's d x n (one sample per column, the library's layout).
Eigen::MatrixXd samplesFromArray(const py::handle& object, const std::string& name, long cols = -1);
// A 1-D array of `size` entries (any size when < 0).
Eigen::VectorXd vectorFromArray(const py::handle& object, const std::string& name, long size = -1);

// An n x d NumPy array from n points (d given: also when n is 0).
py::array_t<double> pointsToArray(const std::vector<Eigen::VectorXd>& points, int d);
py::array_t<double> vectorToArray(const Eigen::VectorXd& v);
// d x n (library layout) to n x d.
py::array_t<double> columnsToArray(const Eigen::MatrixXd& columns);

}  // namespace svmp::python
