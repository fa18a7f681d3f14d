// A star's flux over the pixels of its sprite: each pixel gets the flux times the pixel filter's
// weight at the pixel's centre (star_filter.glsl) over the pixel's solid angle: its area on the
// image plane at unit distance times cos^3 of its angle from the forward direction (the exact
// rectangle's, frame/star_field.cpp's pixel_solid_angle, to a part in (pixel / focal
// length)^2). The blending multiplies it by the fraction of the pixel where the sky is seen (the
// sky pass's alpha) and adds it.
flat in vec3 star_radiance;  // the flux over a pixel's area on the image plane
flat in vec2 star_window;

layout(location = 0) out vec4 colour;

void main() {
  float weight = star_filter_weight(gl_FragCoord.xy - star_window);
  vec2 plane = (gl_FragCoord.xy / image_size * 2.0 - 1.0) * camera_tan_half;
  float q = 1.0 + dot(plane, plane);
  colour = vec4(star_radiance * (weight * q * sqrt(q)), 0.0);
}
