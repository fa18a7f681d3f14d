// A body's fragment: the sample's own ray, carried into the body's shape coordinates (where the
// body is static), meets the face the fragment belongs to (or the sphere) exactly, as the ray
// tracer's does; that surface point's rest-frame pattern colour is received with the Doppler
// factor of the exact look direction, and its light travel distance is the fragment's depth.
flat in vec4 plane;

// The body's map from a ray of look direction u to shape coordinates (frame/resolved_scene.hpp):
// shape_origin + s (ray_offset + shape_spatial u).
uniform vec3 shape_origin;
uniform vec3 ray_offset;
uniform mat3 shape_spatial;
uniform vec2 depth_range;
uniform vec3 doppler_velocity;  // the body's velocity in F (0 for the classical picture)
uniform float doppler_gamma;
uniform int colour_row;  // the row of the pattern's first colour
uniform int pattern;     // 0: one colour; 1: checker; 2: texture; 3: blink; 4: clock
uniform sampler2D texture_image;
uniform float checker_size;
// The body's own clock at the ray's event s: proper_time_origin + s (proper_time_ray +
// proper_time_row . u) (ResolvedBody::proper_time).
uniform float proper_time_origin;
uniform float proper_time_ray;
uniform vec3 proper_time_row;
uniform float pattern_period;  // blink, clock
uniform float blink_duty;
uniform int shape_kind;  // 0: mesh; 1: box; 2: plane; 3: sphere
uniform vec3 box_size;
uniform float sphere_radius;

layout(location = 0) out vec4 colour;

// frame/shading.cpp, checker_index: (floor(x/s) + floor(y/s) + floor(z/s)) mod 2.
int checker_index(vec3 p, float size) {
  vec3 cell = floor(p / size);
  return int(mod(cell.x + cell.y + cell.z, 2.0));
}

// frame/shading.cpp's period_phase, blink_index and clock_index.
float period_phase(float proper_time) {
  float cycles = proper_time / pattern_period;
  return clamp(cycles - floor(cycles), 0.0, 0.99999994);
}

int blink_index(float proper_time) {
  return period_phase(proper_time) < blink_duty ? 1 : 0;
}

int clock_index(vec2 uv, float proper_time) {
  vec2 p = vec2(uv.x - 0.5, 0.5 - uv.y);
  float r = length(p);
  if (r > 0.5) return 0;
  if (r >= 0.45) return 1;
  float angle = 6.283185307179586 * period_phase(proper_time);
  vec2 hand = vec2(sin(angle), cos(angle));
  float along = dot(p, hand), across = abs(p.x * hand.y - p.y * hand.x);
  return (along >= 0.0 && along <= 0.4 && across <= 0.025) || r <= 0.04 ? 1 : 0;
}

// The ray parameter where the sample's ray meets the surface: trace/tracer.cpp's sphere and
// plane intersections (the nearer root; where the tessellated outline covers a sample just
// past the true one, the ray's closest approach).
float surface_parameter(vec3 origin, vec3 direction) {
  if (shape_kind == 3) {
    float a = dot(direction, direction), b = dot(origin, direction);
    float c = dot(origin, origin) - sphere_radius * sphere_radius;
    float root = sqrt(max(b * b - a * c, 0.0));
    return b < 0.0 ? c / (root - b) : -(b + root) / a;
  }
  return (plane.w - dot(plane.xyz, origin)) / dot(plane.xyz, direction);
}

// trace/tracer.cpp: a hit on a box lies exactly on the face where it is relatively farthest
// out, a hit on a plane exactly at y = 0.
vec3 surface_point(vec3 p) {
  if (shape_kind == 1) {
    vec3 rel = abs(p / box_size);
    if (rel.x >= rel.y && rel.x >= rel.z) p.x = sign(p.x) * 0.5 * box_size.x;
    else if (rel.y >= rel.z) p.y = sign(p.y) * 0.5 * box_size.y;
    else p.z = sign(p.z) * 0.5 * box_size.z;
  } else if (shape_kind == 2) {
    p.y = 0.0;
  }
  return p;
}

#if defined(LIGHTCONE_LIT)
// trace/tracer.cpp: the normal at a surface point, in shape coordinates, facing the ray.
vec3 shape_normal(vec3 p, vec3 direction) {
  vec3 n = plane.xyz;
  if (shape_kind == 3) {
    n = p;
  } else if (shape_kind == 1) {
    vec3 rel = abs(p / box_size);
    if (rel.x >= rel.y && rel.x >= rel.z) n = vec3(sign(p.x), 0.0, 0.0);
    else if (rel.y >= rel.z) n = vec3(0.0, sign(p.y), 0.0);
    else n = vec3(0.0, 0.0, sign(p.z));
  } else if (shape_kind == 2) {
    n = vec3(0.0, 1.0, 0.0);
  }
  n = normalize(n);
  return dot(n, direction) > 0.0 ? -n : n;
}


uniform vec3 albedo[2];  // lit materials: the rest-frame albedo of each fixed colour
#endif

const float kTwoPi = 6.283185307179586;
const float kHalfTurn = 3.141592653589793;

// trace/tracer.cpp's texture coordinates of a surface point: sphere_uv, box_uv, the plane's.
vec2 surface_uv(vec3 p) {
  if (shape_kind == 3) {
    vec3 n = normalize(p);
    return vec2(0.5 + atan(n.x, n.z) / kTwoPi, atan(length(n.xz), n.y) / kHalfTurn);
  }
  if (shape_kind == 1) {
    vec3 rel = p / box_size, a = abs(rel);
    if (a.x >= a.y && a.x >= a.z) return vec2(0.5 + rel.z, 0.5 - rel.y);
    if (a.y >= a.z) return vec2(0.5 + rel.x, 0.5 + rel.z);
    return vec2(0.5 + rel.x, 0.5 - rel.y);
  }
  return vec2(0.5 + p.x / box_size.x, 0.5 + p.z / box_size.z);  // a plane's size in x and z
}

void main() {
  vec3 u = fragment_look_direction();
  vec3 direction = ray_offset + shape_spatial * u;
  float s = max(surface_parameter(shape_origin, direction), 0.0);
  vec3 p = surface_point(shape_origin + direction * s);
  gl_FragDepth = clamp((log(max(s, 1e-30)) - depth_range.x) / (depth_range.y - depth_range.x),
                       0.0, 1.0);
  float d = doppler_factor(u, doppler_velocity, doppler_gamma);
  float proper_time = proper_time_origin + s * (proper_time_ray + dot(proper_time_row, u));
  int k = pattern == 1                     ? checker_index(p, checker_size)
          : pattern == 3                   ? blink_index(proper_time)
          : pattern == 4 && shape_kind > 0 ? clock_index(surface_uv(p), proper_time)
                                           : 0;
  // One program per kind of material (the program defines which), so that each stays small.
#if defined(LIGHTCONE_LIT)
  vec3 c = lit_colour(albedo[k], k, u, s, d, shape_normal(p, direction), fragment_light_sample());
  colour = vec4(spectral == 1 ? c * spectral_searchlight(d, searchlight_model) : c, 1.0);
#elif defined(LIGHTCONE_TEXTURED)
  colour = vec4(received_rgb(sample_bilinear(texture_image, surface_uv(p), true), d), 1.0);
#else
  colour = vec4(received_colour(colour_row + k, d), 1.0);
#endif
}
