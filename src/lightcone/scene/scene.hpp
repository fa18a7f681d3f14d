// The true-state scene: bodies with inertial world-lines in the world frame W, their rest-frame
// geometry and materials, the camera and the sky. Knows nothing of file formats or renderers.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "lightcone/physics/hole_world_line.hpp"
#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/radial_observer.hpp"
#include "lightcone/physics/vec.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone {

// Linear RGB (Rec. 709 primaries), radiance in the emitter's rest frame.
struct Rgb {
  float r = 0, g = 0, b = 0;
};

// Inertial world-line in W: X(t) = position + velocity (t - time); |velocity| < 1 (c = 1).
struct WorldLine {
  double time = 0;
  Vec3 position;
  Vec3 velocity;
  double proper_time = 0;  // the body's own clock at the event (time, position)

  Vec3 position_at(double t) const { return position + velocity * (t - time); }
};

// Triangle mesh in its own coordinates. Shared (stored once) by every object that uses it.
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Per vertex, empty when the file has none; (0, 0) is the top-left of the image (glTF's
  // convention; OBJ and PLY v is flipped on loading).
  std::vector<std::array<float, 2>> uvs;
  std::string source;  // file it came from, for messages
};

// A named channel of one float per pixel (an output variable beside the colour: the Doppler
// factor, a depth), row-major like the image it belongs to.
struct NamedChannel {
  std::string name;
  std::vector<float> values;
};

// A linear-RGB image, row-major from the top-left, 3 floats per pixel, and any extra channels.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;
  std::string source;
  std::vector<NamedChannel> channels;
  // The EV a render multiplied the radiance by (the pixels are radiance times 2^exposure), kept
  // in an EXR's header; nullopt where unknown (an image not rendered here, a PNG).
  std::optional<double> exposure;

  Rgb texel(int x, int y) const {
    const float* p = &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
    return {p[0], p[1], p[2]};
  }
};

struct Sphere {
  double radius = 1;
};
// Axis-aligned box centred on the origin.
struct Box {
  Vec3 size{1, 1, 1};
};
// Rectangle in y = 0 centred on the origin, size along x and z.
struct Plane {
  double size_x = 1, size_z = 1;
};
struct MeshShape {
  std::shared_ptr<const Mesh> mesh;
};
using Shape = std::variant<Sphere, Box, Plane, MeshShape>;

struct SolidColor {
  Rgb color;
};
// Colour index (floor(x/s) + floor(y/s) + floor(z/s)) mod 2 in the shape's own coordinates.
struct Checker {
  double size = 1;
  Rgb colors[2];
};
struct Texture {
  std::shared_ptr<const Image> image;
};
// Thermal emission: Planck's law at `temperature_k`, scaled so that its CIE Y at rest equals
// `luminance` (in the units where an RGB emitter (1, 1, 1) has Y = 1).
struct Blackbody {
  double temperature_k = 5762;
  double luminance = 1;
};
// Tabulated spectral radiance (per nm, normalised like RGB: a constant 1 has Y = 1),
// piecewise linear, the end values held beyond the table.
struct EmissionSpectrum {
  std::vector<double> wavelengths_nm;  // strictly increasing, > 0
  std::vector<double> values;          // >= 0
};
// Patterns that change with the body's own clock (its proper time at emission), so that a
// moving one is seen running at the rate the Doppler factor says. Both are drawn in the
// shape's texture coordinates: colors[0] is the background, colors[1] the mark.
// Lit for a fraction `duty` of every `period` (from proper time 0 on), dark otherwise.
struct Blink {
  double period = 1;
  double duty = 0.5;
  Rgb colors[2] = {{0, 0, 0}, {1, 1, 1}};  // off, on
};
// A dial filling the texture square, with a hand from its centre that starts at 12 o'clock
// (toward v = 0) and turns clockwise once every `period`.
struct Clock {
  double period = 1;
  Rgb colors[2] = {{1, 1, 1}, {0, 0, 0}};  // face, hand
};

// A glossy layer over the diffuse base: GGX microfacets with Schlick's Fresnel.
struct Glossy {
  double roughness = 0.3;  // GGX alpha = roughness^2, in (0, 1]
  double specular = 0.04;  // reflectance at normal incidence, in [0, 1]
};
using Pattern =
    std::variant<SolidColor, Checker, Texture, Blackbody, EmissionSpectrum, Blink, Clock>;
struct Material {
  Pattern pattern = SolidColor{{1, 1, 1}};
  // Unlit: the pattern is the radiance the surface emits in its rest frame. Lit: the pattern
  // (an RGB one) is the Lambertian albedo in [0, 1], lit by the scene's lights in the surface's
  // rest frame, with an optional glossy layer.
  bool unlit = true;
  std::optional<Glossy> glossy;
};

// A camera or body moving freely near the scene's black hole (docs/scene-format.md,
// "black_hole"), on a geodesic given in closed form (physics/schwarzschild_geodesics.hpp); W's time
// is Schwarzschild coordinate time there, and the camera's velocity is measured by the local static
// observer.
//
// A circular geodesic at `radius` (> 3M) in the plane of the unit vectors axis_x and axis_y
// (orthogonal), counter-clockwise about axis_x x axis_y: at coordinate time t it is at
// hole + radius (cos phi axis_x + sin phi axis_y), phi = phase + Omega t; proper time 0 at t = 0.
struct HoleOrbit {
  double radius = 0;
  Vec3 axis_x{1, 0, 0}, axis_y{0, 0, -1};
  double phase = 0;  // radians
};
// A radial free fall along the unit vector `direction` from the hole: from rest at r = `from`
// (> 2M; proper time 0 there, at coordinate time `time`), or, with `from` infinite, from rest
// at infinity, passing r = `reference` (> 2M) at proper time 0 and coordinate time `time`.
struct HoleFall {
  double from = 0;
  double reference = 0;  // from infinity only
  Vec3 direction{0, 0, 1};
  double time = 0;
};
struct HoleGeodesic {
  Vec3 hole;        // the hole's position
  double mass = 1;  // and its mass M
  std::variant<HoleOrbit, HoleFall> path;
};

// Motion beyond the inertial world-line of a body's origin (docs/design/accelerated-bodies.md):
// either phases of constant proper acceleration from the world-line's event (proper time 0)
// on, or keyframes, world positions at world times that replace the world-line (proper time 0
// at the first). Neither: inertial.
struct BodyMotion {
  std::vector<AccelerationPhase> phases;
  std::vector<Keyframe> keyframes;
  // Near a black hole, instead of the world-line, phases and keyframes: a geodesic (the
  // world-line then holds its point at coordinate time 0, for what reads one).
  std::optional<HoleGeodesic> geodesic;

  bool inertial() const { return phases.empty() && keyframes.empty(); }
};

// Rigid rotation about the object's origin in its rest frame: at the body's proper time tau its
// shape is turned by rate * tau about `axis` (unit) on top of its `rotation`. Every point has
// its own world-line; the fastest moves at rate times the shape's radius about the origin (< 1).
struct Spin {
  Vec3 axis{0, 0, 1};
  double rate = 0;  // radians per unit of the body's proper time
};

struct Object {
  std::string name;
  Shape shape;
  WorldLine world_line;  // of the object's origin
  BodyMotion motion;
  std::optional<Spin> spin;
  // In the object's rest frame (axes: W's carried by the pure boost): offset = R (S p).
  Mat3 rotation;  // spin turns the shape further, R(rate tau) rotation (scale p)
  Vec3 scale{1, 1, 1};
  Material material;
};

// Light sources, each with an inertial world-line and its emission given in its rest frame.
// Intensities are in the units of RGB radiance: a light of colour (1, 1, 1) and intensity I
// gives a surface facing it at rest, at distance r, the irradiance I / r^2 (Y = I / r^2).
struct PointLight {};
struct SpotLight {
  Vec3 direction{0, 0, -1};    // axis, in the light's rest frame
  double cone_degrees = 60;    // full opening angle, in (0, 180)
  double falloff_degrees = 5;  // width of the soft edge inside the cone, in [0, cone / 2]
};
// A source at infinity (a distant sun): parallel light along `direction` (from the source into
// the scene) with `irradiance` on a surface facing it, both in its rest frame.
struct DirectionalLight {
  Vec3 direction{0, -1, 0};
  double irradiance = 1;
};
// A sphere of uniform radiance; `intensity` is its on-axis intensity, pi R^2 L.
struct SphereLight {
  double radius = 0.1;
};
struct LightSpectrum {
  std::variant<Rgb, Blackbody> emission = Rgb{1, 1, 1};  // a blackbody's luminance is ignored
};
struct Light {
  std::string name;
  std::variant<PointLight, SpotLight, DirectionalLight, SphereLight> kind;
  WorldLine world_line;  // ignored for directional lights except for their velocity
  BodyMotion motion;     // not for directional lights
  LightSpectrum spectrum;
  double intensity = 1;  // point, spot, sphere; rest frame
};

// A camera is static or moving from outside r = 2M (1 + kCameraHorizonMargin) only; a falling one
// is drawn on through the horizon down to r = kCameraInnermostRadius M (inside the margin its
// view is found in its own frame, as everywhere on its fall; W's time is not defined there).
inline constexpr double kCameraHorizonMargin = 1e-9;
inline constexpr double kCameraInnermostRadius = 0.05;

// The largest picture a camera takes: on each side, and in all.
inline constexpr int kMaxCameraSide = 16384;
inline constexpr std::int64_t kMaxCameraPixels = std::int64_t{1} << 27;
// The most samples a pixel takes.
inline constexpr int kMaxCameraSamples = 65536;

struct Camera {
  // The observation event is (world_line.time, world_line.position), and world_line.velocity
  // the camera's velocity there: what renderers read. A camera described by `motion` has them
  // set from it (camera_observation).
  WorldLine world_line;
  // How the camera moves: at start.position at world time start.time with start.velocity (that
  // event has proper time 0), then phases of constant proper acceleration, inertial after
  // them; it observes at its own proper time `proper_time`.
  struct Motion {
    WorldLine start;
    std::vector<AccelerationPhase> phases;
    std::vector<Keyframe> keyframes;  // instead of start and phases (proper time 0 at the first)
    // Near a black hole, instead of start, phases and keyframes: a geodesic (proper time 0 as
    // HoleOrbit and HoleFall say).
    std::optional<HoleGeodesic> geodesic;
    double proper_time = 0;
  } motion;
  // In the camera's rest frame (axes: W's carried by the pure boost).
  Vec3 forward{0, 0, -1};
  Vec3 up{0, 1, 0};
  double fov_degrees = 60;  // vertical
  int width = 640, height = 360;
  int samples = 1;
  // Motion blur: the samples of each pixel are spread over the observation events from
  // proper time motion.proper_time to motion.proper_time + shutter (0: one event).
  double shutter = 0;
};

// Procedural celestial grid: lines of constant longitude and latitude in the sky's rest frame.
struct SkyGrid {
  double spacing_degrees = 15;
  double line_width_degrees = 0.4;
  Rgb line_color{1, 1, 1};
  Rgb background{0.02f, 0.02f, 0.05f};
};
struct SkyImage {
  std::shared_ptr<const Image> image;  // equirectangular
};

// A star of a catalogue: a point source far away (docs/design/stars.md).
struct CatalogueStar {
  Vec3 direction;          // unit, equatorial: the sky's pattern coordinates (physics/celestial)
  float magnitude = 0;     // V
  float colour_index = 0;  // B-V
};

// The stars drawn over the sky's pattern, in its coordinates (so moving and turning with it).
struct SkyStars {
  std::string catalogue = "bright";
  double magnitude_limit = 6.5;  // stars brighter (smaller V) than this are drawn
  double exposure = 0;           // EV on every star's flux (StarPhotometry)
  std::shared_ptr<const std::vector<CatalogueStar>> stars;  // those brighter than the limit
};

struct Sky {
  std::variant<SolidColor, SkyImage, SkyGrid> pattern = SolidColor{{0, 0, 0}};
  Vec3 velocity;  // the sky's rest frame is the pure boost of W by this velocity
  Mat3 rotation;  // orientation of the pattern in the sky's rest frame
  std::optional<SkyStars> stars;
};

// How the Doppler shift changes colour (see docs/design/colour.md).
enum class DopplerModel {
  kSpectral,  // every colour is a spectrum, read at lambda_E = D lambda_R
  kRgb3,      // seed 000: three spectral lines at 626, 534, 465 nm
  kHue,       // seed 003: hue rotated by 512 log2(D) degrees
  kOff,
};
// How radiance scales with D.
enum class SearchlightModel {
  kPhysical,   // D^5 on spectral radiance, D^4 integrated
  kChang1996,  // a single factor D on radiance (the published counter-example)
  kOff,
};
enum class ToneMap { kClamp, kReinhard, kFilmic };
// Which event of a light lights a surface (docs/design/light-transport.md).
enum class LightSourceDelay {
  kSurface,  // on the past light cone of the surface's reception event (exact, two legs)
  kCamera,   // on the camera's past light cone (seed 004's approximation)
  kNone,     // where the light is at the camera's time (teaching only)
};

struct RenderSettings {
  bool relativity = true;   // false: the classical picture
  bool light_delay = true;  // false: bodies as they are at the camera's time, in its rest frame
  double exposure = 0;      // EV, unless auto_exposure
  bool auto_exposure = false;
  DopplerModel doppler = DopplerModel::kSpectral;
  SearchlightModel searchlight = SearchlightModel::kPhysical;
  bool hue_loop = false;  // for DopplerModel::kHue: wrap the hue instead of fading
  ToneMap tonemap = ToneMap::kClamp;
  LightSourceDelay light_source_delay = LightSourceDelay::kSurface;
  bool shadows = true;
};

// A thin accretion disk in the hole's equatorial plane about `normal` (unit; the gas orbits
// counter-clockwise seen from its tip): gas on circular geodesics from `inner` (>= the ISCO,
// 6M) to `outer`, each ring a blackbody at the Novikov-Thorne / Page-Thorne temperature, whose
// profile peaks at `temperature_k` at r = 9.55M (the hottest ring, when the disk spans it).
// `luminance` is the CIE Y, at rest, of a ring at that peak temperature.
struct AccretionDisk {
  double inner = 6, outer = 20;  // Schwarzschild radii r, in the model's units (c = 1)
  Vec3 normal{0, 1, 0};
  double temperature_k = 10000;
  double luminance = 1;
};

// One Schwarzschild black hole at rest in W (docs/design/black-hole.md, PHYSICS.md "Curved
// spacetime"): W's time is then Schwarzschild coordinate time and positions are Schwarzschild r
// and angles about `position`. `mass` is the gravitational radius GM/c^2, a length (> 0).
struct BlackHole {
  Vec3 position;
  double mass = 1;
  std::optional<AccretionDisk> disk;
};

struct Scene {
  // Where it was read from ("scenes/street.json", "<dict>"), the name messages about it start
  // with; empty for a scene built in code.
  std::string source;
  // The speed of light in the scene file's units (length per unit of time). The model is in
  // units where c = 1: its times are the file's times c t, its speeds v / c.
  double speed_of_light = 1;
  Camera camera;
  std::vector<Object> objects;
  std::vector<Light> lights;
  Sky sky;
  std::optional<BlackHole> black_hole;  // none: flat spacetime
  RenderSettings render;
};

// The observation event and velocity of a camera moving as `motion` says: its point at
// motion.proper_time (throws std::invalid_argument for a motion the world-line refuses, or for
// a geodesic observation that geodesic_camera_refused refuses). On a geodesic near a black hole
// the velocity is the one the local static observer measures.
WorldLine camera_observation(const Camera::Motion& motion);

// The proper times at which a camera on `geodesic` is drawn: every one on an orbit; on a fall,
// down to r = kCameraInnermostRadius M, and from rest at r0 not before it rose out of the past
// horizon (outside 2M (1 + kCameraHorizonMargin)). The open interval (earliest, latest), either
// end infinite.
struct ProperTimeSpan {
  double earliest = 0, latest = 0;
};
ProperTimeSpan drawn_proper_times(const HoleGeodesic& geodesic);

// Why a camera on a geodesic `motion` cannot be drawn at motion.proper_time (outside
// drawn_proper_times, or so far along that its coordinate time or position is not a finite
// number), with times in the scene's units (`speed_of_light`); empty
// when it can (always, off a geodesic).
std::optional<std::string> geodesic_camera_refused(const Camera::Motion& motion,
                                                   double speed_of_light);

// Whether a camera on a radial fall is at or inside r = 2M (1 + kCameraHorizonMargin), where it
// has no static observer and W's time is not defined: its picture shows the sky and the disk,
// not objects (not drawn from there yet).
bool camera_inside_horizon(const Camera::Motion& motion);

// The camera as a radially moving observer (its energy per unit mass and dr/dtau at its
// radius), for a camera on a radial fall; none otherwise.
std::optional<RadialObserver> falling_camera(const Camera::Motion& motion);

// The camera's proper time at coordinate (world) time t on its geodesic.
double geodesic_proper_time_at(const HoleGeodesic& geodesic, double t);

// The world-line near the scene's black hole of an object's origin: its geodesic, or its
// world-line read as a straight coordinate line. Requires scene.black_hole.
HoleWorldLine hole_world_line(const Object& object, const BlackHole& hole);

// The world-line of a body whose origin starts on `start` and moves as `motion` says; null for
// an inertial one (then `start` is its world-line). Throws what the world-lines throw.
std::unique_ptr<TimelikeWorldLine> body_world_line(const WorldLine& start,
                                                   const BodyMotion& motion);

// A body placed by where it is seen (an object's "seen_at"): its world-line, start and motion,
// moved in space so that from the camera's observation event its origin is seen where a point
// at rest in W at `seen` is seen. That light left `seen` at W time observation.time - |seen -
// observation.position| (c = 1), so the moved origin passes through `seen` then; it works alike
// for inertial, accelerated and keyframed motion. Flat spacetime only.
void place_where_seen(WorldLine& start, BodyMotion& motion, const WorldLine& observation,
                      const Vec3& seen);

// The same near a black hole for a body at rest or on a straight coordinate line `start`: the
// origin's primary image (order 0) is where a point at rest at `seen` is seen, so the light left
// `seen` at observation.time - T_0, T_0 the closed-form coordinate time of flight on the exact
// ray between them (ray_between, Shapiro delay included), and the moved origin passes through
// `seen` then. Why it cannot be placed, if it cannot: `seen` or the camera at or inside the
// horizon, or no primary ray.
std::optional<std::string> place_where_seen_near_hole(WorldLine& start,
                                                      const WorldLine& observation,
                                                      const BlackHole& hole, const Vec3& seen);

// The camera's observation event and velocity `later` units of its proper time after the one
// its world_line holds: along its motion (phases or keyframes), or inertially without one.
WorldLine observation_after(const Camera& camera, double later);

// The largest distance from an object's origin of a point of its (scaled) shape.
double origin_radius(const Shape& shape, const Vec3& scale);

// The one speed limit: no body, light, spin rim or camera may have a Lorentz factor above this,
// in W or relative to the camera (double precision holds the physics up to it).
inline constexpr double kMaxLorentzFactor = 1e6;

// The Lorentz factor of the 4-velocity `u` relative to an observer of 4-velocity `observer`.
double relative_gamma(const Vec4& observer, const Vec4& u);

// The largest Lorentz factor, relative to `observer`, of a body that starts on `start` and moves
// as `motion` says, anywhere on its world-line.
double max_relative_gamma(const WorldLine& start, const BodyMotion& motion, const Vec4& observer);

// The largest Lorentz factor relative to `observer` of a point of the spinning object `o`, whose
// rim moves at `rim` (< 1) relative to its centre.
double rim_point_gamma(const Object& o, double rim, const Vec4& observer);

// The fastest thing relative to `observer` (objects, their spin rims, lights), over their whole
// world-lines: its name and Lorentz factor.
struct Fastest {
  std::string name;
  double gamma = 1;
};
Fastest fastest_relative_to(const Scene& scene, const Vec4& observer);

// The inertial world-line tangent to `line` at `point` (its event, velocity and proper time).
WorldLine tangent_line(const WorldLinePoint& point);

}  // namespace lightcone
