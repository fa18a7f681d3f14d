// A shadow map's depth: the distance from the light in its rest frame, over the map's far
// distance (lighting.glsl's shadowed() reads it back).
in vec3 from_light;

uniform float far_distance;

void main() {
  gl_FragDepth = clamp(length(from_light) / far_distance, 0.0, 1.0);
}
