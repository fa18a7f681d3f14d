#include "lightcone/raster/baseline_pass.hpp"

#include <cmath>

#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/tessellation.hpp"

namespace lightcone {

BaselinePass::BaselinePass() {
  program_ = link_program(vertex_shader(shader_sources::baseline_vert),
                          fragment_shader(shader_sources::baseline_frag));
}

BaselinePass::~BaselinePass() {
  glDeleteProgram(program_);
}

std::size_t BaselinePass::draw(const ResolvedScene& scene, const RasterRenderer& renderer) const {
  const RasterRenderer::TessellatedBodies bodies = renderer.tessellated_bodies();
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glUseProgram(program_);
  set_camera_uniforms(program_, scene.camera);
  glUniform2f(uniform(program_, "depth_range"), static_cast<float>(std::log(kDepthNear)),
              static_cast<float>(std::log(kDepthFar)));
  glBindVertexArray(bodies.vertex_array);
  glBindBuffer(GL_ARRAY_BUFFER, bodies.vertex_buffer);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE,
                        static_cast<GLsizei>(bodies.floats_per_vertex * sizeof(float)), nullptr);
  std::size_t triangles = 0;
  for (const RasterRenderer::TessellatedBodies::Draw& d : bodies.draws) {
    skip_faces(d.hidden);  // the frame's own culling, so that both rasterise the same faces
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(d.first_vertex),
                 static_cast<GLsizei>(d.vertex_count));
    triangles += d.vertex_count / 3;
  }
  skip_faces(HiddenFaces::kNone);
  check_gl("drawing the baseline");
  return triangles;
}

}  // namespace lightcone
