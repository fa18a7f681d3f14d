// A star's flux over the pixels of its sprite: each pixel gets flux times the pixel filter's
// weight at its centre (frame/star_field.cpp, star_filter_weight: the quadratic B-spline, whose
// weights sum to one) over the pixel's solid angle. The blending multiplies it by the fraction
// of the pixel where the sky is seen (the sky pass's alpha) and adds it.
flat in vec2 star_window;
flat in vec3 star_flux;


layout(location = 0) out vec4 colour;

float filter_1d(float t) {
  float a = abs(t);
  if (a <= 0.5) return 0.75 - a * a;
  if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
  return 0.0;
}

void main() {
  vec2 d = gl_FragCoord.xy - star_window;
  float weight = filter_1d(d.x) * filter_1d(d.y);
  // The pixel's solid angle: its area on the image plane at unit distance times cos^3 of its
  // angle from the forward direction (the exact rectangle's, frame/star_field.cpp's
  // pixel_solid_angle, to a part in (pixel / focal length)^2).
  vec2 plane = (gl_FragCoord.xy / image_size * 2.0 - 1.0) * camera_tan_half;
  vec2 size = 2.0 * camera_tan_half / image_size;
  float q = 1.0 + dot(plane, plane);
  float solid_angle = size.x * size.y / (q * sqrt(q));
  colour = vec4(star_flux * (weight / solid_angle), 0.0);
}
