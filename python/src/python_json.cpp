#include "python_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"
#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_file.hpp"

namespace py = pybind11;

namespace lightcone {
namespace {

class JsonWriter {
 public:
  // `source` names the value in messages: kDictSource, or "--set" for the value of the override
  // at `path`.
  JsonWriter(std::string source, std::string path)
      : source_(std::move(source)), path_(std::move(path)) {
    const py::module_ numpy = py::module_::import("numpy");
    for (const char* name : {"ndarray", "bool_", "integer", "floating"})
      numpy_.push_back(numpy.attr(name));
    mapping_ = py::module_::import("collections.abc").attr("Mapping");
  }

  std::string write(py::handle value) {
    this->value(value, 0);
    return std::move(out_);
  }

 private:
  // A step of the path from the root: a member's key (a str), or an element's index.
  struct Step {
    py::handle key;
    std::size_t index = 0;
  };

  [[noreturn]] void fail(const std::string& what) const {
    std::string path = path_;
    for (const Step& step : steps_) {
      if (!step.key) {
        path = json_element_path(path, step.index);
        continue;
      }
      // (A key with a lone surrogate is no UTF-8: shown escaped.)
      const py::object bytes = py::reinterpret_steal<py::object>(
          PyUnicode_AsEncodedString(step.key.ptr(), "utf-8", "backslashreplace"));
      path = json_member_path(path, bytes ? std::string(py::bytes(bytes)) : "?");
    }
    if (source_ == "--set") throw InputError(fmt::format("--set {}: {}", path, what));
    throw InputError(fmt::format("{}: {}: {}", source_, path.empty() ? "(top level)" : path, what));
  }

  // The text so far plus `more` bytes is still within a scene file's limit.
  void reserve(std::size_t more) const {
    if (out_.size() + more > kMaxSceneFileBytes) {
      const std::string what = fmt::format(
          "more than the limit of {} bytes as JSON text (a scene file's)", kMaxSceneFileBytes);
      if (source_ == "--set") throw InputError(fmt::format("--set {}: {}", path_, what));
      throw InputError(fmt::format("{}: {}", source_, what));
    }
  }
  void append(std::string_view text) {
    reserve(text.size());
    out_ += text;
  }

  void value(py::handle v, int depth) {
    PyObject* p = v.ptr();
    if (PyUnicode_Check(p)) return string(v);
    if (PyBool_Check(p)) return append(p == Py_True ? "true" : "false");
    if (PyLong_Check(p)) return integer(v);
    if (PyFloat_Check(p)) return number(PyFloat_AS_DOUBLE(p));
    if (PyDict_Check(p)) return object(v, depth);
    if (PyList_Check(p) || PyTuple_Check(p)) return array(v, depth);
    if (p == Py_None) return append("null");
    if (isinstance(v, numpy_[0])) {
      // At least one character and a comma an element: a huge array is refused before its
      // elements are made.
      if (const auto n = v.attr("size").cast<std::size_t>(); n > 0) reserve(2 * n - 1);
      return value(v.attr("tolist")(), depth);
    }
    if (isinstance(v, numpy_[1])) return append(PyObject_IsTrue(p) ? "true" : "false");
    if (isinstance(v, numpy_[2]))
      return integer(py::reinterpret_steal<py::object>(check(PyNumber_Index(p))));
    if (isinstance(v, numpy_[3])) {
      const double d = PyFloat_AsDouble(p);
      if (d == -1 && PyErr_Occurred()) throw py::error_already_set();
      return number(d);
    }
    if (isinstance(v, mapping_))
      return object(py::dict(py::reinterpret_borrow<py::object>(v)), depth);
    fail(
        fmt::format("must be a dict, list, str, number, bool or None (the scene format's JSON), "
                    "got {}",
                    py::str(py::type::handle_of(v).attr("__name__")).cast<std::string>()));
  }

  static bool isinstance(py::handle v, const py::object& type) {
    const int is = PyObject_IsInstance(v.ptr(), type.ptr());
    if (is < 0) throw py::error_already_set();
    return is == 1;
  }
  static PyObject* check(PyObject* made) {
    if (!made) throw py::error_already_set();
    return made;
  }

  void number(double d) {
    if (std::isnan(d)) fail("must be a finite number, got nan");
    if (std::isinf(d)) fail(fmt::format("must be a finite number, got {}", d));
    // The shortest text that reads back as d (as Python's repr), still a float when whole.
    char text[40];
    char* end = fmt::format_to(text, "{}", d);
    if (std::all_of(text, end, [](char c) { return c == '-' || (c >= '0' && c <= '9'); }))
      end = std::copy_n(".0", 2, end);
    append(std::string_view(text, static_cast<std::size_t>(end - text)));
  }

  void integer(py::handle v) {
    int overflow = 0;
    const long long i = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (i == -1 && PyErr_Occurred()) throw py::error_already_set();
    if (overflow == 0) return append(fmt::format_int(i).c_str());
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(v.ptr());
      if (!PyErr_Occurred()) return append(fmt::format_int(u).c_str());
      PyErr_Clear();
    }
    // Beyond 64 bits: the nearest double, as the program reads so large a whole number.
    const double d = PyLong_AsDouble(v.ptr());
    if (d == -1 && PyErr_Occurred()) {
      PyErr_Clear();
      fail("must be a finite number, got a whole number beyond a double's range");
    }
    number(d);
  }

  void string(py::handle v) {
    Py_ssize_t size = 0;
    const char* text = PyUnicode_AsUTF8AndSize(v.ptr(), &size);
    if (!text) {
      PyErr_Clear();
      fail("must be text (UTF-8), got a str with a lone surrogate");
    }
    reserve(static_cast<std::size_t>(size) + 2);
    out_ += '"';
    const std::string_view s(text, static_cast<std::size_t>(size));
    std::size_t start = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
      const auto c = static_cast<unsigned char>(s[k]);
      if (c >= 0x20 && c != '"' && c != '\\') continue;
      out_.append(s.substr(start, k - start));
      append(c == '"' ? "\\\"" : c == '\\' ? "\\\\" : fmt::format("\\u{:04x}", c));
      start = k + 1;
    }
    out_.append(s.substr(start));
    out_ += '"';
  }

  void open(int depth) const {
    if (depth >= kMaxSceneNesting)
      fail(fmt::format("nested more than {} levels deep", kMaxSceneNesting));
  }

  void object(py::handle v, int depth) {
    open(depth);
    append("{");
    PyObject *key = nullptr, *item = nullptr;
    Py_ssize_t at = 0;
    bool first = true;
    while (PyDict_Next(v.ptr(), &at, &key, &item)) {
      // Held while they are walked (a numpy conversion runs Python code).
      const py::object held_key = py::reinterpret_borrow<py::object>(key);
      const py::object held_item = py::reinterpret_borrow<py::object>(item);
      if (!PyUnicode_Check(key))
        fail(fmt::format("a key must be a str, got {} {}",
                         py::str(py::type::handle_of(key).attr("__name__")).cast<std::string>(),
                         py::repr(key).cast<std::string>()));
      if (!first) append(",");
      first = false;
      string(key);
      append(":");
      steps_.push_back({key});
      value(item, depth + 1);
      steps_.pop_back();
    }
    append("}");
  }

  void array(py::handle v, int depth) {
    open(depth);
    append("[");
    const bool list = PyList_Check(v.ptr());
    for (Py_ssize_t k = 0; k < (list ? PyList_GET_SIZE(v.ptr()) : PyTuple_GET_SIZE(v.ptr())); ++k) {
      const py::object item = py::reinterpret_borrow<py::object>(
          list ? PyList_GET_ITEM(v.ptr(), k) : PyTuple_GET_ITEM(v.ptr(), k));
      if (k > 0) append(",");
      steps_.push_back({py::handle(), static_cast<std::size_t>(k)});
      value(item, depth + 1);
      steps_.pop_back();
    }
    append("]");
  }

  std::string source_, path_;
  std::vector<py::object> numpy_;  // ndarray, bool_, integer, floating
  py::object mapping_;
  std::vector<Step> steps_;
  std::string out_;
};

}  // namespace

std::string json_text(py::handle value, const std::string& source, const std::string& path) {
  return JsonWriter(source, path).write(value);
}

}  // namespace lightcone
