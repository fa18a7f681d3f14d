// Lit surfaces, for the body fragment shader: frame/lighting.cpp's Lighting::received, law for
// law, in the world frame W with its origin moved to the observation event (so that single
// precision stays accurate). Shadows come from maps of the bodies at rest relative to each
// light (raster/shadow_maps.hpp). Each function names the C++ it mirrors.

const float kPi = 3.141592653589793;

// The lights, any number of them: seven texels each (raster_renderer.cpp, set_lights), as
// uniforms for up to 16 lights (a software rasteriser reads a uniform once for a block of
// fragments, a texture per fragment), else a row of light_table each.
uniform int light_count;
#if defined(LIGHTCONE_MANY_LIGHTS)
uniform highp sampler2D light_table;
vec4 lamp_texel(int l, int i) {
  return texelFetch(light_table, ivec2(i, l), 0);
}
#else
uniform vec4 lamp_texels[7 * 16];  // shader_build.hpp's kUniformLamps
vec4 lamp_texel(int l, int i) {
  return lamp_texels[7 * l + i];
}
#endif
struct Lamp {
  int kind;           // 0 point, 1 spot, 2 directional, 3 sphere
  bool fixed_event;   // emission at `event` (delay camera or none)
  int row;            // its colour row: against ln D (others), or the glossy row
  int shadow_layer;   // the first of its six shadow maps (shadow_maps.hpp), or -1
  vec4 event;         // (t, x) relative to the observation event
  vec3 position;      // its world-line: position at `time`
  float time;
  vec3 velocity;      // in W (0 for the classical picture)
  float one_minus_beta2;
  vec3 axis;          // spot axis, or the directional light's direction
  float intensity;    // point, spot, sphere: I; directional: E
  vec2 cone;          // spot: half angle, falloff (degrees)
  float radius;       // sphere
  float shadow_far;   // its maps' distances are stored over this
  vec4 shadow_origin; // its position at the camera's time (relative to the observation event)
};
Lamp lamp(int l) {
  vec4 t0 = lamp_texel(l, 0), t2 = lamp_texel(l, 2), t3 = lamp_texel(l, 3),
       t4 = lamp_texel(l, 4), t5 = lamp_texel(l, 5);
#if defined(LIGHTCONE_MOVING_LIGHTS)
  vec3 velocity = t3.xyz;
  float one_minus_beta2 = t3.w;
#else
  // Every light at rest in W: the laws below fold to their forms for beta = 0.
  const vec3 velocity = vec3(0.0);
  const float one_minus_beta2 = 1.0;
#endif
  return Lamp(int(t0.x), t0.y > 0.5, int(t0.z), int(t0.w), lamp_texel(l, 1),
              t2.xyz, t2.w, velocity, one_minus_beta2, t4.xyz, t4.w, t5.xy, t5.z, t5.w,
              lamp_texel(l, 6));
}

uniform mat4 trace_to_world;  // the linear part: (t, x) in F to W
uniform vec3 camera_velocity;   // in W (0 for the classical picture)
uniform int searchlight_model;  // 0 physical, 1 chang1996, 2 off
// A lit surface's finish (frame/lighting.cpp's material terms): glossy or not, its GGX
// roughness and specular weight, and its body's row of reflection_index.
struct Finish {
  bool glossy;
  float roughness, specular;
  int reflection_body;
};
// Spectral: the reflected colour of (fixed colour k, light l) of the body: texel (k light_count
// + l, reflection_body) of reflection_index holds its row and whether the light moves relative
// to the body; a row against ln D_camera (a light co-moving with the surface) or, for a moving
// one, the first of a block of rows of reflection_tables, one per node of ln D_light. The row's
// last texel holds the body's finish (roughness, -1 for matte; specular).
uniform highp sampler2D reflection_index;
uniform sampler2D reflection_tables;
uniform vec4 reflection_grid;  // (first ln D_camera, step, first ln D_light, step)
uniform int reflection_light_nodes;

// physics/lorentz.cpp, boost: coordinates in the frame moving with beta.
vec4 boost(vec3 beta, vec4 e) {
  float b2 = dot(beta, beta);
  if (b2 == 0.0) return e;
  float g = 1.0 / sqrt(1.0 - b2);
  float bx = dot(beta, e.yzw);
  return vec4(g * (e.x - bx), e.yzw + ((g - 1.0) / b2 * bx - g * e.x) * beta);
}

// physics/doppler.cpp, doppler_factor: D = (k.U_R) / (k.U_E) for propagation direction n.
float doppler_between(vec3 n, vec3 beta_e, vec3 beta_r) {
  float ge = 1.0 / sqrt(1.0 - dot(beta_e, beta_e)), gr = 1.0 / sqrt(1.0 - dot(beta_r, beta_r));
  return gr * (1.0 - dot(beta_r, n)) / (ge * (1.0 - dot(beta_e, n)));
}

// physics/light_path.cpp, receive_leg.
struct Leg {
  float doppler, distance;
  vec3 direction, emitted_direction;
};
Leg receive_leg(vec4 emission, vec3 beta_emitter, vec4 reception, vec3 beta_receiver) {
  Leg leg;
  vec4 in_receiver = boost(beta_receiver, reception - emission);
  leg.distance = length(in_receiver.yzw);
  leg.direction = in_receiver.yzw / leg.distance;
  vec4 k_common = boost(-beta_receiver, vec4(1.0, leg.direction));
  vec4 k_emitter = boost(beta_emitter, k_common);
  leg.emitted_direction = normalize(k_emitter.yzw);
  leg.doppler = doppler_between(k_common.yzw / k_common.x, beta_emitter, beta_receiver);
  return leg;
}

// frame/lighting.cpp, contracted: a rest offset of a body moving with beta at one instant of W.
vec3 contracted(vec3 offset, vec3 beta) {
  float b2 = dot(beta, beta);
  if (b2 == 0.0) return offset;
  float g = 1.0 / sqrt(1.0 - b2);
  return offset - beta * ((1.0 - 1.0 / g) * dot(beta, offset) / b2);
}

// frame/lighting.cpp, sphere_point: a uniform point on the unit sphere.
vec3 sphere_point(vec2 u) {
  float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// frame/lighting.cpp, glossy_reflectance (GGX, Smith, Schlick).
float glossy_reflectance(Finish finish, vec3 n, vec3 to_light, vec3 to_camera) {
  float cos_i = dot(n, to_light), cos_o = dot(n, to_camera);
  if (cos_i <= 0.0 || cos_o <= 0.0) return 0.0;
  vec3 h = normalize(to_light + to_camera);
  float a2 = pow(finish.roughness, 4.0);
  float cos_h = dot(n, h);
  float denom = cos_h * cos_h * (a2 - 1.0) + 1.0;
  float distribution = a2 / (kPi * denom * denom);
  float g1i = 2.0 * cos_i / (cos_i + sqrt(a2 + (1.0 - a2) * cos_i * cos_i));
  float g1o = 2.0 * cos_o / (cos_o + sqrt(a2 + (1.0 - a2) * cos_o * cos_o));
  float fresnel = finish.specular + (1.0 - finish.specular) * pow(1.0 - dot(h, to_camera), 5.0);
  return distribution * g1i * g1o * fresnel / (4.0 * cos_i * cos_o);
}

#if !defined(LIGHTCONE_NO_SHADOWS)
// raster/shadow_maps.hpp: each light's six maps (Lamp's shadow_layer, shadow_origin and
// shadow_far).
uniform highp sampler2DArray shadow_maps;
uniform float shadow_texel;  // a texel's angle at a face's centre: 2 / the faces' size

// Whether the bodies at rest relative to light l hide it from the surface event: in the
// light's rest frame they and the light stand still, so the tracer's shadow ray runs along the
// segment from the light to the surface's position there, and the cube face that direction
// falls on holds the nearest body's distance along it. The bias covers the half texel between
// a direction and the texel's centre, more on surfaces the light grazes.
bool shadowed(Lamp light, vec4 surface, float cos_incidence) {
  if (light.shadow_layer < 0) return false;
  vec3 d = boost(light.velocity, surface - light.shadow_origin).yzw;
  vec3 a = abs(d);
  int face;
  vec2 uv;
  float major;
  // shadow_maps.cpp's kFaces: each face's right and up over its forward component.
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x > 0.0 ? 0 : 1;
    uv = vec2(d.x > 0.0 ? -d.z : d.z, d.y);
    major = a.x;
  } else if (a.y >= a.z) {
    face = d.y > 0.0 ? 2 : 3;
    uv = vec2(d.x, d.y > 0.0 ? -d.z : d.z);
    major = a.y;
  } else {
    face = d.z > 0.0 ? 4 : 5;
    uv = vec2(d.z > 0.0 ? d.x : -d.x, d.y);
    major = a.z;
  }
  if (!(major > 0.0)) return false;
  uv = uv / major * 0.5 + 0.5;
  float stored = texture(shadow_maps, vec3(uv, float(light.shadow_layer + face))).r;
  float distance = length(d);
  float c = clamp(cos_incidence, 0.1, 1.0);
  float bias = distance * shadow_texel * (1.0 + sqrt(1.0 - c * c) / c);
  return stored < 1.0 && distance > stored * light.shadow_far + bias;
}

#if defined(LIGHTCONE_EXACT_SHADOWS)  // a frame with bodies cast exactly
// raster/shadow_casters.hpp: each body's shape met along the shadow ray carried into its rest
// frame, where it stands still (trace/tracer.cpp's shadow rays: the segment between
// kShadowEpsilon and 1 - kShadowEpsilon of the way to the emission event). Any number of them,
// kCasterTexels each in caster_table: (size, kind, plus 8 for a spinning body), the map's three
// rows (spatial, time) from W events relative to the observation event to shape coordinates,
// (offset, a mesh's root node); for a spinning body then the rows of rest_from_shape and of
// shape_of_rest, (axis, rate), its clock's row (spatial, time) and (ball radius, clock origin).
uniform int caster_count;
uniform highp sampler2D caster_table;
const int kCasterTexelsPerRow = 2048;  // shadow_casters.cpp's kTexelsPerRow
const int kCasterTexels = 14;          // and its kCasterTexels
const float kShadowEpsilon = 1e-5;

vec4 caster_texel(int i) {
  return texelFetch(caster_table, ivec2(i % kCasterTexelsPerRow, i / kCasterTexelsPerRow), 0);
}

// frame/shape_intersection.hpp: first_in's range, [near, far).
bool in_range(float t, float near, float far) {
  return t >= near && t < far;
}

// frame/shape_intersection.hpp's sphere_span: where the line a + t d lies within `radius` of
// the origin (the root without cancellation, as there).
bool sphere_span(float radius, vec3 a, vec3 d, out float enter, out float leave) {
  float qa = dot(d, d), qb = dot(a, d), qc = dot(a, a) - radius * radius;
  float disc = qb * qb - qa * qc;
  enter = leave = 0.0;
  if (disc < 0.0 || qa == 0.0) return false;
  float q = -(qb + (qb < 0.0 ? -1.0 : 1.0) * sqrt(disc));
  enter = min(q / qa, qc / q);
  leave = max(q / qa, qc / q);
  return true;
}

// Its box_span, for the box from `lower` to `upper` (the line's direction given inverted; a
// zero component as 1e-30, so that no slab makes 0 times infinity).
vec3 inverse_direction(vec3 d) {
  return 1.0 / mix(d, vec3(1e-30), equal(d, vec3(0.0)));
}
bool box_span(vec3 lower, vec3 upper, vec3 a, vec3 inverse, out float enter, out float leave) {
  vec3 t0 = (lower - a) * inverse, t1 = (upper - a) * inverse;
  vec3 near = min(t0, t1), far = max(t0, t1);
  enter = max(near.x, max(near.y, near.z));
  leave = min(far.x, min(far.y, far.z));
  return enter <= leave;
}

// Where the line a + t d runs through a box (kind 1, sides `size`), a plane (kind 2, sides in x
// and z: entered and left at once) or a sphere (kind 3, radius size.x), as the tracer finds it.
bool shape_span(int kind, vec3 size, vec3 a, vec3 d, out float enter, out float leave) {
  if (kind == 3) return sphere_span(size.x, a, d, enter, leave);
  if (kind == 2) {
    enter = leave = d.y == 0.0 ? -1.0 : -a.y / d.y;
    vec3 p = a + enter * d;
    return d.y != 0.0 && abs(p.x) <= 0.5 * size.x && abs(p.z) <= 0.5 * size.z;
  }
  return box_span(-0.5 * size, 0.5 * size, a, inverse_direction(d), enter, leave);
}

#ifdef LIGHTCONE_MESH_SHADOWS
// The meshes' hierarchies (frame/mesh_bvh.hpp's MeshBvh): a node is two texels, (lower, leaf
// count) and (upper, its second child's texel or its first triangle's), its first child the
// next node; a triangle is three texels, its corners.
uniform highp sampler2D caster_meshes;
const int kCasterBvhMaxDepth = 32;  // frame/mesh_bvh.hpp's kMeshBvhMaxDepth

vec4 mesh_texel(int i) {
  return texelFetch(caster_meshes, ivec2(i % kCasterTexelsPerRow, i / kCasterTexelsPerRow), 0);
}

// Whether the segment a + t d, t in [t_near, t_far), meets a triangle of the mesh whose root
// node is texel `root`: trace/tracer.cpp's mesh hits (Moller and Trumbore's test).
bool mesh_meets(int root, vec3 a, vec3 d, float t_near, float t_far) {
  vec3 inverse = inverse_direction(d);
  int stack[kCasterBvhMaxDepth];
  int top = 0;
  int node = root;
  while (true) {
    vec4 lower = mesh_texel(node), upper = mesh_texel(node + 1);
    float enter, leave;
    if (box_span(lower.xyz, upper.xyz, a, inverse, enter, leave) &&
        max(enter, t_near) <= min(leave, t_far)) {
      int count = int(lower.w);
      if (count == 0) {
        stack[top++] = int(upper.w);
        node += 2;
        continue;
      }
      int first = int(upper.w);
      for (int i = 0; i < count; ++i) {
        vec3 v0 = mesh_texel(first + 3 * i).xyz;
        vec3 e1 = mesh_texel(first + 3 * i + 1).xyz - v0;
        vec3 e2 = mesh_texel(first + 3 * i + 2).xyz - v0;
        vec3 p = cross(d, e2);
        float det = dot(e1, p);
        if (det == 0.0) continue;
        float inv_det = 1.0 / det;
        vec3 s = a - v0;
        float u = dot(s, p) * inv_det;
        vec3 q = cross(s, e1);
        float v = dot(d, q) * inv_det;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && in_range(dot(e2, q) * inv_det, t_near, t_far))
          return true;
      }
    }
    if (top == 0) return false;
    node = stack[--top];
  }
  return false;
}
#endif

// Whether a caster of kind `kind` (1 box, 2 plane, 3 sphere, 4 mesh) and size `size` (a mesh's
// root node `root`) meets the segment a + t d, t in [t_near, t_far), of shape coordinates: the
// tracer's intersect_sphere, intersect_box and intersect_plane (either end of the span).
bool caster_meets(int kind, vec3 size, int root, vec3 a, vec3 d, float t_near, float t_far) {
#ifdef LIGHTCONE_MESH_SHADOWS
  if (kind == 4) return mesh_meets(root, a, d, t_near, t_far);
#endif
  float enter, leave;
  return shape_span(kind, size, a, d, enter, leave) &&
         (in_range(enter, t_near, t_far) || in_range(leave, t_near, t_far));
}

#ifdef LIGHTCONE_SPIN_SHADOWS
// frame/spinning_intersection.cpp, intersect_spinning_body, whether it meets and not where: the
// straight ray in the rest frame is a curve through the turning shape's coordinates, followed in
// chords that turn by at most kSpinChordAngle, each met against the shape as the tracer meets
// it (a sphere's or a box's entry, a plane's or a mesh's crossing, within the chord).
const float kSpinChordAngle = 0.03;
const float kMaxSpinChords = 4096.0;

bool chord_meets(int kind, vec3 size, int root, vec3 p, vec3 d) {
#ifdef LIGHTCONE_MESH_SHADOWS
  if (kind == 4) return mesh_meets(root, p, d, 0.0, 1.0);
#endif
  float enter, leave;
  return shape_span(kind, size, p, d, enter, leave) && in_range(enter, 0.0, 1.0);
}

// Whether the spinning caster at texel `base` meets the frozen shadow ray a + s d, s in
// [t_near, t_far), from the surface event along `direction` (W).
bool spinning_caster_meets(int base, int kind, vec3 size, int root, vec3 a, vec3 d,
                           vec4 surface, vec4 direction, float t_near, float t_far) {
  mat3 rest_from_shape = transpose(mat3(caster_texel(base + 5).xyz, caster_texel(base + 6).xyz,
                                        caster_texel(base + 7).xyz));
  mat3 shape_of_rest = transpose(mat3(caster_texel(base + 8).xyz, caster_texel(base + 9).xyz,
                                      caster_texel(base + 10).xyz));
  vec4 axis_rate = caster_texel(base + 11), row = caster_texel(base + 12);
  vec4 ball = caster_texel(base + 13);
  float tau0 = ball.y + dot(row, vec4(surface.yzw, surface.x));
  float tau1 = dot(row, vec4(direction.yzw, direction.x));
  vec3 o = rest_from_shape * a, r = rest_from_shape * d;
  // The part of the ray inside the ball that holds the shape at every angle.
  float in_ball, out_ball;
  if (!sphere_span(ball.x, o, r, in_ball, out_ball)) return false;
  float lo = max(in_ball, t_near), hi = min(out_ball, t_far);
  if (!(lo < hi)) return false;
  float rate = axis_rate.w;
  float sweep = abs(rate * tau1) * (hi - lo);
  int chunks = int(clamp(ceil(sweep / kSpinChordAngle), 1.0, kMaxSpinChords));
  vec3 pa = shape_of_rest * turned(axis_rate.xyz, -rate * (tau0 + lo * tau1), o + lo * r);
  for (int k = 1; k <= chunks; ++k) {
    float s = lo + (hi - lo) * float(k) / float(chunks);
    vec3 pb = shape_of_rest * turned(axis_rate.xyz, -rate * (tau0 + s * tau1), o + s * r);
    if (chord_meets(kind, size, root, pa, pb - pa)) return true;
    pa = pb;
  }
  return false;
}
#endif

// Whether any exact caster blocks the shadow ray from the surface event to `end` (or backward
// along direction `end` without end).
bool exactly_shadowed(vec4 surface, vec4 end, bool to_infinity) {
  vec4 direction = to_infinity ? -end : end - surface;
  float t_far = to_infinity ? 1e30 : 1.0 - kShadowEpsilon;
  for (int k = 0; k < caster_count; ++k) {
    int base = kCasterTexels * k;
    vec4 head = caster_texel(base);
    vec4 r0 = caster_texel(base + 1), r1 = caster_texel(base + 2), r2 = caster_texel(base + 3);
    vec4 tail = caster_texel(base + 4);
    // The map's rows on events (t, x) as (x, t), its offset on the point alone.
    mat3x4 rows = mat3x4(r0, r1, r2);
    vec3 a = vec4(surface.yzw, surface.x) * rows + tail.xyz;
    vec3 d = vec4(direction.yzw, direction.x) * rows;
    int kind = int(head.w);
#ifdef LIGHTCONE_SPIN_SHADOWS
    if (kind >= 8) {
      if (spinning_caster_meets(base, kind - 8, head.xyz, int(tail.w), a, d, surface, direction,
                                kShadowEpsilon, t_far))
        return true;
      continue;
    }
#endif
    if (caster_meets(kind, head.xyz, int(tail.w), a, d, kShadowEpsilon, t_far)) return true;
  }
  return false;
}
#endif  // LIGHTCONE_EXACT_SHADOWS
#endif

struct Incoming {
  vec3 direction_to_light;
  float doppler, irradiance, spectral_factor;
  // The shadow ray's far end (W, relative to the observation event): the emission event, or
  // for a directional light the light's direction of travel (the ray runs backward along it
  // without end).
  vec4 shadow_end;
  bool to_infinity;
};

// frame/lighting.cpp, set_irradiance: the searchlight model's irradiance factors.
void set_irradiance(inout Incoming in_light, float geometric, float physical,
                    float physical_spectral) {
  if (searchlight_model == 0) {
    in_light.irradiance = physical;
    in_light.spectral_factor = physical_spectral;
  } else if (searchlight_model == 1) {
    in_light.irradiance = in_light.spectral_factor = geometric * in_light.doppler;
  } else {
    in_light.irradiance = in_light.spectral_factor = geometric;
  }
}

// frame/lighting.cpp, Lighting::incoming (without shadows).
bool incoming(Lamp light, vec4 surface, vec3 surface_velocity, vec3 normal, vec2 light_sample,
              out Incoming result) {
  result = Incoming(vec3(0.0), 1.0, 0.0, 0.0, vec4(0.0), false);
  vec3 beta_l = light.velocity;
#if defined(LIGHTCONE_SUN_LIGHTS)
  if (light.kind == 2) {
    // A plane wave: physics/light_path.cpp's plane-wave laws.
    vec4 k_world = boost(-beta_l, vec4(1.0, normalize(light.axis)));
    vec4 k_surface = boost(surface_velocity, k_world);
    result.direction_to_light = -(k_surface.yzw / k_surface.x);
    result.doppler = k_surface.x;
    float cos_i = dot(normal, result.direction_to_light);
    if (!(cos_i > 0.0)) return false;
    float e = light.intensity;
    set_irradiance(result, e * cos_i, result.doppler * result.doppler * e * cos_i,
                   e * result.doppler * result.doppler * result.doppler * cos_i);
    result.shadow_end = k_world;
    result.to_infinity = true;
    return true;
  }
#endif
  vec3 rest_offset = vec3(0.0);
  float intensity = light.intensity;
#if defined(LIGHTCONE_SPHERE_LIGHTS)
  if (light.kind == 3) rest_offset = sphere_point(light_sample) * light.radius;
#endif
  vec3 offset_world = contracted(rest_offset, beta_l);
  vec4 emission;
  if (light.fixed_event) {
    emission = light.event + vec4(0.0, offset_world);
  } else {
    vec3 at = light.position + beta_l * (surface.x - light.time) + offset_world;
    float tau = retarded_delay(at - surface.yzw, beta_l, light.one_minus_beta2);
    emission = vec4(surface.x - tau, at - beta_l * tau);
  }
  Leg leg = receive_leg(emission, beta_l, surface, surface_velocity);
  result.direction_to_light = -leg.direction;
  result.doppler = leg.doppler;
  float cos_i = dot(normal, result.direction_to_light);
  if (!(cos_i > 0.0) || !(leg.distance > 0.0)) return false;
#if defined(LIGHTCONE_SPOT_LIGHTS)
  if (light.kind == 1) {
    float angle = degrees(acos(clamp(dot(leg.emitted_direction, normalize(light.axis)), -1.0,
                                     1.0)));
    float half_cone = light.cone.x, falloff = light.cone.y;
    intensity *= 1.0 - (falloff <= 0.0 ? (angle >= half_cone ? 1.0 : 0.0)
                                       : smoothstep(half_cone - falloff, half_cone, angle));
  }
#endif
#if defined(LIGHTCONE_SPHERE_LIGHTS)
  if (light.kind == 3)
    intensity *= 4.0 * max(0.0, dot(normalize(rest_offset), leg.emitted_direction));
#endif
  if (intensity <= 0.0) return false;
  float d2 = leg.doppler * leg.doppler, r2 = leg.distance * leg.distance;
  set_irradiance(result, intensity * cos_i / r2, d2 * d2 * intensity * cos_i / r2,
                 intensity * d2 * d2 * leg.doppler * cos_i / r2);
  result.shadow_end = emission;
  return true;
}

// A moving light's reflected colour against (ln D_camera, ln D_light): bilinear between the
// rows of its block.
vec3 reflection_table(int first_row, float log_camera, float log_light) {
  float x = (log_camera - reflection_grid.x) / reflection_grid.y;
  float y = (log_light - reflection_grid.z) / reflection_grid.w;
  float last_x = float(textureSize(reflection_tables, 0).x - 1);
  float last_y = float(reflection_light_nodes - 1);
  x = clamp(x, 0.0, last_x);
  y = clamp(y, 0.0, last_y);
  float i = min(floor(x), last_x - 1.0), j = min(floor(y), last_y - 1.0);
  int r = first_row + int(j);
  vec3 a = mix(texelFetch(reflection_tables, ivec2(int(i), r), 0).rgb,
               texelFetch(reflection_tables, ivec2(int(i) + 1, r), 0).rgb, x - i);
  vec3 b = mix(texelFetch(reflection_tables, ivec2(int(i), r + 1), 0).rgb,
               texelFetch(reflection_tables, ivec2(int(i) + 1, r + 1), 0).rgb, x - i);
  return mix(a, b, y - j);
}

#if defined(LIGHTCONE_SPECTRAL_TEXTURES)
// A lit texture under the spectral model (raster/spectral_albedo.hpp): each sample's albedo is
// fitted to a reflectance spectrum as the tracer fits it, and its light summed wavelength by
// wavelength. The Jakob-Hanika coefficient table: texel (i, j, 64 l + k) holds cell (l, k, j, i)
// (color/sigmoid_polynomial.hpp's layout).
uniform highp sampler3D rgb_to_spectrum;
// Row 0: the CIE 1931 functions at 360, 361, ..., 830 nm as linear sRGB (the matrix applied),
// over the integral of y-bar, and ln(lambda) in alpha.
uniform highp sampler2D cie_srgb;
// Each light's spectrum against ln(lambda) from light_spectra_grid.x in steps of
// 1 / light_spectra_grid.y, folded into rows of light_spectra_grid.z texels,
// light_spectra_grid.w rows a light.
uniform highp sampler2D light_spectra;
uniform vec4 light_spectra_grid;
// The fitted reflectance of the fragment's texel (set before lit_colour).
vec3 texel_reflectance;

// color/sigmoid_polynomial.hpp, rgb_to_spectrum_scale_node.
float scale_node(int k) {
  float t = float(k) / 63.0;
  t = t * t * (3.0 - 2.0 * t);
  return t * t * (3.0 - 2.0 * t);
}

// color/rgb_spectrum.cpp, rgb_to_sigmoid: the table's cell by the largest component and the
// other two over it, coefficients interpolated trilinearly.
vec3 rgb_to_sigmoid(vec3 rgb) {
  vec3 c = clamp(rgb, 0.0, 1.0);
  int l = 0;
  if (c.y > c[l]) l = 1;
  if (c.z > c[l]) l = 2;
  float z = c[l];
  if (z <= 0.0) return vec3(0.0, 0.0, -1e18);  // black: 0 at every wavelength
  float fx = c[(l + 1) % 3] / z * 63.0, fy = c[(l + 2) % 3] / z * 63.0;
  int xi = min(int(fx), 62), yi = min(int(fy), 62);
  float dx = fx - float(xi), dy = fy - float(yi);
  // The last node at or below z (nodes[0] = 0 < z), at most 62.
  int lo = 0, hi = 63;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (scale_node(mid) <= z) lo = mid; else hi = mid;
  }
  int zi = min(lo, 62);
  float z0 = scale_node(zi);
  float dz = (z - z0) / (scale_node(zi + 1) - z0);
  vec3 out_c = vec3(0.0);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int e = 0; e < 2; ++e) {
        float w = (a == 1 ? dz : 1.0 - dz) * (b == 1 ? dy : 1.0 - dy) * (e == 1 ? dx : 1.0 - dx);
        out_c += w * texelFetch(rgb_to_spectrum, ivec3(xi + e, yi + b, 64 * l + zi + a), 0).xyz;
      }
  return out_c;
}

// color/sigmoid_polynomial.hpp, SigmoidPolynomial (flat beyond 360 and 830 nm) and sigmoid.
float reflectance_at(vec3 coefficients, float lambda) {
  float u = (clamp(lambda, 360.0, 830.0) - 595.0) / 235.0;
  float x = (coefficients.x * u + coefficients.y) * u + coefficients.z;
  float r = sqrt(1.0 + x * x);
  return x >= 0.0 ? (r + x) / (2.0 * r) : 1.0 / (2.0 * r * (r - x));
}

// Light l's spectrum at ln(lambda) = x, linear between the table's samples.
float light_spectrum(int l, float x) {
  float last = light_spectra_grid.z * light_spectra_grid.w - 2.0;
  float p = clamp((x - light_spectra_grid.x) * light_spectra_grid.y, 0.0, last);
  int j = int(p);
  int width = int(light_spectra_grid.z), first_row = l * int(light_spectra_grid.w);
  float a = texelFetch(light_spectra, ivec2(j % width, first_row + j / width), 0).r;
  float b = texelFetch(light_spectra, ivec2((j + 1) % width, first_row + (j + 1) / width), 0).r;
  return mix(a, b, p - float(j));
}

// color/doppler_table.hpp, xyz_of_reflection_seen_with_doppler: the texel's reflectance seen
// with d_camera, lit by light l seen with d_light from the surface, by the 1 nm sum; as linear
// sRGB.
vec3 texel_reflected(int l, float d_camera, float d_light) {
  float log_total = log(d_camera * d_light);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 471; ++i) {
    float lambda = 360.0 + float(i);
    vec4 cie = texelFetch(cie_srgb, ivec2(i, 0), 0);
    sum += reflectance_at(texel_reflectance, d_camera * lambda) *
           light_spectrum(l, cie.a + log_total) * cie.rgb;
  }
  return sum;
}
#endif

// frame/lighting.cpp, Lighting::received: the light a lit surface point of albedo `albedo`
// (fixed colour `k`, or -1 for a texel under the spectral model: texel_reflectance) and finish
// sends to the camera, seen along u with factor d_camera; s is the ray parameter of the surface
// point, surface_velocity its velocity in W (0 for the classical picture) and normal its normal
// in its body's rest frame.
vec3 lit_colour(vec3 albedo, int k, Finish finish, vec3 u, float s, float d_camera,
                vec3 surface_velocity, vec3 normal, vec2 light_sample) {
  float diffuse = finish.glossy ? 1.0 - finish.specular : 1.0;
  vec4 surface = trace_to_world * vec4(ray_time * s, u * s);
  Leg view = receive_leg(surface, surface_velocity, vec4(0.0), camera_velocity);
  vec3 to_camera = view.emitted_direction;
  vec3 seen = vec3(0.0), outgoing = vec3(0.0);
  ColourNode camera_node = colour_node(d_camera);  // the reflected rows' node, once
  for (int l = 0; l < light_count; ++l) {
    Lamp light = lamp(l);
    Incoming in_light;
    if (!incoming(light, surface, surface_velocity, normal, light_sample, in_light)) continue;
#if !defined(LIGHTCONE_NO_SHADOWS)
    if (shadowed(light, surface, dot(normal, in_light.direction_to_light))) continue;
#if defined(LIGHTCONE_EXACT_SHADOWS)
    if (exactly_shadowed(surface, in_light.shadow_end, in_light.to_infinity)) continue;
#endif
#endif
#if defined(LIGHTCONE_GLOSSY)
    float gloss = finish.glossy ? glossy_reflectance(finish, normal, in_light.direction_to_light,
                                                     to_camera)
                                : 0.0;
#else
    const float gloss = 0.0;
#endif
    if (spectral == 1) {
      vec3 reflected;
#if defined(LIGHTCONE_SPECTRAL_TEXTURES)
      if (k < 0) {
        reflected = texel_reflected(l, d_camera, in_light.doppler);
      } else
#endif
      {
        vec2 index =
            texelFetch(reflection_index, ivec2(k * light_count + l, finish.reflection_body), 0).xy;
#if defined(LIGHTCONE_MOVING_LIGHT_REFLECTIONS)
        reflected = index.y > 0.5
                        ? reflection_table(int(index.x), log(d_camera), log(in_light.doppler))
                        : received_colour_at(int(index.x), camera_node);
#else
        reflected = received_colour_at(int(index.x), camera_node);
#endif
      }
      seen += diffuse / kPi * in_light.spectral_factor * reflected;
      if (gloss > 0.0)
        seen += gloss * in_light.spectral_factor *
                received_colour(light.row, d_camera * in_light.doppler);
    } else {
      vec3 colour = received_colour(light.row, in_light.doppler);
      outgoing += (diffuse * albedo / kPi + vec3(gloss)) * colour * in_light.irradiance;
    }
  }
  if (spectral == 1) return seen;  // the searchlight factor is applied by the caller
  // The colour models other than spectral are linear in the colour (common.glsl).
  return received_rgb(outgoing, d_camera);
}
