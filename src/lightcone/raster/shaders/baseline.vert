// The pass-through baseline (RasterRenderer::baseline_pass): a body's tessellated vertex where
// its world-line is at F's time 0, projected by the camera's pinhole, nothing more: what the
// same triangles cost a GL driver without the light-cone solve.
layout(location = 0) in vec3 shape_position;

void main() {
  vec3 e = shape_to_trace * (shape_position - shape_origin);
  gl_Position = clip_of(vec4(e, length(e)));
}
