// Where a body's shape points are seen and drawn: the tessellation shaders (on the GPU) carry
// shape points to their events; every vertex shader projects events (vertices tessellated on
// the CPU arrive as events: body.vert).
// The body's map from shape coordinates to its world-line in F:
// position_at_zero = shape_to_trace * (shape - shape_origin), velocity as given.
uniform mat3 shape_to_trace;
uniform vec3 shape_origin;
uniform vec3 world_line_velocity;
uniform float one_minus_beta2;
uniform vec2 depth_range;  // (ln near, ln far) of the light travel distance

// The depth of light travel distance s: on a log scale between the ends of depth_range, shared
// with the fragment shader, which writes the exact depth of its own surface point.
float depth_of(float s) {
  return (log(max(s, 1e-30)) - depth_range.x) / (depth_range.y - depth_range.x);
}

// The apparent position (in F, relative to the camera) of a shape point, and its light travel
// distance: its event on the camera's ray family.
vec4 apparent_event(vec3 shape_position) {
  vec3 at_zero = shape_to_trace * (shape_position - shape_origin);
  return meet_world_line(ray_time, at_zero, world_line_velocity, one_minus_beta2);
}

// The clip-space position of an apparent event; the sample offset shifts the image by a
// fraction of a pixel (the fragment at a pixel's centre shows the image point at pixel_offset
// within it).
vec4 clip_of(vec4 event) {
  vec3 e = event.xyz;
  float forward = dot(e, camera_forward);
  vec2 ndc_shift = vec2(1.0 - 2.0 * pixel_offset.x, 2.0 * pixel_offset.y - 1.0) / image_size;
  vec2 xy = vec2(dot(e, camera_right) / camera_tan_half.x, dot(e, camera_up) / camera_tan_half.y);
  // Depth: the light travel distance s, so that the nearest emission event wins.
  return vec4(xy + ndc_shift * forward, (2.0 * depth_of(event.w) - 1.0) * forward, forward);
}

// frame/camera_model.cpp, project_direction: the image point (pixels) of a direction in front.
vec2 image_point(vec3 e) {
  float f = dot(e, camera_forward);
  float a = dot(e, camera_right) / f, c = dot(e, camera_up) / f;
  return vec2((a / camera_tan_half.x + 1.0) * 0.5 * image_size.x,
              (1.0 - c / camera_tan_half.y) * 0.5 * image_size.y);
}

// raster/tessellation.cpp, edge_error_pixels: how far the apparent midpoint pm of an edge with
// apparent ends pa, pb lies from where the rasteriser draws it, in pixels.
float edge_error_pixels(vec3 pa, vec3 pb, vec3 pm) {
  float ax = camera_tan_half.x, ay = camera_tan_half.y;
  vec3 sides[5] = vec3[5](camera_forward * ax + camera_right, camera_forward * ax - camera_right,
                          camera_forward * ay + camera_up, camera_forward * ay - camera_up,
                          camera_forward);
  for (int k = 0; k < 5; ++k)
    if (dot(pa, sides[k]) < 0.0 && dot(pb, sides[k]) < 0.0 && dot(pm, sides[k]) < 0.0)
      return 0.0;
  vec3 chord_middle = (pa + pb) * 0.5;
  if (dot(chord_middle, camera_forward) > 1e-6 * length(chord_middle) &&
      dot(pm, camera_forward) > 1e-6 * length(pm))
    return distance(image_point(pm), image_point(chord_middle));
  vec3 n = cross(pa, pb);
  float ln = length(n), lm = length(pm);
  if (ln == 0.0 || lm == 0.0) return 0.0;
  return abs(dot(n, pm)) / (ln * lm) * image_size.y / (2.0 * camera_tan_half.y);
}
