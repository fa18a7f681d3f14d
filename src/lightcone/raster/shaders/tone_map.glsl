// Tone curves, the mirror of frame/tone_map.cpp (tested against it): linear radiance after
// exposure to display-referred values in [0, 1]. curve 0: clamp; 1: reinhard; 2: filmic.

float tone_luminance(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// filmic_curve.
float filmic_curve(float y) {
  y = max(y, 0.0);
  return min(1.0, y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14));
}

// filmic_on_luminance: the curve on the luminance, bounded by the curve on the largest channel.
vec3 filmic_on_luminance(vec3 c) {
  c = max(c, vec3(0.0));
  float y = tone_luminance(c), top = max(c.r, max(c.g, c.b));
  if (!(y > 0.0)) return vec3(0.0);
  return clamp(c * min(filmic_curve(y) / y, filmic_curve(top) / top), 0.0, 1.0);
}

vec3 tone_map(vec3 c, int curve) {
  if (curve == 1) return clamp(c / (1.0 + max(0.0, tone_luminance(c))), 0.0, 1.0);
  if (curve == 2) return filmic_on_luminance(c);
  return clamp(c, 0.0, 1.0);
}
