// The GPU tessellation path: vertices pass to the tessellation shaders untouched.
layout(location = 0) in vec3 shape_position;
layout(location = 1) in vec4 face_plane;

out vec3 patch_position;
out vec4 patch_plane;
#if defined(LIGHTCONE_FACE_UVS)
layout(location = 2) in vec4 face_u;  // a textured mesh's face's texture coordinates (body.vert)
layout(location = 3) in vec4 face_v;
out vec4 patch_u;
out vec4 patch_v;
#endif

void main() {
  patch_position = shape_position;
  patch_plane = face_plane;
#if defined(LIGHTCONE_FACE_UVS)
  patch_u = face_u;
  patch_v = face_v;
#endif
}
