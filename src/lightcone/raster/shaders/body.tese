// The GPU tessellation path: each generated vertex is a point of the triangle (on the sphere
// for a sphere) carried to its apparent event, as body.vert carries a vertex.
layout(triangles, equal_spacing, ccw) in;

in vec3 control_position[];
in vec4 control_plane[];
flat out vec4 plane;
out float vertex_distance;  // its light travel distance, for the fragments of spinning bodies
#if defined(LIGHTCONE_FACE_UVS)
in vec4 control_u[];
in vec4 control_v[];
flat out vec4 uv_u;
flat out vec4 uv_v;
#endif

uniform float sphere_radius_for_tessellation;

void main() {
  vec3 p = gl_TessCoord.x * control_position[0] + gl_TessCoord.y * control_position[1] +
           gl_TessCoord.z * control_position[2];
  if (sphere_radius_for_tessellation > 0.0 && length(p) > 0.0)
    p *= sphere_radius_for_tessellation / length(p);
  vec4 event = apparent_event(p);
  gl_Position = clip_of(event);
  vertex_distance = event.w;
  plane = control_plane[0];
#if defined(LIGHTCONE_FACE_UVS)
  uv_u = control_u[0];
  uv_v = control_v[0];
#endif
}
