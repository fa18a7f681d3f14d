// A star's flux over the pixels of its sprite: each pixel gets the flux times the pixel filter's
// weight at the pixel's centre over the pixel's solid angle (frame/star_field.cpp,
// star_filter_weight: the quadratic B-spline, B(t) = 3/4 - t^2 for |t| <= 1/2, (3/2 - |t|)^2 / 2
// to |t| = 3/2, in each axis; its weights sum to one). The solid angle is the pixel's area on
// the image plane at unit distance times cos^3 of its angle from the forward direction (the
// exact rectangle's, frame/star_field.cpp's pixel_solid_angle, to a part in (pixel / focal
// length)^2). The blending multiplies it by the
// fraction of the pixel where the sky is seen (the sky pass's alpha) and adds it.
flat in vec3 star_radiance;  // the flux over a pixel's area on the image plane
flat in vec2 star_window;

layout(location = 0) out vec4 colour;

void main() {
  vec2 a = abs(gl_FragCoord.xy - star_window);
  vec2 outer = max(vec2(1.5) - a, vec2(0.0));
  vec2 w = mix(0.5 * outer * outer, vec2(0.75) - a * a, lessThanEqual(a, vec2(0.5)));
  vec2 plane = (gl_FragCoord.xy / image_size * 2.0 - 1.0) * camera_tan_half;
  float q = 1.0 + dot(plane, plane);
  colour = vec4(star_radiance * (w.x * w.y * q * sqrt(q)), 0.0);
}
