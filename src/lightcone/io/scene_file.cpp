#include "lightcone/io/scene_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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
#include "lightcone/io/scene_reader.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone::scene_io {
namespace {

namespace fs = std::filesystem;

}  // namespace

Scene SceneReader::read(const json& document) {
  const Node root{&document};
  object(root, {"$schema", "speed_of_light", "camera", "objects", "lights", "sky", "render",
                "black_hole"});
  if (Node schema = member(root, "$schema"); schema.value) string(schema);
  // Every speed, time and acceleration in the file is in the scene's units; the engine's are
  // those where c = 1: times become c t, speeds v / c, accelerations a / c^2.
  if (Node c = member(root, "speed_of_light"); c.value) {
    c_ = positive(c);
    if (!std::isfinite(c_)) fail(c, "must be finite");
  }
  Scene scene;
  scene.speed_of_light = c_;
  // The hole first: the camera, objects and lights are checked against it.
  if (Node hole = member(root, "black_hole"); hole.value) hole_ = black_hole(hole);
  scene.black_hole = hole_;
  scene.camera = camera(member(root, "camera"));
  observation_ = scene.camera.world_line;
  add_camera_observers(scene.camera);
  if (Node objects = member(root, "objects"); objects.value) {
    read_objects(objects, scene);
    if (camera_inside_horizon(scene.camera.motion) && !scene.objects.empty())
      fail(objects,
           fmt::format("objects seen from inside the black hole's horizon are not drawn yet (the "
                       "falling camera is at r = {:.6g} there, inside r = 2M = {}); this version "
                       "draws the sky and the disk from there",
                       // In units of M: the scene units' square underflows for a tiny hole.
                       hole_->mass * length((scene.camera.world_line.position - hole_->position) /
                                            hole_->mass),
                       2 * hole_->mass));
  }
  if (Node lights = member(root, "lights"); lights.value) read_lights(lights, scene);
  if (Node sky_node = member(root, "sky"); sky_node.value) scene.sky = sky(sky_node);
  Node render_node = member(root, "render");
  scene.render = render_node.value ? render(render_node) : file_render_defaults();
  load_assets(scene);
  check_spins(scene);
  check_texture_coordinates(scene);
  return scene;
}

Camera SceneReader::camera(const Node& n) const {
  object(n, {"position", "time", "velocity", "proper_time", "motion", "shutter", "forward", "up",
             "fov", "width", "height", "samples"});
  if (hole_) check_camera_near_hole(n);
  Camera c;
  const Node motion_node = member(n, "motion");
  if (geodesic_motion(motion_node)) {
    // An orbit or a fall near the hole: it says where and when the camera is.
    c.motion.geodesic = geodesic(n, motion_node, "camera");
  } else {
    // Keyframes say where the camera is; otherwise its position is required.
    const bool keyframed = motion_node.value && motion_node.value->is_object() &&
                           motion_node.value->contains("keyframes");
    if (!keyframed || member(n, "position").value)
      c.world_line.position = vec3(member(n, "position"));
    if (Node t = member(n, "time"); t.value) c.world_line.time = time(t);
    if (Node v = member(n, "velocity"); v.value) c.world_line.velocity = velocity(v);
    c.motion.start = c.world_line;
    if (motion_node.value) {
      const BodyMotion moves = body_motion(n, motion_node, c.motion.start);
      c.motion.phases = moves.phases;
      c.motion.keyframes = moves.keyframes;
    }
  }
  if (Node tau = member(n, "proper_time"); tau.value) c.motion.proper_time = time(tau);
  if (const auto why = geodesic_camera_refused(c.motion, c_))
    fail(member(n, "proper_time").value ? member(n, "proper_time") : motion_node, *why);
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
      fail(fov,
           fmt::format("must be between 0 and 180 degrees (both excluded), got {}", c.fov_degrees));
  }
  const Node width = member(n, "width"), height = member(n, "height");
  if (width.value) c.width = integer(width, 1, kMaxCameraSide);
  if (height.value) c.height = integer(height, 1, kMaxCameraSide);
  if (std::int64_t{c.width} * c.height > kMaxCameraPixels)
    fail(width, fmt::format("{} x {} pixels is more than the limit of {} (2^27)", c.width, c.height,
                            kMaxCameraPixels));
  if (Node s = member(n, "samples"); s.value) c.samples = integer(s, 1, kMaxCameraSamples);
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

void SceneReader::add_camera_observers(const Camera& c) {
  if (hole_) return;
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

BodyMotion SceneReader::motion(const Node& n) const {
  BodyMotion m;
  if (one_of(n, {"phases", "keyframes"}) == "phases") {
    m.phases = phases(n);
  } else {
    m.keyframes = keyframes(member(n, "keyframes"));
  }
  return m;
}

std::vector<Keyframe> SceneReader::keyframes(const Node& list) const {
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

std::vector<AccelerationPhase> SceneReader::phases(const Node& n) const {
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

BodyMotion SceneReader::body_motion(const Node& n, const Node& m, WorldLine& start) const {
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

template <class T, class Read>
void SceneReader::read_named(const Node& n, std::string_view noun, std::vector<T>& out, Read read) {
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

void SceneReader::read_objects(const Node& n, Scene& scene) {
  read_named(n, "object", scene.objects,
             [&](const Node& o, std::size_t i) { return read_object(o, i); });
}

void SceneReader::read_lights(const Node& n, Scene& scene) {
  read_named(n, "light", scene.lights, [&](const Node& l, std::size_t) { return read_light(l); });
}

Object SceneReader::read_object(const Node& n, std::size_t index) {
  object(n, {"name", "shape", "position", "time", "seen_at", "velocity", "motion", "spin",
             "rotation", "scale", "material"});
  Object o;
  const Node name = member(n, "name");
  o.name = string(name);
  if (o.name.empty()) fail(name, "must not be empty");
  o.shape = shape(member(n, "shape"), index);
  if (Node p = member(n, "position"); p.value) o.world_line.position = vec3(p);
  if (Node t = member(n, "time"); t.value) o.world_line.time = time(t);
  if (Node v = member(n, "velocity"); v.value) o.world_line.velocity = velocity(v);
  const Node motion_node = member(n, "motion");
  const Node seen = member(n, "seen_at");
  if (seen.value && hole_ && geodesic_motion(motion_node))
    fail(seen,
         "a geodesic motion (\"orbit\" or \"fall\") says where the object is: near a "
         "black hole \"seen_at\" places a body at rest or on a straight coordinate line");
  if (geodesic_motion(motion_node)) {
    o.motion.geodesic = geodesic(n, motion_node, "object");
  } else if (motion_node.value) {
    if (hole_) refuse_near_hole(motion_node, "motion (phases or keyframes) of an object");
    o.motion = body_motion(n, motion_node, o.world_line);
  }
  if (seen.value) {
    for (const char* key : {"position", "time"})
      if (member(n, key).value)
        fail(seen, fmt::format("replaces \"position\" and \"time\": give \"{}\" or \"seen_at\", "
                               "not both",
                               key));
    if (!hole_)
      place_where_seen(o.world_line, o.motion, observation_, vec3(seen));
    else if (const auto why =
                 place_where_seen_near_hole(o.world_line, observation_, *hole_, vec3(seen)))
      fail(seen, *why);
  }
  if (hole_ && !o.motion.geodesic) check_line_near_hole(n, o.world_line, "object");
  if (Node r = member(n, "rotation"); r.value) o.rotation = rotation(r);
  if (Node s = member(n, "scale"); s.value) {
    if (s.value->is_number()) {
      const double k = positive(s);
      o.scale = {k, k, k};
    } else {
      o.scale = positive_vec3(s);
    }
  }
  if (o.motion.geodesic) geodesic_object(motion_node, o);
  if (Node m = member(n, "material"); m.value) o.material = material(m, index);
  if (Node sp = member(n, "spin"); sp.value) {
    if (hole_) refuse_near_hole(sp, "spin");
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

Shape SceneReader::shape(const Node& n, std::size_t index) {
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

RenderSettings SceneReader::render(const Node& n) const {
  object(n, {"relativity", "light_delay", "exposure", "doppler", "searchlight", "hue", "tonemap",
             "light_source_delay", "shadows"});
  RenderSettings r = file_render_defaults();
  if (Node v = member(n, "relativity"); v.value) r.relativity = boolean(v);
  if (Node v = member(n, "light_delay"); v.value) r.light_delay = boolean(v);
  if (Node v = member(n, "exposure"); v.value) {
    if (v.value->is_string()) {
      if (string(v) != "auto") fail(v, "must be a number (EV) or \"auto\"");
      r.auto_exposure = true;
    } else {
      r.exposure = number(v);
      r.auto_exposure = false;
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

namespace {

// Meshes and images are cached by canonical path, so objects naming one file through
// different relative paths still share one copy.
fs::path cache_key(const fs::path& file) {
  std::error_code ec;
  fs::path key = fs::weakly_canonical(file, ec);
  return ec ? file.lexically_normal() : key;
}

}  // namespace

template <class Load>
auto SceneReader::load(const Asset& a, Load&& load_file) const {
  try {
    return load_file();
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    fail_at(a.path, lines_.value_line(a.path), e.what());
  }
}

void SceneReader::load_assets(Scene& scene) {
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
    if (a.kind == Asset::kStars) {
      SkyStars& stars = *scene.sky.stars;
      auto kept = std::make_shared<std::vector<CatalogueStar>>(
          load(a, [&] { return read_star_catalogue(a.file); }));
      std::erase_if(*kept,
                    [&](const CatalogueStar& s) { return !(s.magnitude < stars.magnitude_limit); });
      stars.stars = std::move(kept);
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

void SceneReader::check_texture_coordinates(const Scene& scene) const {
  for (const auto& pattern : uv_patterns_) {
    // (Named: the browser build's clang 14 cannot capture a structured binding.)
    const std::size_t index = pattern.first;
    const std::string& path = pattern.second;
    const auto* mesh = std::get_if<MeshShape>(&scene.objects[index].shape);
    if (!mesh || !mesh->mesh->uvs.empty()) continue;
    const auto file = std::find_if(assets_.begin(), assets_.end(), [&](const Asset& a) {
      return a.kind == Asset::kMesh && a.object == index;
    });
    fail_at(path, lines_.value_line(path),
            fmt::format("needs the texture coordinates of the mesh, and {} has none",
                        file == assets_.end() ? std::string("the mesh")
                                              : fmt::format("\"{}\"", file->file.string())));
  }
}

void SceneReader::check_spins(const Scene& scene) const {
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
      if (!(gamma <= kMaxLorentzFactor))
        fail_at(path, lines_.value_line(path),
                fmt::format("the speed of the rim's fastest point (the rim speed {} added "
                            "to the body's motion){} is too close to the speed of light "
                            "(gamma {:.3g}; at most {:g})",
                            rim * c_, observer.relative, gamma, kMaxLorentzFactor));
    }
  }
}

void SceneReader::check_albedo(const Asset& a, const Image& image) const {
  const auto [lo, hi] = std::minmax_element(image.rgb.begin(), image.rgb.end());
  if (lo != image.rgb.end() && (*lo < 0 || *hi > 1))
    fail_at(a.path, lines_.value_line(a.path),
            fmt::format("{}: the texture of a lit material is an albedo and must have values "
                        "from 0 to 1, found {} to {}",
                        a.file.string(), *lo, *hi));
}

}  // namespace lightcone::scene_io

namespace lightcone {

RenderSettings file_render_defaults() {
  RenderSettings r;
  r.auto_exposure = true;
  r.tonemap = ToneMap::kFilmic;
  return r;
}

Scene load_scene_file(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                      SceneLoadReport& report, const SceneLoadOptions& options) {
  return load_scene_text(read_scene_text(file), file, overrides, report, options);
}

Scene load_scene_text(std::string text, const std::filesystem::path& file,
                      const std::vector<std::string>& overrides, SceneLoadReport& report,
                      const SceneLoadOptions& options) {
  const DocumentArena arena;  // for the document, which is gone when the scene is returned
  bool repeated_key = false;
  SceneJson document = parse_scene_document(file, text, repeated_key, options.line_numbers);
  const JsonLineMap lines(std::move(text));
  if (repeated_key && !lines.duplicate_keys().empty()) {
    const auto& d = lines.duplicate_keys().front();
    const std::string where =
        options.line_numbers ? fmt::format("{}:{}", file.string(), d.line) : file.string();
    throw InputError(
        fmt::format("{}: {}: duplicate key (each key may appear only once)", where, d.path));
  }

  std::vector<std::string> overridden;
  for (const std::string& o : overrides) overridden.push_back(apply_scene_override(document, o));
  Scene scene =
      scene_io::SceneReader(file, lines, std::move(overridden), report, options).read(document);
  scene.source = file.string();
  return scene;
}

}  // namespace lightcone
