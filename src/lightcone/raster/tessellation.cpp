#include "lightcone/raster/tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/world_line.hpp"
#include "lightcone/raster/adaptive_split.hpp"

namespace lightcone {

BodyView body_view(const ResolvedScene& scene, const ResolvedBody& body) {
  // shape = shape_origin + time_column t + spatial x, so x = spatial^-1 (shape - shape_origin)
  // - spatial^-1 time_column t.
  const Mat3 spatial_inverse = body.spatial.inverse();
  BodyView view;
  view.shape_to_trace = spatial_inverse;
  view.shape_origin = body.shape_origin;
  view.velocity = (spatial_inverse * body.time_column) * -1.0;
  if (body.spin < 0) return view;
  const ResolvedSpin& spin = scene.spins[body.spin];
  view.spin = &spin;
  Mat4 linear;
  linear.m[0] = {body.proper_time_row.t, body.proper_time_row.x.x, body.proper_time_row.x.y,
                 body.proper_time_row.x.z};
  const Vec3 time = spin.rest_from_shape * body.time_column;
  const Mat3 space = spin.rest_from_shape * body.spatial;
  for (int i = 0; i < 3; ++i)
    linear.m[i + 1] = {time[i], space.m[i][0], space.m[i][1], space.m[i][2]};
  view.rest_of_trace = {linear,
                        {body.proper_time_origin, spin.rest_from_shape * body.shape_origin}};
  const Mat4 back = inverse(linear);
  view.trace_of_rest = {back, -1.0 * (back * view.rest_of_trace.offset)};
  if (scene.scene->render.relativity)
    view.trace_velocity_at_rest = velocity_of(linear * Vec4{1, {}});
  return view;
}

Vec3 RestMesh::midpoint(const Vec3& a, const Vec3& b) const {
  const Vec3 m = (a + b) * 0.5;
  if (sphere_radius <= 0) return m;
  const double l = length(m);
  return l > 0 ? m * (sphere_radius / l) : m;
}

namespace {

void index_edges(RestMesh& m) {
  // Vertices at one point (where a box's faces meet, a mesh's seams) are one vertex here: the
  // lowest index among them.
  std::vector<std::uint32_t> order(m.positions.size()), one(m.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto point = [&m](std::uint32_t v) {
    const Vec3& p = m.positions[v];
    return std::tie(p.x, p.y, p.z);
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tuple_cat(point(a), std::tie(a)) < std::tuple_cat(point(b), std::tie(b));
  });
  for (std::size_t k = 0; k < order.size(); ++k)
    one[order[k]] = k > 0 && point(order[k]) == point(order[k - 1]) ? one[order[k - 1]] : order[k];
  // Sorting the edges keeps this O(n log n) with no hashing; the order is irrelevant.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;  // (edge key, 3 triangle + side)
  keyed.reserve(3 * m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (std::uint32_t side = 0; side < 3; ++side) {
      const std::uint32_t a = one[m.triangles[t][side]], b = one[m.triangles[t][(side + 1) % 3]];
      keyed.emplace_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b),
                         static_cast<std::uint32_t>(3 * t + side));
    }
  std::sort(keyed.begin(), keyed.end());
  m.edges.clear();
  m.triangle_edges.assign(m.triangles.size(), {});
  // Closed and oriented: each edge met exactly twice, once from its lower vertex.
  bool closed = !keyed.empty();
  const auto from_lower = [&m, &one](std::uint32_t corner) {
    const auto& t = m.triangles[corner / 3];
    return one[t[corner % 3]] < one[t[(corner % 3 + 1) % 3]];
  };
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      m.edges.push_back({static_cast<std::uint32_t>(keyed[k].first >> 32),
                         static_cast<std::uint32_t>(keyed[k].first)});
      closed = closed && k + 1 < keyed.size() && keyed[k + 1].first == keyed[k].first &&
               (k + 2 == keyed.size() || keyed[k + 2].first != keyed[k].first) &&
               from_lower(keyed[k].second) != from_lower(keyed[k + 1].second);
    }
    m.triangle_edges[keyed[k].second / 3][keyed[k].second % 3] =
        static_cast<std::uint32_t>(m.edges.size() - 1);
  }
  double volume = 0;  // six times the enclosed volume
  for (const auto& [a, b, c] : m.triangles)
    volume += dot(m.positions[a], cross(m.positions[b], m.positions[c]));
  m.closed_outward = closed && volume > 0;
}

// An octahedron's faces: the sphere is refined from there by the edge rule.
RestMesh sphere_mesh(double radius) {
  RestMesh m;
  m.sphere_radius = radius;
  m.positions = {{radius, 0, 0},  {-radius, 0, 0}, {0, radius, 0},
                 {0, -radius, 0}, {0, 0, radius},  {0, 0, -radius}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// A rectangle given by a corner and two edge vectors, as a grid of n x n quads (long edges are
// split here so that the tessellation's maximum level suffices).
void add_grid(RestMesh& m, const Vec3& corner, const Vec3& along_u, const Vec3& along_v, int n) {
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.push_back(corner + along_u * (double(i) / n) + along_v * (double(j) / n));
  const auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

// The shape's triangles, before their edges are indexed.
RestMesh rest_triangles(const Shape& shape, int face_grid) {
  struct Visitor {
    int kFaceGrid;
    RestMesh operator()(const Sphere& s) const { return sphere_mesh(s.radius); }
    RestMesh operator()(const Box& b) const {
      RestMesh m;
      const Vec3 h = b.size * 0.5;
      const Vec3 x{b.size.x, 0, 0}, y{0, b.size.y, 0}, z{0, 0, b.size.z};
      add_grid(m, {-h.x, -h.y, -h.z}, y, x, kFaceGrid);  // z = -h
      add_grid(m, {-h.x, -h.y, h.z}, x, y, kFaceGrid);   // z = +h
      add_grid(m, {-h.x, -h.y, -h.z}, z, y, kFaceGrid);  // x = -h
      add_grid(m, {h.x, -h.y, -h.z}, y, z, kFaceGrid);   // x = +h
      add_grid(m, {-h.x, -h.y, -h.z}, x, z, kFaceGrid);  // y = -h
      add_grid(m, {-h.x, h.y, -h.z}, z, x, kFaceGrid);   // y = +h
      return m;
    }
    RestMesh operator()(const Plane& p) const {
      RestMesh m;
      add_grid(m, {-p.size_x / 2, 0, -p.size_z / 2}, {p.size_x, 0, 0}, {0, 0, p.size_z},
               4 * kFaceGrid);
      return m;
    }
    RestMesh operator()(const MeshShape& s) const {
      RestMesh m;
      m.positions = s.mesh->positions;
      m.triangles = s.mesh->triangles;
      m.uvs = s.mesh->uvs;
      return m;
    }
  };
  return std::visit(Visitor{face_grid}, shape);
}

}  // namespace

RestMesh rest_mesh(const Shape& shape, int face_grid) {
  RestMesh m = rest_triangles(shape, face_grid);
  index_edges(m);
  return m;
}

HiddenFaces hidden_faces(const RestMesh& mesh, const ResolvedBody& body) {
  if (!mesh.closed_outward || body.spin >= 0) return HiddenFaces::kNone;
  // The camera (the origin) against the capsule: within it, the body may be seen from inside.
  const Capsule& c = body.trace_capsule;
  const Vec3 along = c.to - c.from;
  const double length2 = dot(along, along);
  const double s = length2 > 0 ? std::clamp(-dot(c.from, along) / length2, 0.0, 1.0) : 0.0;
  const Vec3 nearest = c.from + along * s;
  if (dot(nearest, nearest) <= c.radius * c.radius) return HiddenFaces::kNone;
  return body.spatial.determinant() > 0 ? HiddenFaces::kBack : HiddenFaces::kFront;
}

namespace {

// The inward normals of the view's four sides and of the plane through the camera facing
// forward.
std::array<Vec3, 5> view_sides(const CameraBasis& camera) {
  const double ax = camera.tan_half_fov * camera.aspect, ay = camera.tan_half_fov;
  return {camera.forward * ax + camera.right, camera.forward * ax - camera.right,
          camera.forward * ay + camera.up, camera.forward * ay - camera.up, camera.forward};
}

}  // namespace

bool may_be_in_view(const CameraBasis& camera, const Bounds3& b) {
  for (const Vec3& inward : view_sides(camera)) {
    bool all_beyond = true;
    for (int k = 0; k < 8 && all_beyond; ++k) all_beyond = dot(corner(b, k), inward) < 0;
    if (all_beyond) return false;
  }
  return true;
}

ApparentPoint apparent_point(const ResolvedScene& scene, const BodyView& view,
                             const Vec3& shape_point) {
  if (view.spin) {
    // The point's own turning world-line, met as the ray tracer's rays meet it (locate).
    const ResolvedSpin& spin = *view.spin;
    const RotatingPointWorldLine line(spin.axis, spin.rate, spin.rest_of_shape * shape_point);
    const Vec4 camera = view.rest_of_trace.offset;
    const WorldLinePoint seen = scene.ray_time == -1
                                    ? line.retarded(camera)
                                    : simultaneous_point(line, camera, view.trace_velocity_at_rest);
    const Vec3 position = view.trace_of_rest(seen.event).x;
    return {position, project_direction(scene.camera, position)};
  }
  const RayEvent event = meet_world_line(scene.ray_time, view.world_line(shape_point));
  return {event.position, project_direction(scene.camera, event.position)};
}

double edge_error_pixels(const CameraBasis& camera, const ApparentPoint& pa,
                         const ApparentPoint& pb, const ApparentPoint& pm) {
  // An edge seen wholly beyond one side of the view (its ends and midpoint) needs no accuracy.
  for (const Vec3& inward : view_sides(camera))
    if (dot(pa.position, inward) < 0 && dot(pb.position, inward) < 0 &&
        dot(pm.position, inward) < 0)
      return 0;
  // The rasteriser interpolates linearly in clip space, which is linear in the apparent
  // positions: the edge's midpoint attributes land where the apparent chord's midpoint projects.
  const Vec3 chord_middle = (pa.position + pb.position) * 0.5;
  const auto well_in_front = [&](const Vec3& p) {
    return dot(p, camera.forward) > 1e-6 * length(p);
  };
  if (well_in_front(chord_middle) && well_in_front(pm.position)) {
    const ImagePoint drawn = project_direction(camera, chord_middle);
    const double dx = pm.image.x - drawn.x, dy = pm.image.y - drawn.y;
    return std::sqrt(dx * dx + dy * dy);  // pixel distances: no overflow for hypot to guard
  }
  // An end at or behind the camera: the rasteriser draws the great circle through the ends'
  // directions (it clips in homogeneous coordinates), so measure the midpoint's angle from
  // it, in pixels at the image centre.
  const Vec3 normal = cross(pa.position, pb.position);
  const double n = length(normal), m = length(pm.position);
  if (n == 0 || m == 0) return 0;
  const double pixels_per_radian = camera.height / (2 * camera.tan_half_fov);
  return std::abs(dot(normal, pm.position)) / (n * m) * pixels_per_radian;
}

EdgeErrorBound::EdgeErrorBound(const ResolvedScene& scene, const BodyView& view)
    : camera_(scene.camera), shape_to_trace_(view.shape_to_trace), beta_(view.velocity) {
  speed_ = length(beta_);
  direction_ = speed_ > 0 ? beta_ * (1 / speed_) : Vec3{};
  one_minus_beta2_ = 1 - dot(beta_, beta_);
  focal_ = 0.5 * camera_.height / camera_.tan_half_fov;
  delayed_ = scene.ray_time != 0 && speed_ > 0;
}

double EdgeErrorBound::pixels(const Vec3& shape_a, const ApparentPoint& a, double distance_a,
                              const Vec3& shape_b, const ApparentPoint& b,
                              double distance_b) const {
  // The points y = shape_to_trace (p - shape_origin) are seen at y - beta tau(y), where tau =
  // (N(y) - beta.y) / (1 - beta^2) with N(y) = sqrt((beta.y)^2 + (1 - beta^2) |y|^2), a norm
  // (at the apparent position P, N = |P| + beta.P). y is linear along the edge, so the apparent
  // midpoint lies `drift` = |beta| (mean tau - tau(m)) from the chord's, against beta. For a
  // norm, with s = N(a) + N(b) and t = N(a + b) >= s - N(a - b): s - t = 2 (N(a) N(b) - a.b) /
  // (s + t) <= N(a - b)^2 / (2 s - N(a - b)), twice mean N - N(m). A point drift along -beta
  // from the chord's midpoint C, at least z - drift ahead, is drawn at most focal drift
  // |beta_side - tan beta_ahead| / (z - drift) from C, tan being C's offset from the axis over z.
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const Vec3 &pa = a.position, &pb = b.position;
  const Vec3 chord_middle = (pa + pb) * 0.5;
  const double z = dot(chord_middle, camera_.forward);
  const double distance = 0.5 * (distance_a + distance_b);  // at least |C|
  const double rounding = 1e-9 * distance;                  // of the positions, in any direction
  if (!(z > 1e-3 * distance)) return kNone;
  const double over_z = 1 / z;
  const double tan_x = dot(chord_middle, camera_.right) * over_z,
               tan_y = dot(chord_middle, camera_.up) * over_z;
  double drift = 0, across = 0;  // across: the image's shift per unit of drift, times z
  if (delayed_) {
    const double ends = distance_a + dot(beta_, pa) + distance_b + dot(beta_, pb);
    const Vec3 d = shape_to_trace_ * (shape_a - shape_b);
    const double bd = dot(beta_, d);
    const double along = std::sqrt(bd * bd + one_minus_beta2_ * dot(d, d));  // N(a - b)
    if (!(2 * ends - along > 0)) return kNone;
    drift = speed_ * along * along / (2 * one_minus_beta2_ * (2 * ends - along));
    const double ahead = dot(direction_, camera_.forward);
    const double side_x = dot(direction_, camera_.right) - tan_x * ahead,
                 side_y = dot(direction_, camera_.up) - tan_y * ahead;
    across = std::sqrt(side_x * side_x + side_y * side_y);
  }
  const double nearest = z - drift - rounding;
  // (Well in front, where edge_error_pixels measures in the image.)
  if (!(nearest >= 1e-3 * (distance + drift + rounding))) return kNone;
  return focal_ * (drift * across + rounding * (1 + std::abs(tan_x) + std::abs(tan_y))) / nearest;
}

namespace {

// One vertex of the buffer (body.vert's attributes: a position and its face's plane) and, for a
// textured mesh, its face's texture map.
void append_vertex(const Vec3& position, const std::array<float, 4>& plane,
                   const std::array<float, 8>& uv_map, std::vector<float>& out,
                   std::vector<float>* uv_maps) {
  out.insert(out.end(), {static_cast<float>(position.x), static_cast<float>(position.y),
                         static_cast<float>(position.z), plane[0], plane[1], plane[2], plane[3]});
  if (uv_maps) uv_maps->insert(uv_maps->end(), uv_map.begin(), uv_map.end());
}

// Straight rays: a corner is its shape point and where it is seen (each computed once).
struct FlatSeeing {
  struct Corner {
    Vec3 p;
    ApparentPoint seen;
    double distance = 0;  // |seen.position|, for the edge bound
  };
  const ResolvedScene& scene;
  const BodyView& view;
  const TessellationLimits& limits;
  std::vector<float>& out;
  std::vector<float>* uv_maps;
  HiddenFaces hidden;
  std::array<float, 4> plane{};   // of the untessellated triangle being split
  std::array<float, 8> uv_map{};  // and its texture coordinates' map, where asked for

  Corner corner(const Vec3& p) const {
    Corner c{p, apparent_point(scene, view, p)};
    if (bound) c.distance = length(c.seen.position);
    return c;
  }
  Corner middle(const Corner&, const Corner&, const Vec3& p) const { return corner(p); }
  bool needs_split(const Corner& a, const Corner& b, const Corner& middle) const {
    return edge_error_pixels(scene.camera, a.seen, b.seen, middle.seen) > limits.max_error_pixels;
  }
  // The flat faces of a body without spin: edges shown to be drawn within the bound by their
  // ends alone are left whole without their midpoints.
  std::optional<EdgeErrorBound> bound;
  bool surely_whole(const Corner& a, const Corner& b) const {
    return bound && bound->pixels(a.p, a.seen, a.distance, b.p, b.seen, b.distance) <
                        limits.max_error_pixels * (1 - 1e-9);
  }
  void emit(const Corner& a, const Corner& b, const Corner& c) const {
    if (culled(a.seen.position, b.seen.position, c.seen.position)) return;
    for (const Corner* k : {&a, &b, &c})
      append_vertex(k->seen.position, plane, uv_map, out, uv_maps);
  }
  // Whether the rasteriser culls the triangle drawn through these apparent positions. Its
  // winding in the window is the side of its plane the camera (the origin) lies on, clipped or
  // not: counter-clockwise where det(a, b, c) < 0 (x right, y up, the camera looking along -z).
  // Only a triangle clearly turned away is left out; one nearly edge-on (a sliver the float
  // positions might turn either way) is left to the rasteriser.
  bool culled(const Vec3& a, const Vec3& b, const Vec3& c) const {
    if (hidden == HiddenFaces::kNone) return false;
    const Vec3 n = cross(b - a, c - a);
    const double det = dot(n, a), margin = 1e-6 * length(n) * length(a);
    return hidden == HiddenFaces::kBack ? det > margin : det < -margin;
  }
};

// Triangle t's plane (unit normal, offset; in shape coordinates) and, where asked for, the map of
// its texture coordinates (triangle_uv_map; zero for a mesh without them).
void face_of(const RestMesh& mesh, std::size_t t, bool with_uv_map, std::array<float, 4>& plane,
             std::array<float, 8>& uv_map) {
  const auto [i, j, k] = mesh.triangles[t];
  const Vec3 &a = mesh.positions[i], &b = mesh.positions[j], &c = mesh.positions[k];
  const Vec3 n = cross(b - a, c - a);
  const double l = length(n);
  const Vec3 unit = l > 0 ? n * (1 / l) : Vec3{0, 1, 0};
  plane = {static_cast<float>(unit.x), static_cast<float>(unit.y), static_cast<float>(unit.z),
           static_cast<float>(dot(unit, a))};
  if (with_uv_map && !mesh.uvs.empty()) {
    const std::array<double, 8> map =
        triangle_uv_map({a, b, c}, {mesh.uvs[i], mesh.uvs[j], mesh.uvs[k]});
    std::transform(map.begin(), map.end(), uv_map.begin(),
                   [](double x) { return static_cast<float>(x); });
  }
}

}  // namespace

std::array<double, 8> triangle_uv_map(const std::array<Vec3, 3>& corners,
                                      const std::array<std::array<float, 2>, 3>& uvs) {
  // Barycentric coordinates on the plane: p - a = u e1 + v e2 projected, u = gu . (p - a) and
  // v = gv . (p - a) with gu, gv the dual basis of (e1, e2) in the plane.
  const Vec3 a = corners[0], e1 = corners[1] - a, e2 = corners[2] - a;
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  const double det = d11 * d22 - d12 * d12;
  std::array<double, 8> map{};
  if (!(det > 1e-30 * d11 * d22)) return map;
  const Vec3 gu = (e1 * d22 - e2 * d12) * (1 / det), gv = (e2 * d11 - e1 * d12) * (1 / det);
  for (int k = 0; k < 2; ++k) {
    const double at_a = uvs[0][k];
    const Vec3 row = gu * (uvs[1][k] - at_a) + gv * (uvs[2][k] - at_a);
    map[4 * k] = row.x;
    map[4 * k + 1] = row.y;
    map[4 * k + 2] = row.z;
    map[4 * k + 3] = at_a - dot(row, a);
  }
  return map;
}

void rest_patches(const RestMesh& mesh, std::vector<float>& out, std::vector<float>* uv_maps) {
  std::array<float, 4> plane{};
  std::array<float, 8> uv_map{};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    face_of(mesh, t, uv_maps != nullptr, plane, uv_map);
    for (const std::uint32_t corner : mesh.triangles[t])
      append_vertex(mesh.positions[corner], plane, uv_map, out, uv_maps);
  }
}

void tessellate(const ResolvedScene& scene, const BodyView& view, const RestMesh& mesh,
                const TessellationLimits& limits, std::vector<float>& out,
                std::vector<float>* uv_maps, HiddenFaces hidden) {
  FlatSeeing seeing{scene, view, limits, out, uv_maps, hidden, {}, {}, std::nullopt};
  if (!view.spin && mesh.sphere_radius <= 0) seeing.bound.emplace(scene, view);
  using Split = AdaptiveSplit<FlatSeeing, RestMesh>;
  // Kept per thread, so that a frame like the last allocates nothing.
  thread_local std::vector<Split::Node> nodes;
  thread_local std::vector<FlatSeeing::Corner> corners;
  thread_local std::vector<Split::Edge> edges;
  const Split split(seeing, mesh, limits.max_level, nodes);
  // Each of the mesh's own vertices is seen once, whatever the number of its triangles, and each
  // of its edges decided once, whatever the number of its triangles.
  corners.clear();
  for (const Vec3& p : mesh.positions) corners.push_back(seeing.corner(p));
  edges.clear();
  for (const auto& [i, j] : mesh.edges) edges.push_back(split.decide(corners[i], corners[j], 0));
  // A triangle's side from vertex i runs along its edge, or against it (the edge's first vertex
  // is another point than i).
  const auto side = [&](std::uint32_t edge, std::uint32_t i) {
    const Split::Edge e = edges[edge];
    return mesh.positions[mesh.edges[edge][0]] == mesh.positions[i] ? e : e.flipped();
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto [i, j, k] = mesh.triangles[t];
    face_of(mesh, t, uv_maps != nullptr, seeing.plane, seeing.uv_map);
    const auto [ij, jk, ki] = mesh.triangle_edges[t];
    split.triangle(corners[i], corners[j], corners[k], side(ij, i), side(jk, j), side(ki, k));
  }
}

}  // namespace lightcone
