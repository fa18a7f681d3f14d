#include "lightcone/io/scene_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string_view>
#include <unordered_map>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/mesh_file.hpp"
#include "lightcone/io/scene_document.hpp"
#include "lightcone/io/scene_overrides.hpp"
#include "lightcone/io/scene_parse.hpp"
#include "lightcone/io/scene_value_reader.hpp"
#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone::scene_io {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxImageSide = 16384;
constexpr std::int64_t kMaxPixels = std::int64_t{1} << 27;
constexpr int kMaxSamples = 65536;

Vec4 four_velocity(const Vec3& beta) {
  const double gamma = lorentz_gamma(beta);
  return {gamma, beta * gamma};
}

// Validates the document and builds the scene. Every check names the path of the offending
// value; the line comes from the locator, or the message blames a --set override.
class SceneReader : public SceneValueReader {
 public:
  SceneReader(const fs::path& file, const JsonLineMap& lines, std::vector<std::string> overridden,
              SceneLoadReport& report, const SceneLoadOptions& options)
      : SceneValueReader(file, lines, std::move(overridden)), report_(report), options_(options) {}

  Scene read(const json& document) {
    const Node root{&document};
    object(root, {"$schema", "speed_of_light", "camera", "objects", "lights", "sky", "render"});
    if (Node schema = member(root, "$schema"); schema.value) string(schema);
    // Every speed, time and acceleration in the file is in the scene's units; the engine's are
    // those where c = 1: times become c t, speeds v / c, accelerations a / c^2.
    if (Node c = member(root, "speed_of_light"); c.value) {
      c_ = positive(c);
      if (!std::isfinite(c_)) fail(c, "must be finite");
    }
    Scene scene;
    scene.speed_of_light = c_;
    scene.camera = camera(member(root, "camera"));
    add_camera_observers(scene.camera);
    if (Node objects = member(root, "objects"); objects.value) read_objects(objects, scene);
    if (Node lights = member(root, "lights"); lights.value) read_lights(lights, scene);
    if (Node sky_node = member(root, "sky"); sky_node.value) scene.sky = sky(sky_node);
    if (Node render_node = member(root, "render"); render_node.value)
      scene.render = render(render_node);
    load_assets(scene);
    check_spins(scene);
    return scene;
  }

 private:
  // A mesh or image file named at `path`, to be loaded once the whole document is valid (so that
  // a typo near the end does not wait for large files to load first).
  struct Asset {
    enum Kind { kMesh, kTexture, kSkyImage } kind;
    std::size_t object = 0;
    fs::path file;
    std::string path;
  };

  // --- Sections ---------------------------------------------------------------------------

  Camera camera(const Node& n) const {
    object(n, {"position", "time", "velocity", "proper_time", "motion", "shutter", "forward", "up",
               "fov", "width", "height", "samples"});
    Camera c;
    // Keyframes say where the camera is; otherwise its position is required.
    const Node motion_node = member(n, "motion");
    const bool keyframed = motion_node.value && motion_node.value->is_object() &&
                           motion_node.value->contains("keyframes");
    if (!keyframed || member(n, "position").value)
      c.world_line.position = vec3(member(n, "position"));
    if (Node t = member(n, "time"); t.value) c.world_line.time = time(t);
    if (Node v = member(n, "velocity"); v.value) c.world_line.velocity = velocity(v);
    c.motion.start = c.world_line;
    if (Node m = member(n, "motion"); m.value) {
      const BodyMotion moves = body_motion(n, m, c.motion.start);
      c.motion.phases = moves.phases;
      c.motion.keyframes = moves.keyframes;
    }
    if (Node tau = member(n, "proper_time"); tau.value) c.motion.proper_time = time(tau);
    // The observation: the camera's event and velocity at its proper time. (Its whole
    // world-line is within the limit already; this holds against rounding.)
    c.world_line = camera_observation(c.motion);
    {
      const double speed = length(c.world_line.velocity);
      const Node where = member(n, "motion").value ? member(n, "motion") : member(n, "proper_time");
      limit_gamma(where, 1 / std::sqrt((1 - speed) * (1 + speed)),
                  fmt::format("at proper time {} the camera's speed {}", c.motion.proper_time / c_,
                              speed * c_),
                  observers_.front());
    }
    if (Node f = member(n, "forward"); f.value) c.forward = direction(f);
    if (Node u = member(n, "up"); u.value) c.up = direction(u);
    if (length(cross(c.forward, c.up)) < 1e-9) {
      const Node up = member(n, "up");
      fail(up, up.value ? "must not be parallel to camera.forward"
                        : "must not be parallel to camera.forward (up defaults to [0, 1, 0])");
    }
    if (Node fov = member(n, "fov"); fov.value) {
      c.fov_degrees = number(fov);
      if (!(c.fov_degrees > 0 && c.fov_degrees < 180))
        fail(fov, fmt::format("must be between 0 and 180 degrees (both excluded), got {}",
                              c.fov_degrees));
    }
    const Node width = member(n, "width"), height = member(n, "height");
    if (width.value) c.width = integer(width, 1, kMaxImageSide);
    if (height.value) c.height = integer(height, 1, kMaxImageSide);
    if (std::int64_t{c.width} * c.height > kMaxPixels)
      fail(width, fmt::format("{} x {} pixels is more than the limit of {} (2^27)", c.width,
                              c.height, kMaxPixels));
    if (Node s = member(n, "samples"); s.value) c.samples = integer(s, 1, kMaxSamples);
    if (Node sh = member(n, "shutter"); sh.value) {
      c.shutter = non_negative(sh) * c_;
      if (!std::isfinite(c.shutter)) fail(sh, "must be finite");
      // The observation at the shutter's close must be one double precision can hold.
      const WorldLine closing = observation_after(c, c.shutter);
      const double speed = length(closing.velocity);
      limit_gamma(sh, 1 / std::sqrt((1 - speed) * (1 + speed)),
                  fmt::format("at the shutter's close the camera's speed {}", speed * c_),
                  observers_.front());
    }
    return c;
  }

  // The camera as an observer of every other speed: at its observation, and while its shutter
  // is open at the shutter's close and at every phase's end in between (a phase's gamma relative
  // to a body's phase is convex in each proper time, so the largest is at these ends), or every
  // keyframe in between.
  void add_camera_observers(const Camera& c) {
    observers_.push_back({four_velocity(c.world_line.velocity), " relative to the camera"});
    if (!(c.shutter > 0)) return;
    const double open = c.motion.proper_time, close = open + c.shutter;
    const std::string during = " relative to the camera while its shutter is open";
    const auto add_at = [&](double tau) {
      Camera::Motion m = c.motion;
      m.proper_time = tau;
      observers_.push_back({four_velocity(camera_observation(m).velocity), during});
    };
    double end = 0;
    for (const AccelerationPhase& p : c.motion.phases)
      if ((end += p.duration) > open && end < close) add_at(end);
    if (!c.motion.keyframes.empty()) {
      const KeyframeWorldLine line(c.motion.keyframes);
      for (const Keyframe& key : c.motion.keyframes)
        if (const WorldLinePoint p = line.at_world_time(key.time);
            p.proper_time > open && p.proper_time < close)
          observers_.push_back({p.four_velocity, during});
    }
    observers_.push_back({four_velocity(observation_after(c, c.shutter).velocity),
                          " relative to the camera at its shutter's close"});
  }

  // "motion": {"phases": [{"duration": tau, "acceleration": [ax, ay, az]}, ...]} or
  // {"keyframes": [{"time": t, "position": [x, y, z]}, ...]}.
  BodyMotion motion(const Node& n) const {
    BodyMotion m;
    if (one_of(n, {"phases", "keyframes"}) == "phases") {
      m.phases = phases(n);
    } else {
      m.keyframes = keyframes(member(n, "keyframes"));
    }
    return m;
  }

  std::vector<Keyframe> keyframes(const Node& list) const {
    if (!list.value->is_array() || list.value->empty())
      fail(list, fmt::format("must be a non-empty array of {{time, position}}, got {}",
                             describe(*list.value)));
    std::vector<Keyframe> out;
    for (std::size_t i = 0; i < list.value->size(); ++i) {
      const Node key = element(list, i);
      object(key, {"time", "position"});
      const Node t = member(key, "time"), p = member(key, "position");
      if (!t.value) fail(key, "needs \"time\"");
      if (!p.value) fail(key, "needs \"position\" [x, y, z]");
      out.push_back({time(t), vec3(p)});
    }
    try {
      const KeyframeWorldLine line(out);
    } catch (const KeyframeError& e) {
      fail(element(list, e.second), e.what());
    }
    return out;
  }

  std::vector<AccelerationPhase> phases(const Node& n) const {
    const Node list = member(n, "phases");
    if (!list.value) fail(n, "needs \"phases\", an array of {duration, acceleration}");
    if (!list.value->is_array())
      fail(list, fmt::format("must be an array of phases, got {}", describe(*list.value)));
    std::vector<AccelerationPhase> out;
    for (std::size_t i = 0; i < list.value->size(); ++i) {
      const Node phase = element(list, i);
      object(phase, {"duration", "acceleration"});
      const Node duration = member(phase, "duration"), acceleration = member(phase, "acceleration");
      if (!duration.value) fail(phase, "needs \"duration\" (proper time, > 0)");
      if (!acceleration.value) fail(phase, "needs \"acceleration\" [ax, ay, az] (not zero)");
      AccelerationPhase p;
      p.duration = positive(duration) * c_;
      p.acceleration = vec3(acceleration) / (c_ * c_);
      if (length(p.acceleration) == 0)
        fail(acceleration,
             "must not be zero (a phase without acceleration is inertial: leave "
             "it out)");
      if (!std::isfinite(length(p.acceleration))) fail(acceleration, "is too large");
      out.push_back(p);
    }
    return out;
  }

  // The motion of the body `n` whose world-line so far is `start`. Keyframes replace the
  // world-line; phases start from its event. Nowhere may the body come too close to the speed
  // of light, in W or relative to the camera: between any two keyframes, or at any phase's end
  // (the largest gamma of a phase is at one of its ends: max_relative_gamma).
  BodyMotion body_motion(const Node& n, const Node& m, WorldLine& start) const {
    BodyMotion motion = this->motion(m);
    if (!motion.keyframes.empty()) {
      for (const char* key : {"position", "time", "velocity"})
        if (member(n, key).value)
          fail(member(n, key),
               "must not be given with motion.keyframes (the keyframes are "
               "where and when the body is)");
      start = {motion.keyframes.front().time, motion.keyframes.front().position, {}, 0};
      const KeyframeWorldLine line(motion.keyframes);
      const Node list = member(m, "keyframes");
      for (const Observer& o : observers_) {
        const KeyframeWorldLine::Fastest f = line.max_gamma(velocity_of(o.four_velocity));
        const std::size_t i = f.segment;
        limit_gamma(element(list, std::min(i + 1, motion.keyframes.size() - 1)), f.gamma,
                    fmt::format("between keyframes {} and {} its speed", i, i + 1), o);
      }
      return motion;
    }
    const AcceleratedWorldLine line(start.time, start.position, start.velocity, motion.phases);
    const Node list = member(m, "phases");
    double end = 0;
    for (std::size_t i = 0; i < motion.phases.size(); ++i) {
      end += motion.phases[i].duration;
      const Vec4 u = line.at_proper_time(end).four_velocity;
      for (const Observer& o : observers_)
        limit_gamma(element(list, i), relative_gamma(o.four_velocity, u),
                    fmt::format("at the end of phase {} its speed", i), o);
    }
    return motion;
  }

  // The array `n` of objects or lights (`noun`s), each read by `read`; no two may have the
  // same name.
  template <class T, class Read>
  void read_named(const Node& n, std::string_view noun, std::vector<T>& out, Read read) {
    if (!n.value->is_array())
      fail(n, fmt::format("must be an array of {}s, got {}", noun, describe(*n.value)));
    const std::size_t count = n.value->size();
    out.reserve(count);
    // Name (in the document, which outlives this) -> index of the first element that has it.
    std::unordered_map<std::string_view, std::size_t> names;
    names.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Node e = element(n, i);
      out.push_back(read(e, i));
      const auto [it, added] =
          names.emplace(member(e, "name").value->get_ref<const std::string&>(), i);
      if (!added)
        fail(member(e, "name"), fmt::format("duplicate {} name \"{}\" (also used by {})", noun,
                                            it->first, json_element_path(n.path(), it->second)));
    }
  }

  void read_objects(const Node& n, Scene& scene) {
    read_named(n, "object", scene.objects,
               [&](const Node& o, std::size_t i) { return read_object(o, i); });
  }

  Object read_object(const Node& n, std::size_t index) {
    object(n, {"name", "shape", "position", "time", "velocity", "motion", "spin", "rotation",
               "scale", "material"});
    Object o;
    const Node name = member(n, "name");
    o.name = string(name);
    if (o.name.empty()) fail(name, "must not be empty");
    o.shape = shape(member(n, "shape"), index);
    if (Node p = member(n, "position"); p.value) o.world_line.position = vec3(p);
    if (Node t = member(n, "time"); t.value) o.world_line.time = time(t);
    if (Node v = member(n, "velocity"); v.value) o.world_line.velocity = velocity(v);
    if (Node m = member(n, "motion"); m.value) o.motion = body_motion(n, m, o.world_line);
    if (Node r = member(n, "rotation"); r.value) o.rotation = rotation(r);
    if (Node s = member(n, "scale"); s.value) {
      if (s.value->is_number()) {
        const double k = positive(s);
        o.scale = {k, k, k};
      } else {
        o.scale = positive_vec3(s);
      }
    }
    if (Node m = member(n, "material"); m.value) o.material = material(m, index);
    if (Node sp = member(n, "spin"); sp.value) {
      object(sp, {"axis", "rate"});
      const Node axis = member(sp, "axis"), rate = member(sp, "rate");
      if (!axis.value) fail(sp, "needs \"axis\" [x, y, z]");
      if (!rate.value) fail(sp, "needs \"rate\" (degrees per unit of the body's proper time)");
      // Degrees per unit of the scene's time, in radians per unit of the engine's (c t).
      o.spin = Spin{direction(axis), number(rate) * std::numbers::pi / 180 / c_};
      spins_.push_back({index, rate.path()});
    }
    return o;
  }

  Shape shape(const Node& n, std::size_t index) {
    const std::string_view kind = one_of(n, {"sphere", "box", "plane", "mesh"});
    const Node body = member(n, kind);
    if (kind == "sphere") {
      object(body, {"radius"});
      return Sphere{positive(member(body, "radius"))};
    }
    if (kind == "box") {
      object(body, {"size"});
      return Box{positive_vec3(member(body, "size"))};
    }
    if (kind == "plane") {
      object(body, {"size"});
      const Node size = member(body, "size");
      numbers(size, 2);
      return Plane{positive(element(size, 0)), positive(element(size, 1))};
    }
    object(body, {"file"});
    const Node file = member(body, "file");
    assets_.push_back({Asset::kMesh, index, file_path(file), file.path()});
    return MeshShape{};
  }

  Material material(const Node& n, std::size_t index) {
    const std::string_view kind =
        one_of(n, {"color", "checker", "texture", "blackbody", "spectrum", "blink", "clock"},
               {"unlit", "glossy"});
    Material m;
    const Node unlit = member(n, "unlit");
    if (unlit.value) m.unlit = boolean(unlit);
    if (!m.unlit && (kind == "blackbody" || kind == "spectrum"))
      fail(unlit, fmt::format("a {} material is an emitter and cannot be lit (a lit material's "
                              "albedo is a color, checker or texture)",
                              kind));
    if (Node glossy = member(n, "glossy"); glossy.value) {
      if (m.unlit) fail(glossy, "a glossy layer needs a lit material (\"unlit\": false)");
      m.glossy = glossy_layer(glossy);
    }
    // A lit surface reflects a fraction of the light: its colours are albedos, in [0, 1].
    auto surface_color = [&](const Node& c) { return m.unlit ? color(c) : albedo(c); };
    const Node body = member(n, kind);
    if (kind == "color") {
      m.pattern = SolidColor{surface_color(body)};
    } else if (kind == "checker") {
      object(body, {"size", "colors"});
      Checker checker;
      checker.size = positive(member(body, "size"));
      const Node colors = member(body, "colors");
      if (!need(colors).is_array() || colors.value->size() != 2)
        fail(colors, fmt::format("must be an array of 2 colours, got {}", describe(*colors.value)));
      checker.colors[0] = surface_color(element(colors, 0));
      checker.colors[1] = surface_color(element(colors, 1));
      m.pattern = checker;
    } else if (kind == "blink" || kind == "clock") {
      // Patterns on the body's own clock: a period of its proper time, two colours.
      const bool blink = kind == "blink";
      object(body, blink ? Names{"period", "duty", "colors"} : Names{"period", "colors"});
      const Node period = member(body, "period");
      const double p = positive(period) * c_;
      if (!std::isfinite(p)) fail(period, "must be finite");
      Rgb colors[2];
      const Node colors_node = member(body, "colors");
      if (colors_node.value) {
        if (!colors_node.value->is_array() || colors_node.value->size() != 2)
          fail(colors_node,
               fmt::format("must be an array of 2 colours, got {}", describe(*colors_node.value)));
        for (int k = 0; k < 2; ++k) colors[k] = surface_color(element(colors_node, k));
      }
      if (blink) {
        Blink b;
        b.period = p;
        if (Node duty = member(body, "duty"); duty.value) b.duty = in_range(duty, 0, 1);
        if (colors_node.value) std::copy(colors, colors + 2, b.colors);
        m.pattern = b;
      } else {
        Clock c;
        c.period = p;
        if (colors_node.value) std::copy(colors, colors + 2, c.colors);
        m.pattern = c;
      }
    } else if (kind == "blackbody") {
      object(body, {"temperature", "luminance"});
      Blackbody b;
      b.temperature_k = positive(member(body, "temperature"));
      if (Node y = member(body, "luminance"); y.value) b.luminance = non_negative(y);
      m.pattern = b;
    } else if (kind == "spectrum") {
      m.pattern = emission_spectrum(body);
    } else {
      assets_.push_back({Asset::kTexture, index, file_path(body), body.path()});
      m.pattern = Texture{};
    }
    return m;
  }

  Glossy glossy_layer(const Node& n) const {
    object(n, {"roughness", "specular"});
    Glossy g;
    if (Node r = member(n, "roughness"); r.value) g.roughness = in_range(r, 0, 1, true);
    if (Node f = member(n, "specular"); f.value) g.specular = in_range(f, 0, 1);
    return g;
  }

  // --- Lights -----------------------------------------------------------------------------

  void read_lights(const Node& n, Scene& scene) {
    read_named(n, "light", scene.lights, [&](const Node& l, std::size_t) { return read_light(l); });
  }

  Light read_light(const Node& n) const {
    const json& v = need(n);
    if (!v.is_object()) fail(n, fmt::format("must be an object, got {}", describe(v)));
    const Node type = member(n, "type");
    const std::string kind = string(type);
    std::vector<std::string_view> allowed = {"name",     "type",   "position", "time",
                                             "velocity", "motion", "color",    "blackbody"};
    if (kind == "point") {
      allowed.insert(allowed.end(), {"intensity"});
    } else if (kind == "spot") {
      allowed.insert(allowed.end(), {"intensity", "direction", "cone", "falloff"});
    } else if (kind == "directional") {
      allowed.insert(allowed.end(), {"irradiance", "direction"});
    } else if (kind == "sphere") {
      allowed.insert(allowed.end(), {"intensity", "radius"});
    } else {
      fail(type, fmt::format("unknown light type \"{}\" (expected one of: point, spot, "
                             "directional, sphere)",
                             kind));
    }
    object(n, allowed, {}, fmt::format(" for a {} light", kind));

    Light l;
    const Node name = member(n, "name");
    l.name = string(name);
    if (l.name.empty()) fail(name, "must not be empty");
    if (Node p = member(n, "position"); p.value) l.world_line.position = vec3(p);
    if (Node t = member(n, "time"); t.value) l.world_line.time = time(t);
    if (Node vel = member(n, "velocity"); vel.value) l.world_line.velocity = velocity(vel);
    if (Node m = member(n, "motion"); m.value) {
      if (kind == "directional")
        fail(m, "a directional light is at infinity: it has a velocity but no motion");
      l.motion = body_motion(n, m, l.world_line);
    }

    const Node color_node = member(n, "color"), blackbody = member(n, "blackbody");
    if (color_node.value && blackbody.value)
      fail(n, "must have at most one of: color, blackbody (found color, blackbody)");
    if (color_node.value) l.spectrum.emission = color(color_node);
    if (blackbody.value) {
      object(blackbody, {"temperature"});
      Blackbody b;
      b.temperature_k = positive(member(blackbody, "temperature"));
      l.spectrum.emission = b;
    }
    if (Node i = member(n, "intensity"); i.value) l.intensity = non_negative(i);

    if (kind == "point") {
      l.kind = PointLight{};
    } else if (kind == "spot") {
      SpotLight s;
      if (Node d = member(n, "direction"); d.value) s.direction = direction(d);
      if (Node cone = member(n, "cone"); cone.value) {
        s.cone_degrees = number(cone);
        if (!(s.cone_degrees > 0 && s.cone_degrees < 180))
          fail(cone, fmt::format("must be between 0 and 180 degrees (both excluded), got {}",
                                 s.cone_degrees));
      }
      // The default soft edge, 5 degrees, shrinks to fit a cone narrower than 10 degrees.
      s.falloff_degrees = std::min(s.falloff_degrees, s.cone_degrees / 2);
      if (Node f = member(n, "falloff"); f.value) {
        s.falloff_degrees = number(f);
        if (!(s.falloff_degrees >= 0 && s.falloff_degrees <= s.cone_degrees / 2))
          fail(f, fmt::format("must be from 0 to half the cone ({} degrees), got {}",
                              s.cone_degrees / 2, s.falloff_degrees));
      }
      l.kind = s;
    } else if (kind == "directional") {
      DirectionalLight d;
      if (Node dir = member(n, "direction"); dir.value) d.direction = direction(dir);
      if (Node e = member(n, "irradiance"); e.value) d.irradiance = non_negative(e);
      l.kind = d;
    } else {
      l.kind = SphereLight{positive(member(n, "radius"))};
    }
    return l;
  }

  EmissionSpectrum emission_spectrum(const Node& n) const {
    object(n, {"wavelengths", "values"});
    const Node wavelengths = member(n, "wavelengths"), values = member(n, "values");
    auto list = [&](const Node& list_node) {
      const json& v = need(list_node);
      if (!v.is_array() || v.size() < 2)
        fail(list_node, fmt::format("must be an array of at least 2 numbers, got {}", describe(v)));
      std::vector<double> out;
      for (std::size_t i = 0; i < v.size(); ++i) out.push_back(number(element(list_node, i)));
      return out;
    };
    EmissionSpectrum s{list(wavelengths), list(values)};
    if (s.values.size() != s.wavelengths_nm.size())
      fail(values, fmt::format("must have as many entries as wavelengths ({}), got {}",
                               s.wavelengths_nm.size(), s.values.size()));
    for (std::size_t i = 0; i < s.wavelengths_nm.size(); ++i) {
      if (!(s.wavelengths_nm[i] > 0))
        fail(element(wavelengths, i),
             fmt::format("wavelengths must be greater than 0 nm, got {}", s.wavelengths_nm[i]));
      if (i > 0 && !(s.wavelengths_nm[i] > s.wavelengths_nm[i - 1]))
        fail(element(wavelengths, i),
             fmt::format("wavelengths must be strictly increasing ({} after {})",
                         s.wavelengths_nm[i], s.wavelengths_nm[i - 1]));
      if (s.values[i] < 0)
        fail(element(values, i), fmt::format("must be >= 0, got {}", s.values[i]));
    }
    return s;
  }

  Sky sky(const Node& n) {
    const std::string_view kind = one_of(n, {"color", "image", "grid"}, {"velocity", "rotation"});
    Sky s;
    const Node body = member(n, kind);
    if (kind == "color") {
      s.pattern = SolidColor{color(body)};
    } else if (kind == "image") {
      assets_.push_back({Asset::kSkyImage, 0, file_path(body), body.path()});
      s.pattern = SkyImage{};
    } else {
      object(body, {"spacing", "line_width", "color", "background"});
      SkyGrid grid;
      if (Node spacing = member(body, "spacing"); spacing.value) {
        grid.spacing_degrees = number(spacing);
        if (!(grid.spacing_degrees > 0 && grid.spacing_degrees <= 90))
          fail(spacing, fmt::format("must be greater than 0 and at most 90 degrees, got {}",
                                    grid.spacing_degrees));
      }
      if (Node w = member(body, "line_width"); w.value) grid.line_width_degrees = positive(w);
      if (Node c = member(body, "color"); c.value) grid.line_color = color(c);
      if (Node b = member(body, "background"); b.value) grid.background = color(b);
      s.pattern = grid;
    }
    if (Node v = member(n, "velocity"); v.value) s.velocity = velocity(v);
    if (Node r = member(n, "rotation"); r.value) s.rotation = rotation(r);
    return s;
  }

  RenderSettings render(const Node& n) const {
    object(n, {"relativity", "light_delay", "exposure", "doppler", "searchlight", "hue", "tonemap",
               "light_source_delay", "shadows"});
    RenderSettings r;
    if (Node v = member(n, "relativity"); v.value) r.relativity = boolean(v);
    if (Node v = member(n, "light_delay"); v.value) r.light_delay = boolean(v);
    if (Node v = member(n, "exposure"); v.value) {
      if (v.value->is_string()) {
        if (string(v) != "auto") fail(v, "must be a number (EV) or \"auto\"");
        r.auto_exposure = true;
      } else {
        r.exposure = number(v);
      }
    }
    if (Node v = member(n, "doppler"); v.value)
      r.doppler = choice<DopplerModel>(v, {{"spectral", DopplerModel::kSpectral},
                                           {"rgb3", DopplerModel::kRgb3},
                                           {"hue", DopplerModel::kHue},
                                           {"off", DopplerModel::kOff}});
    if (Node v = member(n, "searchlight"); v.value)
      r.searchlight = choice<SearchlightModel>(v, {{"physical", SearchlightModel::kPhysical},
                                                   {"chang1996", SearchlightModel::kChang1996},
                                                   {"off", SearchlightModel::kOff}});
    if (Node hue = member(n, "hue"); hue.value) {
      object(hue, {"loop"});
      if (Node loop = member(hue, "loop"); loop.value) r.hue_loop = boolean(loop);
    }
    if (Node v = member(n, "tonemap"); v.value)
      r.tonemap = choice<ToneMap>(v, {{"clamp", ToneMap::kClamp},
                                      {"reinhard", ToneMap::kReinhard},
                                      {"filmic", ToneMap::kFilmic}});
    if (Node v = member(n, "light_source_delay"); v.value)
      r.light_source_delay = choice<LightSourceDelay>(v,
                                                      {{"surface", LightSourceDelay::kSurface},
                                                       {"camera", LightSourceDelay::kCamera},
                                                       {"none", LightSourceDelay::kNone}},
                                                      "mode");
    if (Node v = member(n, "shadows"); v.value) r.shadows = boolean(v);
    return r;
  }

  // --- Files ------------------------------------------------------------------------------

  // Meshes and images are cached by canonical path, so objects naming one file through
  // different relative paths still share one copy.
  static fs::path cache_key(const fs::path& file) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(file, ec);
    return ec ? file.lexically_normal() : key;
  }

  // The loaders' own InputError names the file; prefix where the scene names it. Other errors
  // from the decoding libraries are about the file too; running out of memory is not.
  template <class Load>
  auto load(const Asset& a, Load&& load_file) const {
    try {
      return load_file();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      fail_at(a.path, lines_.value_line(a.path), e.what());
    }
  }

  void load_assets(Scene& scene) {
    std::map<fs::path, std::shared_ptr<const Mesh>> meshes;
    std::map<fs::path, std::shared_ptr<const Image>> images;
    for (const Asset& a : assets_) {
      const fs::path key = cache_key(a.file);
      if (a.kind == Asset::kMesh) {
        auto& mesh = meshes[key];
        if (!mesh) {
          MeshLoadReport mesh_report;
          mesh = load(a, [&] { return load_mesh_file(a.file, mesh_report, options_.mesh); });
          if (mesh_report.degenerate_triangles_dropped > 0)
            report_.warnings.push_back(fmt::format("{}: {} degenerate triangles dropped",
                                                   a.file.string(),
                                                   mesh_report.degenerate_triangles_dropped));
        }
        std::get<MeshShape>(scene.objects[a.object].shape).mesh = mesh;
        continue;
      }
      auto& image = images[key];
      if (!image) image = load(a, [&] { return load_image_file(a.file); });
      if (a.kind == Asset::kTexture) {
        Material& material = scene.objects[a.object].material;
        if (!material.unlit) check_albedo(a, *image);
        std::get<Texture>(material.pattern).image = image;
      } else {
        std::get<SkyImage>(scene.sky.pattern).image = image;
      }
    }
  }

  // A spinning body's rim moves at rate times its radius about the origin (which needs the
  // meshes loaded): below the speed of light, and its fastest point, with the body's own motion
  // added (relativistic velocity addition), within the one limit in W and relative to the camera.
  void check_spins(const Scene& scene) const {
    for (const auto& [index, path] : spins_) {
      const Object& o = scene.objects[index];
      const double r = origin_radius(o.shape, o.scale), rim = std::abs(o.spin->rate) * r;
      if (!(rim < 1))
        fail_at(path, lines_.value_line(path),
                fmt::format("the rim speed {:.4g} (rate times the shape's radius {:.4g} about "
                            "the origin) must be below the speed of light ({})",
                            rim * c_, r, c_));
      for (const Observer& observer : observers_) {
        const double gamma = rim_point_gamma(o, rim, observer.four_velocity);
        if (!(gamma <= kMaxGamma))
          fail_at(path, lines_.value_line(path),
                  fmt::format("the speed of the rim's fastest point (the rim speed {} added "
                              "to the body's motion){} is too close to the speed of light "
                              "(gamma {:.3g}; at most {:g})",
                              rim * c_, observer.relative, gamma, kMaxGamma));
      }
    }
  }

  // A lit material's texture is an albedo: every value in [0, 1] (PNG and JPEG always are; an
  // EXR need not be).
  void check_albedo(const Asset& a, const Image& image) const {
    const auto [lo, hi] = std::minmax_element(image.rgb.begin(), image.rgb.end());
    if (lo != image.rgb.end() && (*lo < 0 || *hi > 1))
      fail_at(a.path, lines_.value_line(a.path),
              fmt::format("{}: the texture of a lit material is an albedo and must have values "
                          "from 0 to 1, found {} to {}",
                          a.file.string(), *lo, *hi));
  }

  std::vector<std::pair<std::size_t, std::string>> spins_;  // spinning objects, path of rate
  SceneLoadReport& report_;
  const SceneLoadOptions options_;
  std::vector<Asset> assets_;
};

}  // namespace
}  // namespace lightcone::scene_io

namespace lightcone {

Scene load_scene_file(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                      SceneLoadReport& report, const SceneLoadOptions& options) {
  std::string text = read_scene_text(file);
  const DocumentArena arena;  // for the document, which is gone when the scene is returned
  bool repeated_key = false;
  SceneJson document = parse_scene_document(file, text, repeated_key);
  const JsonLineMap lines(std::move(text));
  if (repeated_key && !lines.duplicate_keys().empty()) {
    const auto& d = lines.duplicate_keys().front();
    throw InputError(fmt::format("{}:{}: {}: duplicate key (each key may appear only once)",
                                 file.string(), d.line, d.path));
  }

  std::vector<std::string> overridden;
  for (const std::string& o : overrides) overridden.push_back(apply_scene_override(document, o));
  return scene_io::SceneReader(file, lines, std::move(overridden), report, options).read(document);
}

}  // namespace lightcone
