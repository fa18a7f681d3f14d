// The sky: each sample's look direction mapped into the sky's pattern coordinates through the
// event (ray_time, u), as frame/resolved_scene.hpp's sky_direction does, and received with its
// Doppler factor.
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
  vec3 d = sky_direction(u, sky_time_column, sky_spatial, ray_time);
  float doppler = doppler_factor(u, doppler_velocity, doppler_gamma);
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
    colour = vec4(received_rgb(rgb, doppler), 1.0);
    return;
  }
#endif
  int row = colour_row + (pattern == 1 && on_grid_line(d) ? 1 : 0);
  colour = vec4(received_colour(row, doppler), 1.0);
}
