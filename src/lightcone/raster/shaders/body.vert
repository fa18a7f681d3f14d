// Each vertex of a body, given in its shape coordinates, is carried to the event where the ray
// family of the camera meets its world-line (the exact retarded event for light delay on) and
// projected from there: aberration, light delay and Lorentz contraction all follow from the
// body's world-line in the camera's rest frame F, computed per frame in double precision.
layout(location = 0) in vec3 shape_position;
// The plane of the (untessellated) face the vertex belongs to, in shape coordinates: normal and
// offset (n.p = offset), for the fragments' exact surface points.
layout(location = 1) in vec4 face_plane;

// The body's map from shape coordinates to its world-line in F:
// position_at_zero = shape_to_trace * (shape - shape_origin), velocity as given.
uniform mat3 shape_to_trace;
uniform vec3 shape_origin;
uniform vec3 world_line_velocity;
uniform float one_minus_beta2;
uniform vec2 depth_range;  // (ln near, ln far) of the light travel distance

flat out vec4 plane;

// The depth of light travel distance s: on a log scale between the ends of depth_range, shared
// with the fragment shader, which writes the exact depth of its own surface point.
float depth_of(float s) {
  return (log(max(s, 1e-30)) - depth_range.x) / (depth_range.y - depth_range.x);
}

void main() {
  vec3 at_zero = shape_to_trace * (shape_position - shape_origin);
  vec4 event = meet_world_line(ray_time, at_zero, world_line_velocity, one_minus_beta2);
  vec3 e = event.xyz;
  float forward = dot(e, camera_forward);
  // The sample offset shifts the image by a fraction of a pixel.
  // (The fragment at a pixel's centre shows the image point at pixel_offset within it.)
  vec2 ndc_shift = vec2(1.0 - 2.0 * pixel_offset.x, 2.0 * pixel_offset.y - 1.0) / image_size;
  vec2 xy = vec2(dot(e, camera_right) / camera_tan_half.x, dot(e, camera_up) / camera_tan_half.y);
  // Depth: the light travel distance s, so that the nearest emission event wins.
  gl_Position = vec4(xy + ndc_shift * forward, (2.0 * depth_of(event.w) - 1.0) * forward, forward);
  plane = face_plane;
}
