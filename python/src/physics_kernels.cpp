#include "physics_kernels.hpp"

#include <pybind11/numpy.h>

#include <string>

#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"

namespace py = pybind11;

namespace lightcone {
namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The n rows of `a`, each of `width` numbers (checked by the package; asserted here).
const double* rows(const Rows& a, py::ssize_t n, py::ssize_t width, const char* name) {
  if (a.ndim() != 2 || a.shape(0) != n || a.shape(1) != width)
    throw py::value_error(std::string(name) + ": expected shape (" + std::to_string(n) + ", " +
                          std::to_string(width) + ")");
  return a.data();
}

Vec3 vec3(const double* p) {
  return {p[0], p[1], p[2]};
}

}  // namespace

void add_physics_kernels(py::module_ m) {
  m.def(
      "aberrate",
      [](const Rows& directions, const Rows& beta) {
        const py::ssize_t n = directions.shape(0);
        const double* d = rows(directions, n, 3, "directions");
        const double* b = rows(beta, n, 3, "beta");
        py::array_t<double> out({n, py::ssize_t{3}});
        double* o = out.mutable_data();
        {
          py::gil_scoped_release unlocked;
          for (py::ssize_t i = 0; i < n; ++i) {
            const Vec3 v = aberrate_into_moving_frame(vec3(d + 3 * i), vec3(b + 3 * i));
            o[3 * i] = v.x, o[3 * i + 1] = v.y, o[3 * i + 2] = v.z;
          }
        }
        return out;
      },
      py::arg("directions"), py::arg("beta"));
  m.def(
      "doppler_factor",
      [](const Rows& n_rows, const Rows& beta_e, const Rows& beta_r) {
        const py::ssize_t n = n_rows.shape(0);
        const double* d = rows(n_rows, n, 3, "n");
        const double* e = rows(beta_e, n, 3, "beta_emitter");
        const double* r = rows(beta_r, n, 3, "beta_receiver");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        {
          py::gil_scoped_release unlocked;
          for (py::ssize_t i = 0; i < n; ++i)
            o[i] = doppler_factor(vec3(d + 3 * i), vec3(e + 3 * i), vec3(r + 3 * i));
        }
        return out;
      },
      py::arg("n"), py::arg("beta_emitter"), py::arg("beta_receiver"));
  m.def(
      "lorentz_boost",
      [](const Rows& events, const Rows& beta) {
        const py::ssize_t n = events.shape(0);
        const double* x = rows(events, n, 4, "events");
        const double* b = rows(beta, n, 3, "beta");
        py::array_t<double> out({n, py::ssize_t{4}});
        double* o = out.mutable_data();
        {
          py::gil_scoped_release unlocked;
          for (py::ssize_t i = 0; i < n; ++i) {
            const Vec4 v = boost(vec3(b + 3 * i)) * Vec4{x[4 * i], vec3(x + 4 * i + 1)};
            o[4 * i] = v.t, o[4 * i + 1] = v.x.x, o[4 * i + 2] = v.x.y, o[4 * i + 3] = v.x.z;
          }
        }
        return out;
      },
      py::arg("events"), py::arg("beta"));
  m.def(
      "retarded_delay",
      [](const Rows& delta, const Rows& beta) {
        const py::ssize_t n = delta.shape(0);
        const double* d = rows(delta, n, 3, "delta");
        const double* b = rows(beta, n, 3, "beta");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        {
          py::gil_scoped_release unlocked;
          for (py::ssize_t i = 0; i < n; ++i)
            o[i] = retarded_delay(vec3(d + 3 * i), vec3(b + 3 * i));
        }
        return out;
      },
      py::arg("delta"), py::arg("beta"));
}

}  // namespace lightcone
