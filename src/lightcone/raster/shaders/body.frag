// A body's fragment: the sample's own ray, carried into the body's shape coordinates (where the
// body is static), meets the face the fragment belongs to (a box where the ray enters it, or
// the sphere) exactly, as the ray tracer's does; that surface point's rest-frame pattern colour
// is received with the Doppler factor of the exact look direction, and its light travel
// distance is the fragment's depth.
flat in vec4 plane;
in float vertex_distance;  // the light travel distance at the vertices, interpolated

// The body's map from a ray of look direction u to shape coordinates (frame/resolved_scene.hpp):
// shape_origin + s (ray_offset + shape_spatial u).
uniform vec3 shape_origin;
uniform vec3 ray_offset;
uniform mat3 shape_spatial;
uniform vec2 depth_range;
uniform vec3 doppler_velocity;  // the body's velocity in F (0 for the classical picture)
// The colour's alpha: 2 on a body moving relative to the camera (the automatic exposure's
// subject, RasterFrameImage), else 1; the sky's is at most 1.
uniform float subject_alpha;
uniform float doppler_gamma;
uniform int colour_row;  // the row of the pattern's first colour
uniform sampler2D texture_image;
#if defined(LIGHTCONE_FACE_UVS)
flat in vec4 uv_u;  // a textured mesh's face: u = uv_u.xyz . p + uv_u.w (body.vert)
flat in vec4 uv_v;

// The texture coordinates of surface point p: a mesh face's map, or the shape's own.
vec2 body_uv(vec3 p) {
  return shape_kind == 0 ? vec2(dot(uv_u.xyz, p) + uv_u.w, dot(uv_v.xyz, p) + uv_v.w)
                         : surface_uv(p);
}
#endif
// The body's own clock at the ray's event s: proper_time_origin + s (proper_time_ray +
// proper_time_row . u) (ResolvedBody::proper_time).
uniform float proper_time_origin;
uniform float proper_time_ray;
uniform vec3 proper_time_row;
// A spinning body (ResolvedSpin): its shape coordinates above are those of the shape frozen at
// the angle its origin shows; the rest frame of its centre is rest_from_shape of them, where
// at proper time tau a point p of the shape sits at R(spin_rate tau) rest_of_shape p.
uniform int spinning;
uniform int spin_round;  // a ball of one radius: the same at every angle
uniform vec3 spin_axis;
uniform float spin_rate;
uniform mat3 rest_from_shape;
uniform mat3 shape_of_rest;
uniform mat4 trace_from_rest;  // the linear part: 4-velocities from the rest frame to F
uniform float sphere_radius;
uniform int relativity;  // 0: the classical picture, where no point's motion shifts its light

#if defined(LIGHTCONE_LIT)
// A lit body writes what the lighting pass (lit_surfaces.frag) needs of its nearest surface at
// each pixel, its exact depth deciding which is nearest; that pass lights each pixel once.
layout(location = 0) out vec4 lit_surface;  // the normal in the body's rest frame, s
layout(location = 1) out vec4 lit_motion;   // the surface's velocity in W, D_camera
layout(location = 2) out vec4 lit_albedo;   // the albedo, lit_code

// What the lighting pass needs of the surface besides: its body's row of reflection_index
// (where its finish is too), the fixed colour k (-1: a texel's, to be fitted) and the colour's
// alpha (1 or 2), in one float, exact as an integer; 0 is left for "no lit surface".
// lit_surfaces.frag takes it apart.
float lit_code(int body, int k, float alpha) {
  return float((body * 4 + k + 1) * 2 + (alpha > 1.5 ? 1 : 0) + 1);
}
#elif defined(LIGHTCONE_SURFACE_VARIABLES)
// What the output variables need of the nearest surface at each pixel's centre
// (raster/surface_variables.cpp): its normal with W's axes, facing the ray, and its light
// travel distance s; its body's index and Doppler factor (alpha 1: a surface, 0: none).
layout(location = 0) out vec4 surface_normal_distance;
layout(location = 1) out vec4 surface_object_doppler;
uniform float body_index;
#else
layout(location = 0) out vec4 colour;
#endif

// The ray parameter where the sample's ray meets the surface: trace/tracer.cpp's sphere, box
// and plane intersections (the nearer root; a box's entry into its slabs, so that a sample near
// an edge meets the face its own ray meets, not the one the tessellated edge, up to half a
// pixel off, drew there; where the tessellated outline covers a sample just past the true one,
// the ray's closest approach, or the fragment's face).
float surface_parameter(vec3 origin, vec3 direction) {
  if (shape_kind == 3) {
    float a = dot(direction, direction), b = dot(origin, direction);
    float c = dot(origin, origin) - sphere_radius * sphere_radius;
    float root = sqrt(max(b * b - a * c, 0.0));
    return b < 0.0 ? c / (root - b) : -(b + root) / a;
  }
  if (shape_kind == 1) {
    // A direction's zero component kept off zero with its sign, so that no slab divides by 0.
    vec3 safe = sign(direction + vec3(1e-30)) * max(abs(direction), vec3(1e-30));
    vec3 near_side = (-0.5 * sign(safe) * box_size - origin) / safe;
    vec3 far_side = (0.5 * sign(safe) * box_size - origin) / safe;
    float enter = max(max(near_side.x, near_side.y), near_side.z);
    float leave = min(min(far_side.x, far_side.y), far_side.z);
    if (enter <= leave && enter > 0.0) return enter;
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

// A spinning body's point met by the ray (origin + s direction in frozen shape coordinates,
// its clock tau0 + s tau1): the ray is a curve in the shape's own coordinates. A round ball is
// met where the straight ray meets it; other shapes by Newton's method on the fragment's face
// plane along that curve, from the interpolated distance (trace/tracer.cpp bisects instead).
struct SpinHit {
  float s;
  vec3 shape_point, rest_point;
  float angle;
};
SpinHit spinning_hit(vec3 origin, vec3 direction, float tau0, float tau1, bool round) {
  vec3 o = rest_from_shape * origin, d = rest_from_shape * direction;
  float s = round ? max(surface_parameter(origin, direction), 0.0) : vertex_distance;
  for (int i = 0; i < 8 && !round; ++i) {
    float angle = -spin_rate * (tau0 + s * tau1);
    vec3 x = o + d * s;
    vec3 p = shape_of_rest * turned(spin_axis, angle, x);
    vec3 dp = shape_of_rest * (turned(spin_axis, angle, d) -
                               spin_rate * tau1 * cross(spin_axis, turned(spin_axis, angle, x)));
    float slope = dot(plane.xyz, dp);
    if (slope == 0.0) break;
    float step = (dot(plane.xyz, p) - plane.w) / slope;
    s -= step;
    if (abs(step) <= 1e-6 * s) break;
  }
  SpinHit hit;
  hit.s = s;
  hit.rest_point = o + d * s;
  hit.angle = spin_rate * (tau0 + s * tau1);
  hit.shape_point = shape_of_rest * turned(spin_axis, -hit.angle, hit.rest_point);
  return hit;
}

#if defined(LIGHTCONE_LIT) || defined(LIGHTCONE_SURFACE_VARIABLES)
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

uniform mat3 normal_to_rest;  // rotation * diag(1 / scale)
#endif

#if defined(LIGHTCONE_LIT)
uniform vec3 albedo[2];  // lit materials: the rest-frame albedo of each fixed colour
uniform mat4 trace_to_world;  // the linear part: (t, x) in F to W
uniform vec3 surface_velocity_of_body;  // in W (0 for the classical picture)
uniform int reflection_body;  // the body's row of reflection_index
#endif

void main() {
  vec3 u = fragment_look_direction();
  vec3 direction = ray_offset + shape_spatial * u;
  float tau1 = proper_time_ray + dot(proper_time_row, u);
  float s;
  vec3 p;
  vec3 velocity = doppler_velocity;
  float gamma = doppler_gamma;
  float spin_angle = 0.0;
#if !defined(LIGHTCONE_NO_SPIN)
  if (spinning == 1) {
    // The point's own velocity, rate axis x r in the rest frame, carried to F.
    SpinHit hit = spinning_hit(shape_origin, direction, proper_time_origin, tau1, spin_round == 1);
    s = hit.s;
    p = surface_point(hit.shape_point);
    spin_angle = hit.angle;
    direction = shape_of_rest * turned(spin_axis, -hit.angle, rest_from_shape * direction);
    if (relativity == 1) {
      vec4 moving = trace_from_rest * vec4(1.0, spin_rate * cross(spin_axis, hit.rest_point));
      velocity = moving.yzw / moving.x;
      gamma = inversesqrt(max(1.0 - dot(velocity, velocity), 1e-12));
    }
  } else
#endif
  {
    s = max(surface_parameter(shape_origin, direction), 0.0);
    p = surface_point(shape_origin + direction * s);
  }
  float depth =
      clamp((log(max(s, 1e-30)) - depth_range.x) / (depth_range.y - depth_range.x), 0.0, 1.0);
  gl_FragDepth = depth;
  float d = doppler_factor(u, velocity, gamma);
  float proper_time = proper_time_origin + s * tau1;
  int k = pattern_index(p, proper_time);
#if defined(LIGHTCONE_MESH_CLOCKS)
  // A clock on a mesh: its dial at the face's texture coordinates, as the tracer reads it.
  if (pattern == 4 && shape_kind == 0) k = clock_index(body_uv(p), proper_time);
#endif
  // One program per kind of material (the program defines which), so that each stays small.
#if defined(LIGHTCONE_SURFACE_VARIABLES)
  vec3 normal = normalize(normal_to_rest * shape_normal(p, direction));
#if !defined(LIGHTCONE_NO_SPIN)
  if (spinning == 1) normal = turned(spin_axis, spin_angle, normal);
#endif
  surface_normal_distance = vec4(normal, s);
  surface_object_doppler = vec4(body_index, d, 0.0, 1.0);
#elif defined(LIGHTCONE_LIT)
  vec3 normal = normalize(normal_to_rest * shape_normal(p, direction));
  vec3 surface_velocity = surface_velocity_of_body;
#if !defined(LIGHTCONE_NO_SPIN)
  if (spinning == 1) {
    normal = turned(spin_axis, spin_angle, normal);
    vec4 moving = trace_to_world * vec4(1.0, velocity);
    surface_velocity = relativity == 1 ? moving.yzw / moving.x : vec3(0.0);
  }
#endif
  vec3 surface_albedo = albedo[k];
#if defined(LIGHTCONE_LIT_TEXTURES)
  // A lit texture: each sample's texel is its albedo (the colour models other than spectral are
  // linear in it; under the spectral model the lighting pass fits it to a reflectance).
  if (pattern == 2) {
    surface_albedo = sample_bilinear(texture_image, body_uv(p), true);
#if defined(LIGHTCONE_SPECTRAL_TEXTURES)
    k = -1;
#endif
  }
#endif
  lit_surface = vec4(normal, s);
  lit_motion = vec4(surface_velocity, d);
  lit_albedo = vec4(surface_albedo, lit_code(reflection_body, k, subject_alpha));
#elif defined(LIGHTCONE_TEXTURED)
  colour = vec4(received_rgb(sample_bilinear(texture_image, body_uv(p), true), d), subject_alpha);
#else
  colour = vec4(received_colour(colour_row + k, d), subject_alpha);
#endif
}
