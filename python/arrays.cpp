#include "python/arrays.hpp"

#include <cmath>

namespace svmp::python {

std::string numberText(double v) { return py::repr(py::float_(v)); }

namespace {

// Text, truth values and complex numbers convert to numbers in Python (float("2"), float(np.bool_),
// np.complex128.__float__) but are not the numbers an argument means.
bool looksLikeNoNumber(const py::handle& value) {
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::isinstance<py::bool_>(value) ||
      PyComplex_Check(value.ptr()))
    return true;
  if (!py::hasattr(value, "dtype")) return false;
  try {
    const char kind = py::dtype::from_args(value.attr("dtype")).kind();
    return kind == 'b' || kind == 'c' || kind == 'U' || kind == 'S' || kind == 'O';
  } catch (const py::error_already_set&) {
    return false;  // a `dtype` that is not NumPy's: its float() decides
  }
}

[[noreturn]] void refuse(const py::handle& value, const std::string& name, const std::string& why) {
  throw py::value_error(name + " is " + py::repr(value).cast<std::string>() + ": " + why);
}

}  // namespace

double numberArgument(const py::handle& value, const std::string& name) {
  if (looksLikeNoNumber(value)) refuse(value, name, "expected a real number");
  PyObject* as_float = PyNumber_Float(value.ptr());  // Python and NumPy numbers, 0-d arrays, Decimal
  if (!as_float) {
    const bool overflow = PyErr_ExceptionMatches(PyExc_OverflowError);
    PyErr_Clear();
    refuse(value, name, overflow ? "out of a double's range" : "expected a real number");
  }
  const double v = PyFloat_AsDouble(as_float);
  Py_DECREF(as_float);
  return v;
}

bool truthArgument(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::hasattr(value, "dtype") && py::hasattr(value, "ndim") && py::hasattr(value, "item")) {
    try {  // np.bool_ or a 0-d bool array, as integers take 0-d arrays
      if (py::dtype::from_args(value.attr("dtype")).kind() == 'b' && value.attr("ndim").cast<int>() == 0)
        return value.attr("item")().cast<bool>();
    } catch (const py::error_already_set&) {
    }
  }
  refuse(value, name, "expected True or False");
}

std::string pathArgument(const py::handle& value, const std::string& name) {
  PyObject* path = PyOS_FSPath(value.ptr());  // os.fspath: str, bytes, os.PathLike
  if (!path) {
    PyErr_Clear();
    refuse(value, name, "expected a file name (str, bytes or os.PathLike)");
  }
  const py::object text = py::reinterpret_steal<py::object>(path);
  // As open() encodes it: str in the file system's encoding (undecodable bytes kept by
  // surrogateescape), bytes as they are; a NUL byte would cut the name short in C.
  PyObject* encoded = nullptr;
  if (!PyUnicode_FSConverter(text.ptr(), &encoded)) {
    const bool unencodable = PyErr_ExceptionMatches(PyExc_UnicodeEncodeError);
    PyErr_Clear();
    refuse(value, name, unencodable ? "cannot be encoded in the file system's encoding"
                                    : "a file name cannot hold a NUL byte");
  }
  const py::bytes bytes = py::reinterpret_steal<py::bytes>(encoded);
  return bytes.cast<std::string>();
}

py::int_ integerValue(const py::handle& value, const std::string& name) {
  if (looksLikeNoNumber(value)) refuse(value, name, "expected an integer");
  PyObject* as_int = PyNumber_Index(value.ptr());  // Python and NumPy integers, 0-d integer arrays
  if (!as_int) {
    PyErr_Clear();
    refuse(value, name, "expected an integer");
  }
  return py::reinterpret_steal<py::int_>(as_int);
}

long long integerArgument(const py::int_& value, const std::string& name, long long lo, long long hi,
                          const std::string& why) {
  if (value < py::int_(lo) || value > py::int_(hi))
    throw py::value_error(name + " is " + py::str(static_cast<const py::object&>(value)).cast<std::string>() + ": " + why);
  return value.cast<long long>();
}

DoubleArray checkedArray(const py::handle& object, const std::string& name, int ndim, long cols) {
  // forcecast would drop an imaginary part with only NumPy's warning, and read text ("1.5") and
  // booleans as numbers, which the scalar arguments refuse.
  if (const py::array raw = py::array::ensure(object); raw) {
    const char kind = raw.dtype().kind();
    if (kind == 'c') throw py::value_error(name + ": expected real numbers, got an array of complex numbers");
    if (kind != 'f' && kind != 'i' && kind != 'u')
      throw py::value_error(name + ": expected an array of numbers, got one of dtype " +
                            std::string(py::str(raw.dtype())));
  }
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
