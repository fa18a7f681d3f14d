// The GPU tessellation path: vertices pass to the tessellation shaders untouched.
layout(location = 0) in vec3 shape_position;
layout(location = 1) in vec4 face_plane;

out vec3 patch_position;
out vec4 patch_plane;

void main() {
  patch_position = shape_position;
  patch_plane = face_plane;
}
