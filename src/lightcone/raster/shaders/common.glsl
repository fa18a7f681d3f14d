// Shared by every stage. Each function mirrors one C++ kernel (named beside it) and is tested
// against it (tests/test_raster.cpp). Written for GLSL 330 core and GLSL ES 3.00 alike: the
// program prepends only the version line (for ES also the precision line) and, for fragment
// shaders, the definition of LIGHTCONE_FRAGMENT_STAGE.

// Textured bodies, unlit or lit (LIGHTCONE_LIT_TEXTURES), and clocks on meshes
// (LIGHTCONE_MESH_CLOCKS) carry their mesh faces' texture maps.
#if defined(LIGHTCONE_TEXTURED) || defined(LIGHTCONE_LIT_TEXTURES) || defined(LIGHTCONE_MESH_CLOCKS)
#define LIGHTCONE_FACE_UVS 1
#endif

// v turned by `angle` about the unit `axis` (physics/vec.hpp, rotated).
vec3 turned(vec3 axis, float angle, vec3 v) {
  float c = cos(angle), s = sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0 - c));
}

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

// frame/received_colour.cpp, spectral_searchlight: the factor on spectral radiance for model
// 0 (physical, D^5), 1 (Chang et al. 1996, D) or 2 (off).
float spectral_searchlight(float d, int model) {
  if (model == 0) return d * d * d * d * d;
  if (model == 1) return d;
  return 1.0;
}

// frame/received_colour.cpp, integrated_searchlight: the factor on radiance integrated over
// wavelength, for the same models (physical: D^4).
float integrated_searchlight(float d, int model) {
  if (model == 0) return d * d * d * d;
  if (model == 1) return d;
  return 1.0;
}

// color/colour_models.cpp, hsv_from_rgb and rgb_from_hsv (h in degrees).
vec3 hsv_from_rgb(vec3 c) {
  float hi = max(c.r, max(c.g, c.b)), lo = min(c.r, min(c.g, c.b));
  float delta = hi - lo;
  if (hi <= 0.0 || delta <= 0.0) return vec3(0.0, 0.0, hi);  // grey: hue 0, saturation 0
  float h;
  if (c.r == hi)
    h = (c.g - c.b) / delta;
  else if (c.g == hi)
    h = 2.0 + (c.b - c.r) / delta;
  else
    h = 4.0 + (c.r - c.g) / delta;
  h *= 60.0;
  return vec3(h < 0.0 ? h + 360.0 : h, delta / hi, hi);
}
vec3 rgb_from_hsv(vec3 hsv) {
  float v = hsv.z, s = hsv.y;
  if (s == 0.0) return vec3(v);
  float h = hsv.x / 60.0;
  float sector = floor(h);
  float f = h - sector;
  float p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
  int k = int(sector);
  if (k == 0) return vec3(v, t, p);
  if (k == 1) return vec3(q, v, p);
  if (k == 2) return vec3(p, v, t);
  if (k == 3) return vec3(p, q, v);
  if (k == 4) return vec3(t, p, v);
  return vec3(v, p, q);
}

// color/colour_models.cpp, hue_shift: H += 512 log2(d) degrees; outside [0, 300] the value
// fades to black over 60 degrees, or with `loop` H wraps around 360.
vec3 hue_shift(vec3 rgb, float d, bool loop) {
  vec3 c = hsv_from_rgb(rgb);
  c.x += 512.0 * log2(d);
  if (loop) {
    c.x = mod(c.x, 360.0);
    if (c.x >= 360.0) c.x -= 360.0;  // mod of a tiny negative angle rounds up to 360
  } else if (c.x > 300.0) {
    c.z *= 1.0 - (min(c.x, 360.0) - 300.0) / 60.0;
    c.x = 300.0;
  } else if (c.x < 0.0) {
    c.z *= (max(c.x, -60.0) + 60.0) / 60.0;
    c.x = 0.0;
  }
  return rgb_from_hsv(c);
}

// frame/resolved_scene.hpp, sky_direction: the direction in the sky's pattern coordinates of
// the ray event (ray_time, u).
vec3 sky_direction(vec3 u, vec3 time_column, mat3 spatial, float ray_time_of_rays) {
  return normalize(time_column * ray_time_of_rays + spatial * u);
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
#if defined(LIGHTCONE_NO_SAMPLE_OFFSETS)  // one sample a pixel
  vec2 offset = pixel_offset;
#else
  vec2 offset = shade_at_sample_offsets == 1
                    ? texelFetch(sample_offsets, ivec2(gl_FragCoord.xy), 0).rg
                    : pixel_offset;
#endif
  vec2 p = vec2(floor(gl_FragCoord.x), image_size.y - 1.0 - floor(gl_FragCoord.y)) + offset;
  return look_direction(p);
}

// The fragment's point on sphere lights (one sample a pixel: the same for every pixel).
vec2 fragment_light_sample() {
#if defined(LIGHTCONE_NO_SAMPLE_OFFSETS)
  return vec2(0.5);
#else
  return shade_at_sample_offsets == 1 ? texelFetch(sample_offsets, ivec2(gl_FragCoord.xy), 0).ba
                                      : vec2(0.5);
#endif
}
#endif

// Received colour against ln D, one row per fixed emission, tabulated on the CPU from
// frame/received_colour.cpp's received_colour (so every colour and searchlight model is that
// one function), read with linear interpolation between nodes.
uniform sampler2D colour_rows;
uniform float log_doppler_first;  // ln D of the first node
uniform float log_doppler_step;

// Where factor d falls between the rows' nodes: the node below it and the fraction past it
// (found once for the rows a sample reads with one factor).
struct ColourNode {
  int below;
  float past;
};
ColourNode colour_node(float d) {
  float x = (log(d) - log_doppler_first) / log_doppler_step;
  float last = float(textureSize(colour_rows, 0).x - 1);
  x = clamp(x, 0.0, last);
  float i = min(floor(x), last - 1.0);
  return ColourNode(int(i), x - i);
}
vec3 received_colour_at(int row, ColourNode node) {
  vec3 a = texelFetch(colour_rows, ivec2(node.below, row), 0).rgb;
  vec3 b = texelFetch(colour_rows, ivec2(node.below + 1, row), 0).rgb;
  return mix(a, b, node.past);
}
vec3 received_colour(int row, float d) {
  return received_colour_at(row, colour_node(d));
}

// Colours looked up per sample (textures, sky images, lit surfaces' outgoing radiance),
// received with factor d. The spectral model: color/rgb_spectrum.cpp's
// RgbEmitterSpectrum::from_rgb (a grey part of the RGB white, and a blend of two emitter
// nodes), each part's row tabulated from its table; the hue model, not linear in the colour:
// frame/received_colour.cpp's law itself; the others are linear in the colour, so the received
// colour is that of the three primaries, weighted.
// `spectral`: 1 for the spectral model, else 0; a constant in programs built for one model
// (shader_build.hpp's lighting_variant_defines).
#if defined(LIGHTCONE_SPECTRAL_MODEL) && !defined(LIGHTCONE_OTHER_MODELS)
const int spectral = 1;
#elif defined(LIGHTCONE_OTHER_MODELS) && !defined(LIGHTCONE_SPECTRAL_MODEL)
const int spectral = 0;
#else
uniform int spectral;
#endif
uniform int hue_model;        // 1: the hue model, 2: the same with the hue wrapping (hue_loop)
uniform int hue_searchlight;  // its searchlight model, as integrated_searchlight's
uniform int primary_rows[3];
uniform int basis_first_row;  // the white's row, then 6 x 64 emitter nodes' (case-major)
uniform vec3 reference_white;

vec3 received_rgb(vec3 rgb, float d) {
  vec3 c = max(rgb, vec3(0.0));
#if !defined(LIGHTCONE_NO_HUE)  // (a frame under another model leaves it out)
  if (hue_model > 0)
    return hue_shift(c, d, hue_model == 2) * integrated_searchlight(d, hue_searchlight);
#endif
  ColourNode d_node = colour_node(d);
  if (spectral == 0)
    return c.r * received_colour_at(primary_rows[0], d_node) +
           c.g * received_colour_at(primary_rows[1], d_node) +
           c.b * received_colour_at(primary_rows[2], d_node);
  float grey = min(c.r, min(c.g, c.b));
  vec3 result = grey > 0.0 ? grey * received_colour_at(basis_first_row, d_node) : vec3(0.0);
  vec3 q = (c - vec3(grey)) / reference_white;
  int l = 0;
  if (q.y > q[l]) l = 1;
  if (q.z > q[l]) l = 2;
  if (!(q[l] > 0.0)) return result;
  int m1 = (l + 1) % 3, m2 = (l + 2) % 3;
  int m = q[m2] > q[m1] ? m2 : m1;
  float scale = 2.0 * q[l];
  int node_case = 2 * l + (m == (l + 1) % 3 ? 0 : 1);  // rgb_emitter_case
  float position = min(q[m] / q[l], 1.0) * 63.0;
  int node = min(int(position), 62);
  float blend = position - float(node);
  int row = basis_first_row + 1 + 64 * node_case + node;
  return result + scale * ((1.0 - blend) * received_colour_at(row, d_node) +
                           blend * received_colour_at(row + 1, d_node));
}

// frame/shading.cpp, sample_bilinear: texel centres at ((i + .5)/w, (j + .5)/h); u wraps, v
// wraps or clamps. The image holds linear RGB, rows from the top.
vec3 texel(sampler2D image, ivec2 size, int i, int j, bool wrap_v) {
  i = ((i % size.x) + size.x) % size.x;
  j = wrap_v ? ((j % size.y) + size.y) % size.y : clamp(j, 0, size.y - 1);
  return texelFetch(image, ivec2(i, j), 0).rgb;
}
vec3 sample_bilinear(sampler2D image, vec2 uv, bool wrap_v) {
  ivec2 size = textureSize(image, 0);
  // The wrap is taken first, so that large u and v keep their precision.
  vec2 at = vec2(fract(uv.x), wrap_v ? fract(uv.y) : uv.y) * vec2(size) - 0.5;
  vec2 f = floor(at);
  int x0 = int(f.x), y0 = int(f.y);
  vec3 top = mix(texel(image, size, x0, y0, wrap_v), texel(image, size, x0 + 1, y0, wrap_v),
                 at.x - f.x);
  vec3 bottom = mix(texel(image, size, x0, y0 + 1, wrap_v),
                    texel(image, size, x0 + 1, y0 + 1, wrap_v), at.x - f.x);
  return mix(top, bottom, at.y - f.y);
}
