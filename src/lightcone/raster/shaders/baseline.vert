// The pass-through baseline (raster/baseline_pass.hpp): a body's tessellated vertex where the
// frame draws it, projected by the camera's pinhole, nothing more: what the same triangles cost
// a GL driver without the renderer's per-fragment work.
layout(location = 0) in vec3 apparent_position;

void main() {
  gl_Position = clip_of(vec4(apparent_position, length(apparent_position)));
}
