// Each vertex of a body tessellated on the CPU arrives seen: its position in the camera's rest
// frame F at the event where the camera's ray family meets the shape point's world-line (the
// exact retarded event for light delay on), which the tessellation computed in double precision
// to decide its splits (raster/tessellation.hpp, apparent_point). It is projected from there:
// aberration, light delay and Lorentz contraction all follow from the body's world-line in F.
layout(location = 0) in vec3 apparent_position;
// The plane of the (untessellated) face the vertex belongs to, in shape coordinates: normal and
// offset (n.p = offset), for the fragments' exact surface points.
layout(location = 1) in vec4 face_plane;

flat out vec4 plane;
out float vertex_distance;  // its light travel distance, for the fragments of spinning bodies
#if defined(LIGHTCONE_FACE_UVS)
// A textured mesh's face: its texture coordinates as an affine map of the shape point (u =
// face_u.xyz . p + face_u.w; raster/tessellation.hpp, triangle_uv_map).
layout(location = 2) in vec4 face_u;
layout(location = 3) in vec4 face_v;
flat out vec4 uv_u;
flat out vec4 uv_v;
#endif

void main() {
  // Its light travel distance: the event lies on the camera's past light cone.
  vec4 event = vec4(apparent_position, length(apparent_position));
  gl_Position = clip_of(event);
  vertex_distance = event.w;
  plane = face_plane;
#if defined(LIGHTCONE_FACE_UVS)
  uv_u = face_u;
  uv_v = face_v;
#endif
}
