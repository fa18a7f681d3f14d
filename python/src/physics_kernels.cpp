#include "physics_kernels.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/physics/world_line.hpp"
#include "lightcone/portable.hpp"

namespace py = pybind11;

namespace lightcone {
namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Rows of `width` numbers: n of them, or one shared by all n (a broadcast vector, read with
// step 0 rather than copied n times).
struct RowReader {
  const double* data;
  py::ssize_t step;
  const double* operator[](py::ssize_t i) const { return data + step * i; }
};

RowReader rows(const Rows& a, py::ssize_t n, py::ssize_t width, const char* name) {
  if (a.ndim() != 2 || (a.shape(0) != n && a.shape(0) != 1) || a.shape(1) != width)
    throw py::value_error(std::string(name) + ": expected shape (" + std::to_string(n) + ", " +
                          std::to_string(width) + ") or (1, " + std::to_string(width) + ")");
  return {a.data(), a.shape(0) == 1 ? 0 : width};
}

py::ssize_t count(std::initializer_list<const Rows*> arrays) {
  py::ssize_t n = 1;
  for (const Rows* a : arrays)
    if (a->ndim() == 2 && a->shape(0) != 1) n = a->shape(0);
  return n;
}

Vec3 vec3(const double* p) {
  return {p[0], p[1], p[2]};
}

// The package checks the name.
SearchlightModel searchlight_named(const std::string& name) {
  return name == "chang1996" ? SearchlightModel::kChang1996
         : name == "off"     ? SearchlightModel::kOff
                             : SearchlightModel::kPhysical;
}

// The linear sRGB colour received from `emitted` seen with factor d (three numbers at out):
// the emission tables' quadrature of L(d lambda) against the CIE observer, times the
// searchlight factor on spectral radiance.
template <class Spectrum>
void put_received(const Spectrum& emitted, double d, SearchlightModel model, double* out) {
  const Xyz seen = xyz_seen_with_doppler(emitted, d);
  const double factor = spectral_searchlight(d, model);
  const LinearRgb c = linear_srgb_from_xyz({seen.x * factor, seen.y * factor, seen.z * factor});
  out[0] = c.r, out[1] = c.g, out[2] = c.b;
}

// body(i) for i in [0, n), on every core, without the GIL.
template <class Body>
void each_row(py::ssize_t n, const Body& body) {
  py::gil_scoped_release unlocked;
  parallel_for_pieces(py::ssize_t{0}, n, py::ssize_t{16384},
                      [&](py::ssize_t begin, py::ssize_t end) {
                        for (py::ssize_t i = begin; i < end; ++i) body(i);
                      });
}

}  // namespace

void add_physics_kernels(py::module_ m) {
  m.def(
      "aberrate",
      [](const Rows& directions, const Rows& beta) {
        const py::ssize_t n = count({&directions, &beta});
        const RowReader d = rows(directions, n, 3, "directions"), b = rows(beta, n, 3, "beta");
        py::array_t<double> out({n, py::ssize_t{3}});
        double* o = out.mutable_data();
        if (b.step == 0) {
          // One frame for every direction: its gamma once.
          const Vec3 beta0 = vec3(b[0]);
          const double g = lorentz_gamma(beta0);
          each_row(n, [&](py::ssize_t i) {
            const Vec3 v = aberrate_into_moving_frame_with_gamma(vec3(d[i]), beta0, g);
            o[3 * i] = v.x, o[3 * i + 1] = v.y, o[3 * i + 2] = v.z;
          });
        } else {
          each_row(n, [&](py::ssize_t i) {
            const Vec3 v = aberrate_into_moving_frame(vec3(d[i]), vec3(b[i]));
            o[3 * i] = v.x, o[3 * i + 1] = v.y, o[3 * i + 2] = v.z;
          });
        }
        return out;
      },
      py::arg("directions"), py::arg("beta"));
  m.def(
      "doppler_factor",
      [](const Rows& n_rows, const Rows& beta_e, const Rows& beta_r) {
        const py::ssize_t n = count({&n_rows, &beta_e, &beta_r});
        const RowReader d = rows(n_rows, n, 3, "n"), e = rows(beta_e, n, 3, "beta_emitter"),
                        r = rows(beta_r, n, 3, "beta_receiver");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        if (e.step == 0 && r.step == 0) {
          // One emitter and one receiver for every direction: their 4-velocities once (the
          // same numbers the three-velocity form computes for each).
          const Vec4 u_e = four_velocity(vec3(e[0])), u_r = four_velocity(vec3(r[0]));
          each_row(n, [&](py::ssize_t i) {
            o[i] = doppler_factor_of_four_velocities(vec3(d[i]), u_e, u_r);
          });
        } else {
          each_row(
              n, [&](py::ssize_t i) { o[i] = doppler_factor(vec3(d[i]), vec3(e[i]), vec3(r[i])); });
        }
        return out;
      },
      py::arg("n"), py::arg("beta_emitter"), py::arg("beta_receiver"));
  m.def(
      "lorentz_boost",
      [](const Rows& events, const Rows& beta) {
        const py::ssize_t n = count({&events, &beta});
        const RowReader x = rows(events, n, 4, "events"), b = rows(beta, n, 3, "beta");
        py::array_t<double> out({n, py::ssize_t{4}});
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) {
          const Vec4 v = boost(vec3(b[i])) * Vec4{x[i][0], vec3(x[i] + 1)};
          o[4 * i] = v.t, o[4 * i + 1] = v.x.x, o[4 * i + 2] = v.x.y, o[4 * i + 3] = v.x.z;
        });
        return out;
      },
      py::arg("events"), py::arg("beta"));
  m.def(
      "blackbody",
      [](const Rows& wavelength, const Rows& temperature) {
        const py::ssize_t n = count({&wavelength, &temperature});
        const RowReader l = rows(wavelength, n, 1, "wavelength_nm"),
                        t = rows(temperature, n, 1, "temperature_k");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) { o[i] = planck_radiance(l[i][0], t[i][0]); });
        return out;
      },
      py::arg("wavelength_nm"), py::arg("temperature_k"));
  m.def(
      "received_blackbody",
      [](const Rows& temperature, const Rows& doppler, const Rows& luminance,
         const std::string& searchlight) {
        const py::ssize_t n = count({&temperature, &doppler, &luminance});
        const RowReader t = rows(temperature, n, 1, "temperature_k"),
                        d = rows(doppler, n, 1, "doppler"), y = rows(luminance, n, 1, "luminance");
        const SearchlightModel model = searchlight_named(searchlight);
        py::array_t<double> out({n, py::ssize_t{3}});
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) {
          // A luminance below 0: Planck's radiance itself (scale 1).
          const BlackbodySpectrum emitted =
              y[i][0] < 0 ? BlackbodySpectrum{t[i][0], 1.0}
                          : BlackbodySpectrum::with_luminance(t[i][0], y[i][0]);
          put_received(emitted, d[i][0], model, o + 3 * i);
        });
        return out;
      },
      py::arg("temperature_k"), py::arg("doppler"), py::arg("luminance"), py::arg("searchlight"));
  m.def(
      "received_spectrum",
      [](const std::vector<double>& wavelengths, const std::vector<double>& values,
         const Rows& doppler, const std::string& searchlight) {
        const TabulatedSpectrum emitted{wavelengths, values};
        const py::ssize_t n = doppler.ndim() == 2 ? doppler.shape(0) : 0;
        const RowReader d = rows(doppler, n, 1, "doppler");
        const SearchlightModel model = searchlight_named(searchlight);
        py::array_t<double> out({n, py::ssize_t{3}});
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) { put_received(emitted, d[i][0], model, o + 3 * i); });
        return out;
      },
      py::arg("wavelengths_nm"), py::arg("values"), py::arg("doppler"), py::arg("searchlight"));
  m.def(
      "retarded_time_accelerated",
      [](const Rows& events, double time, const std::array<double, 3>& position,
         const std::array<double, 3>& velocity,
         const std::vector<std::pair<double, std::array<double, 3>>>& phases) {
        std::vector<AccelerationPhase> pieces;
        for (const auto& [duration, a] : phases) pieces.push_back({duration, {a[0], a[1], a[2]}});
        const AcceleratedWorldLine line(time, vec3(position.data()), vec3(velocity.data()), pieces);
        const py::ssize_t n = events.ndim() == 2 ? events.shape(0) : 0;
        const RowReader x = rows(events, n, 4, "observer_events");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) {
          o[i] = line.retarded(Vec4{x[i][0], vec3(x[i] + 1)}).event.t;
        });
        return out;
      },
      py::arg("events"), py::arg("time"), py::arg("position"), py::arg("velocity"),
      py::arg("phases"));
  m.def(
      "retarded_delay",
      [](const Rows& delta, const Rows& beta) {
        const py::ssize_t n = count({&delta, &beta});
        const RowReader d = rows(delta, n, 3, "delta"), b = rows(beta, n, 3, "beta");
        py::array_t<double> out(n);
        double* o = out.mutable_data();
        each_row(n, [&](py::ssize_t i) { o[i] = retarded_delay(vec3(d[i]), vec3(b[i])); });
        return out;
      },
      py::arg("delta"), py::arg("beta"));
}

}  // namespace lightcone
