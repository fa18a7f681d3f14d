// The stars' pixel filter (frame/star_field.cpp, star_filter_weight): the quadratic B-spline
// B(dx) B(dy) at offset d from a star's image point, B(t) = 3/4 - t^2 for |t| <= 1/2,
// (3/2 - |t|)^2 / 2 to |t| = 3/2, else 0; its weights over the pixel centres sum to one.
float star_filter_weight(vec2 d) {
  vec2 a = abs(d);
  vec2 outer = max(vec2(1.5) - a, vec2(0.0));
  vec2 w = mix(0.5 * outer * outer, vec2(0.75) - a * a, lessThanEqual(a, vec2(0.5)));
  return w.x * w.y;
}
