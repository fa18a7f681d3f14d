// The GPU tessellation path (OpenGL 4): each edge of a triangle is cut into as many equal
// pieces as its apparent curvature needs, by the CPU path's measure: an edge whose midpoint
// lies e pixels from where the rasteriser draws it bends like a conic, so n pieces leave about
// e / n^2, and n = ceil(sqrt(e / max_error)) keeps within max_error. The curvature need not be
// even along the edge (the end nearer the camera spreads over more pixels), so each half is
// measured too, and needs twice its own count. The measure depends only on the edge's ends, so
// neighbouring triangles cut a shared edge alike (no cracks).
layout(vertices = 3) out;

in vec3 patch_position[];
in vec4 patch_plane[];
out vec3 control_position[];
out vec4 control_plane[];
#if defined(LIGHTCONE_FACE_UVS)
in vec4 patch_u[];
in vec4 patch_v[];
out vec4 control_u[];
out vec4 control_v[];
#endif

uniform float sphere_radius_for_tessellation;  // > 0: the shape is that sphere
uniform float max_error_pixels;
uniform float max_level;

// raster/tessellation.cpp, RestMesh::midpoint.
vec3 shape_midpoint(vec3 a, vec3 b) {
  vec3 m = (a + b) * 0.5;
  if (sphere_radius_for_tessellation <= 0.0) return m;
  float l = length(m);
  return l > 0.0 ? m * (sphere_radius_for_tessellation / l) : m;
}

float edge_level(vec3 a, vec3 b) {
  vec3 m = shape_midpoint(a, b);
  vec3 pa = apparent_event(a).xyz, pb = apparent_event(b).xyz, pm = apparent_event(m).xyz;
  float whole = edge_error_pixels(pa, pb, pm);
  float first = edge_error_pixels(pa, pm, apparent_event(shape_midpoint(a, m)).xyz);
  float second = edge_error_pixels(pm, pb, apparent_event(shape_midpoint(m, b)).xyz);
  float pieces = max(sqrt(whole / max_error_pixels),
                     2.0 * sqrt(max(first, second) / max_error_pixels));
  return clamp(ceil(pieces), 1.0, max_level);
}

void main() {
  control_position[gl_InvocationID] = patch_position[gl_InvocationID];
  control_plane[gl_InvocationID] = patch_plane[gl_InvocationID];
#if defined(LIGHTCONE_FACE_UVS)
  control_u[gl_InvocationID] = patch_u[gl_InvocationID];
  control_v[gl_InvocationID] = patch_v[gl_InvocationID];
#endif
  if (gl_InvocationID == 0) {
    // Outer level i is the edge opposite vertex i.
    gl_TessLevelOuter[0] = edge_level(patch_position[1], patch_position[2]);
    gl_TessLevelOuter[1] = edge_level(patch_position[2], patch_position[0]);
    gl_TessLevelOuter[2] = edge_level(patch_position[0], patch_position[1]);
    gl_TessLevelInner[0] =
        max(gl_TessLevelOuter[0], max(gl_TessLevelOuter[1], gl_TessLevelOuter[2]));
  }
}
