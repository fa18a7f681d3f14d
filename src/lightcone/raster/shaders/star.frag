// A star's flux over the pixels of its sprite: each pixel gets the star's radiance (star.vert)
// times the pixel filter's weight at the pixel's centre (frame/star_field.cpp,
// star_filter_weight: the quadratic B-spline, B(t) = 3/4 - t^2 for |t| <= 1/2, (3/2 - |t|)^2 / 2
// to |t| = 3/2, in each axis; its weights sum to one). The blending multiplies it by the
// fraction of the pixel where the sky is seen (the sky pass's alpha) and adds it.
flat in vec3 star_radiance;
flat in vec2 star_window;

layout(location = 0) out vec4 colour;

void main() {
  vec2 a = abs(gl_FragCoord.xy - star_window);
  vec2 outer = max(vec2(1.5) - a, vec2(0.0));
  vec2 w = mix(0.5 * outer * outer, vec2(0.75) - a * a, lessThanEqual(a, vec2(0.5)));
  colour = vec4(star_radiance * (w.x * w.y), 0.0);
}
