// The sky: each sample's look direction mapped into the sky's pattern coordinates through the
// event (ray_time, u), as frame/resolved_scene.hpp's sky_direction does, and received with its
// Doppler factor. Near a black hole (LIGHTCONE_BLACK_HOLE, with black_hole.glsl) the ray is
// followed round the hole instead, to the sky (its direction far away and its shift g), the
// accretion disk or the horizon, as the ray tracer's curved_radiance draws them.
uniform vec3 sky_time_column;
uniform mat3 sky_spatial;
uniform vec3 doppler_velocity;
uniform float doppler_gamma;
uniform int colour_row;
uniform int pattern;  // 0: one colour; 1: grid; 2: image
uniform sampler2D sky_image;
uniform float grid_spacing;     // degrees
uniform float grid_half_width;  // degrees

layout(location = 0) out vec4 colour;

const float kDegrees = 57.29577951308232;

// frame/shading.cpp: the angle's distance, in degrees, to the nearest multiple of the spacing.
float distance_to_grid(float angle, float spacing) {
  float r = mod(abs(angle), spacing);
  return min(r, spacing - r);
}

// frame/shading.cpp, on_grid_line (the latitude as atan rather than asin, the same angle but
// well conditioned near the poles in single precision).
bool on_grid_line(vec3 d) {
  float latitude = kDegrees * atan(d.y, length(d.xz));
  float longitude = kDegrees * atan(d.x, -d.z);
  float along_parallel =
      distance_to_grid(longitude, grid_spacing) * cos(latitude / kDegrees);
  return distance_to_grid(latitude, grid_spacing) <= grid_half_width ||
         along_parallel <= grid_half_width;
}

void main() {
  vec3 u = fragment_look_direction();
#if defined(LIGHTCONE_BLACK_HOLE)
  HoleRay ray = follow_hole_ray(u);
  vec3 d = ray.sky_direction;
  float doppler = ray.shift;
#else
  vec3 d = sky_direction(u, sky_time_column, sky_spatial, ray_time);
  float doppler = doppler_factor(u, doppler_velocity, doppler_gamma);
#endif
  vec3 received;
#if defined(LIGHTCONE_SKY_IMAGE)
  {
    // frame/shading.cpp, sky_image_colour: equirectangular, v from the north pole.
    vec2 uv = vec2(0.5 + atan(d.x, -d.z) / 6.283185307179586,
                   atan(length(d.xz), d.y) / 3.141592653589793);
    vec3 rgb;
    if (shade_at_sample_offsets == 1) {
      // Several samples a pixel: each reads the texel as the ray tracer reads it.
      rgb = sample_bilinear(sky_image, uv, false);
    } else {
      // One sample a pixel (the viewer): the mip level the pixel's footprint needs, from
      // gradients taken across the seam the short way round, so that the sky crowded ahead
      // does not alias.
      vec2 dx = dFdx(uv), dy = dFdy(uv);
      dx.x -= floor(dx.x + 0.5);
      dy.x -= floor(dy.x + 0.5);
      rgb = textureGrad(sky_image, uv, dx, dy).rgb;
    }
    received = received_rgb(rgb, doppler);
  }
#else
  int row = colour_row + (pattern == 1 && on_grid_line(d) ? 1 : 0);
  received = received_colour(row, doppler);
#endif
  // Alpha: whether the sky is seen here (the stars are drawn where it is, star.frag).
  float sky_seen = 1.0;
#if defined(LIGHTCONE_BLACK_HOLE)
  // Chosen after the sky is read everywhere, so that its gradients stay defined.
  if (ray.end == kHoleDisk) received = disk_colour(ray.disk_radius, ray.shift);
  if (ray.end == kHoleHorizon) received = vec3(0.0);
  if (ray.end != kHoleSky) sky_seen = 0.0;
#endif
  colour = vec4(received, sky_seen);
}
