// Camera rays near a black hole: frame/curved_ray.cpp's follow_curved_ray, step for step, with
// the exact kernel's answers read from the frame's tables (raster/hole_tables.cpp, whose C++
// lookups these mirror; docs/design/black-hole.md, "The raster renderer").

uniform sampler2D hole_rays;         // HoleRayTables::texels (RGBA)
uniform sampler2D hole_temperature;  // row 0: HoleRayTables::temperature (R), tau^2 against
                                     // ln r; row 1: inner_angle
// From inside the horizon (HoleRayTables, "From inside the horizon"): 1, the falling camera's
// (E, u^r, r0, b_c), and the number of inner_angle's nodes; the tables are then R's, and
// hole_camera_radius and hole_camera_lapse R's too.
uniform int hole_inside;
uniform vec4 hole_falling;
uniform int hole_inner_nodes;
uniform mat4 hole_trace_to_static;   // F to the static observer's frame, on (t, x, y, z)
uniform mat4 hole_world_to_sky;      // W far away to the sky's rest frame
uniform mat3 hole_to_pattern;        // the sky's rest frame to its pattern coordinates
uniform vec3 hole_outward;           // e1, from the hole to the camera
uniform float hole_camera_lapse;     // sqrt(1 - 2M / r0)
uniform float hole_camera_radius;    // r0
uniform float hole_mass;
uniform float hole_critical_alpha;
uniform vec2 hole_side_width;
uniform vec2 hole_x_first;
uniform vec2 hole_x_step;
uniform int hole_rows;   // per side
uniform int hole_nodes;  // per leg; 0 without a disk
uniform float hole_stop_radius;
uniform vec3 disk_normal;
uniform vec2 disk_radii;             // inner, outer
uniform vec2 disk_temperature_grid;  // ln r of the first node, the step

const float kHolePi = 3.141592653589793;
const int kHoleSky = 0;
const int kHoleDisk = 1;
const int kHoleHorizon = 2;

// raster/hole_tables.cpp, hole_row_position: (side, fractional row).
vec2 hole_row_position(float sin_alpha, float cos_alpha) {
  float alpha = atan(sin_alpha, cos_alpha);
  float beta = atan(sin_alpha, -cos_alpha);
  float side;
  float delta;
  if (hole_critical_alpha > 0.5 * kHolePi) {
    side = beta > hole_side_width.y ? 0.0 : 1.0;
    delta = abs(beta - hole_side_width.y);
  } else {
    side = alpha < hole_critical_alpha ? 0.0 : 1.0;
    delta = abs(alpha - hole_critical_alpha);
  }
  float far_end = side == 0.0 ? alpha : beta;
  float x = log(max(delta, 1e-30)) - log(far_end);
  int s = int(side);
  float p = (x - hole_x_first[s]) / hole_x_step[s];
  float last = float(hole_rows - 1);
  if (!(p < last)) p = last;
  return vec2(side, p);
}

// raster/hole_tables.cpp, hole_row_weights: rows first .. first + 3 and their weights at p, for
// the total angle (w) and for u (w_clamped: the first row's alone before it).
struct HoleRowWeights {
  int first;
  vec4 w, w_clamped;
};
HoleRowWeights hole_row_weights(float p) {
  HoleRowWeights r;
  r.first = clamp(int(floor(p)) - 1, 0, hole_rows - 4);
  float s = p - float(r.first);
  vec4 cubic = vec4(-(s - 1.0) * (s - 2.0) * (s - 3.0) / 6.0, s * (s - 2.0) * (s - 3.0) / 2.0,
                    -s * (s - 1.0) * (s - 3.0) / 2.0, s * (s - 1.0) * (s - 2.0) / 6.0);
  bool before = p <= 0.0;  // then first is 0
  r.w = before ? vec4(1.0 - p, p, 0.0, 0.0) : cubic;
  r.w_clamped = before ? vec4(1.0, 0.0, 0.0, 0.0) : cubic;
  return r;
}

vec4 hole_texel(int side, int row, int column) {
  return texelFetch(hole_rays, ivec2(column, side * hole_rows + row), 0);
}

// raster/hole_tables.cpp, hermite: the leg from texel `column` (nodes in pairs), over
// [0, leg_length], at phi clamped to it.
float hole_hermite(int side, int row, int column, float leg_length, float phi) {
  float p = leg_length > 0.0 ? clamp(phi / leg_length, 0.0, 1.0) * float(hole_nodes - 1) : 0.0;
  int j = min(int(p), hole_nodes - 2);
  float s = p - float(j);
  float h = leg_length / float(hole_nodes - 1);
  vec4 a = hole_texel(side, row, column + j);
  float s2 = s * s;
  float s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * a.x + (s3 - 2.0 * s2 + s) * h * a.y +
         (3.0 * s2 - 2.0 * s3) * a.z + (s3 - s2) * h * a.w;
}

// raster/hole_tables.cpp, row_u: u = M/r on one row, whose first texel is `head` (without
// branches: the leg is read in every case, then the escaped and inside cases chosen).
float hole_row_u(int side, int row, vec4 head, float phi, float psi, bool use_out) {
  float leg_length = use_out ? head.z : head.y;
  float at = use_out ? psi : phi;
  bool whole = head.w != 0.0;
  float u = hole_hermite(side, row, use_out ? hole_nodes : 1, leg_length, at);
  bool escaped = use_out ? !(psi > 0.0) : (whole && phi > leg_length);
  bool inside = at > leg_length && !whole;
  return escaped ? 0.0 : (inside ? hole_mass / hole_stop_radius : u);
}

// The tables at one ray: its side, the weights of its rows and their first texels, and how far
// their legs reach (the crossings between need no lookup: they are inside r_stop).
struct HoleRows {
  int side;
  HoleRowWeights weights;
  vec4 head[4];
  float in_reach, out_reach;
  bool whole;
};
HoleRows hole_rows_at(float sin_alpha, float cos_alpha) {
  HoleRows r;
  vec2 at = hole_row_position(sin_alpha, cos_alpha);
  r.side = int(at.x);
  r.weights = hole_row_weights(at.y);
  for (int k = 0; k < 4; ++k) r.head[k] = hole_texel(r.side, r.weights.first + k, 0);
  r.in_reach = max(max(r.head[0].y, r.head[1].y), max(r.head[2].y, r.head[3].y));
  r.out_reach = max(max(r.head[0].z, r.head[1].z), max(r.head[2].z, r.head[3].z));
  r.whole = r.head[0].w + r.head[1].w + r.head[2].w + r.head[3].w != 0.0;
  return r;
}

// raster/hole_tables.cpp, tabulated_total_angle.
float hole_total_angle(HoleRows r) {
  return dot(r.weights.w, vec4(r.head[0].x, r.head[1].x, r.head[2].x, r.head[3].x));
}

// raster/hole_tables.cpp, tabulated_radius, given the total angle (infinity: a negative number).
float hole_radius(HoleRows r, float total, float phi) {
  bool use_out = r.side == 0 && phi > 0.5 * total;
  float u = 0.0;
  for (int k = 0; k < 4; ++k)
    u += r.weights.w_clamped[k] *
         hole_row_u(r.side, r.weights.first + k, r.head[k], phi, total - phi, use_out);
  return u > 0.0 ? hole_mass / u : -1.0;
}

// raster/hole_tables.cpp, tabulated_temperature_ratio (physics/accretion_disk.cpp,
// disk_temperature_ratio, from its table).
float hole_temperature_ratio(float r) {
  float last = float(textureSize(hole_temperature, 0).x - 1);
  float p = clamp((log(r) - disk_temperature_grid.x) / disk_temperature_grid.y, 0.0, last);
  int j = min(int(p), int(last) - 1);
  float a = texelFetch(hole_temperature, ivec2(j, 0), 0).x;
  float b = texelFetch(hole_temperature, ivec2(j + 1, 0), 0).x;
  return sqrt(max(mix(a, b, p - float(j)), 0.0));
}

// physics/accretion_disk.cpp, circular_orbit_frequency_shift: g = sqrt(1 - 3M/r) / (1 - Omega
// lambda) with Omega = sqrt(M / r^3), for r > 3M.
float circular_orbit_frequency_shift(float mass, float r, float lambda) {
  float omega = sqrt(mass / r) / r;
  return sqrt(1.0 - 3.0 * mass / r) / (1.0 - omega * lambda);
}

// frame/curved_ray.cpp, any_perpendicular.
vec3 hole_any_perpendicular(vec3 n) {
  vec3 other = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  return normalize(cross(n, other));
}

// raster/hole_tables.cpp, tabulated_inner_angle.
float hole_inner_angle(float impact) {
  float p = clamp(impact / hole_falling.w * float(hole_inner_nodes - 1), 0.0,
                  float(hole_inner_nodes - 1));
  int j = min(int(p), hole_inner_nodes - 2);
  float a = texelFetch(hole_temperature, ivec2(j, 1), 0).x;
  float b = texelFetch(hole_temperature, ivec2(j + 1, 1), 0).x;
  return mix(a, b, p - float(j));
}

// frame/curved_ray.hpp, CurvedRay: the sky direction and the shift are set for every end (the
// sky's where the ray does not reach it), so that a pass can read the sky everywhere.
struct HoleRay {
  int end;
  int order;
  float phi;
  float shift;
  vec3 sky_direction;
  float disk_radius;
};

// frame/curved_ray.cpp, follow_curved_ray.
HoleRay follow_hole_ray(vec3 u) {
  HoleRay ray;
  ray.disk_radius = 0.0;
  vec3 e1 = hole_outward;
  float cos_alpha, sin_alpha, camera_energy;
  vec3 e2;
  float swept = 0.0;  // from inside the horizon: the angle swept below R
  if (hole_inside == 1) {
    // physics/radial_observer.cpp, observed_ray, in the falling camera's own frame (radial axis
    // e1, the others W's); light of no positive energy, and rays beyond b_c, are dark.
    float cos_look = dot(u, e1);
    vec3 across = u - e1 * cos_look;
    float sin_look = length(across);
    e2 = sin_look > 0.0 ? across / sin_look : hole_any_perpendicular(e1);
    float per_energy = hole_falling.x - hole_falling.y * cos_look;
    float impact = hole_falling.z * sin_look / max(per_energy, 1e-30);
    if (!(per_energy > 0.0) || !(impact < hole_falling.w)) {
      ray.end = kHoleHorizon;
      ray.order = 0;
      ray.phi = 0.0;
      ray.shift = 0.0;
      ray.sky_direction = vec3(0.0, 0.0, 1.0);
      return ray;
    }
    camera_energy = 1.0 / per_energy;
    swept = hole_inner_angle(impact);
    // On at R, looking outward from there; the ray's plane turned by the angle swept.
    sin_alpha = impact * hole_camera_lapse / hole_camera_radius;
    cos_alpha = sqrt(max(1.0 - sin_alpha * sin_alpha, 0.0));
    vec3 r1 = e1 * cos(swept) + e2 * sin(swept);
    e2 = e2 * cos(swept) - e1 * sin(swept);
    e1 = r1;
  } else {
    vec4 back = hole_trace_to_static * vec4(-1.0, u);
    vec3 d = back.yzw / -back.x;
    camera_energy = 1.0 / (hole_camera_lapse * -back.x);
    cos_alpha = dot(d, e1);
    vec3 tangential = d - e1 * cos_alpha;
    sin_alpha = length(tangential);
    e2 = sin_alpha > 0.0 ? tangential / sin_alpha : hole_any_perpendicular(e1);
  }
  HoleRows rows = hole_rows_at(sin_alpha, cos_alpha);
  float total = hole_total_angle(rows);

  ray.end = rows.side == 0 ? kHoleSky : kHoleHorizon;
  ray.phi = swept + total;
  ray.order = ray.phi > 0.0 ? int(ceil(ray.phi / kHolePi)) - 1 : 0;
  vec3 far_direction = e1 * cos(total) + e2 * sin(total);
  vec4 in_sky = hole_world_to_sky * vec4(-1.0, far_direction);
  ray.sky_direction = hole_to_pattern * (in_sky.yzw / -in_sky.x);
  ray.shift = camera_energy / -in_sky.x;
  if (hole_nodes == 0) return ray;
  float a = dot(e1, disk_normal);
  float c = dot(e2, disk_normal);
  if (a == 0.0 && c == 0.0) return ray;
  float phi = atan(-a, c);
  if (phi <= 0.0) phi += kHolePi;
  // The crossings the in-legs serve, then those the out-legs serve; any between lie inside
  // r_stop on every row (tabulated_radius would give r_stop there) and are passed over.
  float in_end = rows.side == 0 ? 0.5 * total : total;
  float out_start = rows.side == 0 ? 0.5 * total : total;
  if (!rows.whole) {
    in_end = min(in_end, rows.in_reach);
    out_start = max(out_start, total - rows.out_reach);
  }
  for (int k = 0; k < 64 && phi < total; ++k, phi += kHolePi) {
    if (phi > in_end && phi < out_start) {
      float skipped = ceil((out_start - phi) / kHolePi);
      k += int(skipped);
      phi += skipped * kHolePi;
      if (!(phi < total) || k >= 64) break;
    }
    float r = hole_radius(rows, total, phi);
    if (r < disk_radii.x || r > disk_radii.y) continue;  // also infinity (negative)
    float impact = hole_camera_radius * sin_alpha / hole_camera_lapse;
    float lambda = -impact * dot(cross(e1, e2), disk_normal);
    ray.end = kHoleDisk;
    ray.order = k;
    ray.phi = swept + phi;
    ray.disk_radius = r;
    ray.shift = camera_energy * circular_orbit_frequency_shift(hole_mass, r, lambda);
    return ray;
  }
  return ray;
}

#ifdef LIGHTCONE_FRAGMENT_STAGE
// The disk's colour: frame/received_colour.cpp, received_thermal_colour, with the hottest ring's
// colour read from row disk_row against ln s: s = tau g for the spectral model
// (LIGHTCONE_SPECTRAL_DISK), tau for the others, which then receive it with g as any colour at
// rest (received_rgb). One program each: on a software rasteriser the branch not taken still
// costs a fifth of the pass.
uniform int disk_row;
uniform float disk_floor;
uniform int disk_searchlight;  // spectral_searchlight's model

vec3 disk_colour(float r, float g) {
  float tau = hole_temperature_ratio(r);
  float tau5 = tau * tau * tau * tau * tau;
#if defined(LIGHTCONE_SPECTRAL_DISK)
  float s = tau * g;
  if (!(s >= disk_floor)) return vec3(0.0);
  return tau5 * spectral_searchlight(g, disk_searchlight) * received_colour(disk_row, s);
#else
  if (!(tau >= disk_floor)) return vec3(0.0);
  return received_rgb(tau5 * received_colour(disk_row, tau), g);
#endif
}
#endif
