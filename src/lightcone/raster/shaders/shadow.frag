// A shadow map's depth: the distance from the light in its rest frame, over the map's far
// distance (lighting.glsl's shadowed() reads it back). A sphere is drawn as its bounding box and
// met exactly here, so that its shadow is round, as the tracer's is.
in vec3 from_light;

uniform float far_distance;
uniform float sphere_radius;  // > 0: the body is that sphere (in its shape coordinates)
uniform mat3 light_to_shape;  // the inverse of shadow.vert's shape_to_light
uniform vec3 body_offset;

void main() {
  float distance = length(from_light);
  if (sphere_radius > 0.0) {
    // The ray from the light along this direction, in the sphere's shape coordinates.
    vec3 d = light_to_shape * (from_light / distance), o = light_to_shape * -body_offset;
    float a = dot(d, d), b = dot(o, d), c = dot(o, o) - sphere_radius * sphere_radius;
    float disc = b * b - a * c;
    if (disc < 0.0) discard;
    float root = sqrt(disc);
    float t = (-b - root) / a;
    if (t < 0.0) t = (-b + root) / a;
    if (t < 0.0) discard;
    distance = t;
  }
  gl_FragDepth = clamp(distance / far_distance, 0.0, 1.0);
}
