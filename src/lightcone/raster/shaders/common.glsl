// Shared by every stage. Each function mirrors one C++ kernel (named beside it) and is tested
// against it (tests/test_raster.cpp). Written for GLSL 330 core and GLSL ES 3.00 alike: the
// program prepends only the version line (for ES also the precision line) and, for fragment
// shaders, the definition of LIGHTCONE_FRAGMENT_STAGE.

// physics/retarded_time.cpp, retarded_delay: the root tau >= 0 of |delta - beta tau| = tau, with
// 1 - beta.beta given (computed in double on the CPU, where it does not cancel).
float retarded_delay(vec3 delta, vec3 beta, float one_minus_beta2) {
  float bd = dot(beta, delta);
  float d2 = dot(delta, delta);
  float root = sqrt(bd * bd + one_minus_beta2 * d2);
  if (bd > 0.0) return d2 / (bd + root);
  return (root - bd) / one_minus_beta2;
}

// frame/resolved_scene.cpp, meet_world_line: the event on the ray family s (ray_time, u) that
// lies on the world-line position_at_zero + velocity t; returns (position in F, s).
vec4 meet_world_line(float ray_time, vec3 position_at_zero, vec3 velocity,
                     float one_minus_beta2) {
  if (ray_time == 0.0) return vec4(position_at_zero, length(position_at_zero));
  float tau = retarded_delay(position_at_zero, velocity, one_minus_beta2);
  return vec4(position_at_zero - velocity * tau, tau);
}

// physics/doppler.cpp, doppler_factor, for a receiver at rest in F: D = (k.U_R) / (k.U_E) with
// k = (1, n), n = -u the direction the light travels, U_E = gamma (1, beta).
float doppler_factor(vec3 u, vec3 beta, float gamma) {
  return 1.0 / (gamma * (1.0 + dot(beta, u)));
}

// The camera's ray family s (ray_time, u): -1 the backward null rays, 0 the simultaneous
// picture (frame/resolved_scene.hpp).
uniform float ray_time;

// The camera's pinhole (frame/camera_model.cpp).
uniform vec3 camera_forward;
uniform vec3 camera_right;
uniform vec3 camera_up;
uniform vec2 camera_tan_half;  // (tan_half_fov * aspect, tan_half_fov)
uniform vec2 image_size;       // pixels
uniform vec2 pixel_offset;     // this pass's sample offset within the pixel, in pixels

// look_direction for image point (x, y), y down from the top.
vec3 look_direction(vec2 p) {
  float a = (2.0 * p.x / image_size.x - 1.0) * camera_tan_half.x;
  float c = (1.0 - 2.0 * p.y / image_size.y) * camera_tan_half.y;
  return normalize(camera_forward + camera_right * a + camera_up * c);
}

#ifdef LIGHTCONE_FRAGMENT_STAGE
// Where in its pixel a fragment is shaded: the pass's offset, or (for many samples a pixel)
// the ray tracer's own sample position for this pixel and pass (frame/sampler.cpp's
// pixel_sample, tabulated on the CPU), so that both renderers shade the same directions.
uniform int shade_at_sample_offsets;
// Per pixel: the position in the pixel and the point on sphere lights (rg, ba); rows from the
// bottom, as the framebuffer's.
uniform sampler2D sample_offsets;

// The fragment's look direction through its shading position.
vec3 fragment_look_direction() {
  vec2 offset = shade_at_sample_offsets == 1
                    ? texelFetch(sample_offsets, ivec2(gl_FragCoord.xy), 0).rg
                    : pixel_offset;
  vec2 p = vec2(floor(gl_FragCoord.x), image_size.y - 1.0 - floor(gl_FragCoord.y)) + offset;
  return look_direction(p);
}

// The fragment's point on sphere lights (one sample a pixel: the same for every pixel).
vec2 fragment_light_sample() {
  return shade_at_sample_offsets == 1 ? texelFetch(sample_offsets, ivec2(gl_FragCoord.xy), 0).ba
                                      : vec2(0.5);
}
#endif

// Received colour against ln D, one row per fixed emission, tabulated on the CPU from
// frame/received_colour.cpp's received_colour (so every colour and searchlight model is that
// one function), read with linear interpolation between nodes.
uniform sampler2D colour_rows;
uniform float log_doppler_first;  // ln D of the first node
uniform float log_doppler_step;

vec3 received_colour(int row, float d) {
  float x = (log(d) - log_doppler_first) / log_doppler_step;
  float last = float(textureSize(colour_rows, 0).x - 1);
  x = clamp(x, 0.0, last);
  float i = min(floor(x), last - 1.0);
  vec3 a = texelFetch(colour_rows, ivec2(int(i), row), 0).rgb;
  vec3 b = texelFetch(colour_rows, ivec2(int(i) + 1, row), 0).rgb;
  return mix(a, b, x - i);
}
