// How the raster renderer's programs are put together from the embedded sources: a version line,
// the shared code (common.glsl, and for vertices where bodies are seen, body_projection.glsl),
// then the stage's own source.
#pragma once

#include <string>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

// GLSL 330 for the CPU tessellation path, 400 for the GPU one (tessellation shaders); in the
// browser, GLSL ES 3.00 (WebGL 2), which the shaders are also written in (tests/test_raster.cpp).
inline std::string version_line(bool tessellation) {
#ifdef __EMSCRIPTEN__
  (void)tessellation;
  return "#version 300 es\nprecision highp float;\nprecision highp int;\n"
         "precision highp sampler2D;\n";
#else
  return tessellation ? "#version 400 core\n" : "#version 330 core\n";
#endif
}
inline std::string vertex_shader(const char* source, bool tessellation = false,
                                 const std::string& defines = "") {
  return version_line(tessellation) + defines + shader_sources::common_glsl +
         shader_sources::body_projection_glsl + source;
}
inline std::string fragment_shader(const char* source, const std::string& extra = "",
                                   const char* defines = "", bool tessellation = false) {
  return version_line(tessellation) + "#define LIGHTCONE_FRAGMENT_STAGE 1\n" + defines +
         shader_sources::common_glsl + extra + source;
}

// common.glsl's pinhole uniforms on `program` (in use): the camera's axes, its half-field
// tangents, the image size, and this pass's sample offset within each pixel.
inline void set_camera_uniforms(GLuint program, const CameraBasis& c, double offset_x = 0.5,
                                double offset_y = 0.5) {
  set_vec3(program, "camera_forward", c.forward);
  set_vec3(program, "camera_right", c.right);
  set_vec3(program, "camera_up", c.up);
  glUniform2f(uniform(program, "camera_tan_half"), static_cast<float>(c.tan_half_fov * c.aspect),
              static_cast<float>(c.tan_half_fov));
  glUniform2f(uniform(program, "image_size"), static_cast<float>(c.width),
              static_cast<float>(c.height));
  glUniform2f(uniform(program, "pixel_offset"), static_cast<float>(offset_x),
              static_cast<float>(offset_y));
}

// What a body program and the lighting pass may leave out when no body of the frame uses it
// (shaders/body.frag, lit_surfaces.frag, patterns.glsl, common.glsl): spinning bodies, blinks
// and clocks, shading at per-pixel sample offsets (several samples a pixel), the hue model's law
// (received_rgb), shadows (lighting.glsl), lit textures (and their spectral fit), clocks on
// meshes (their faces' texture maps), and the shadows of meshes and of spinning bodies met
// exactly. The defines take out those a frame does not use.
enum BodyFeature {
  kBodySpin = 1,
  kBodyTimedPattern = 2,
  kBodySampleOffsets = 4,
  kBodyHueModel = 8,
  kBodyShadows = 16,
  kBodyLitTextures = 32,
  kBodyMeshClocks = 64,
  kBodySpectralTextures = 128,
  kBodyMeshShadows = 256,
  kBodySpinShadows = 512,
  kAllBodyFeatures = 1023,
};
inline std::string body_variant_defines(int features) {
  std::string defines;
  if (!(features & kBodySpin)) defines += "#define LIGHTCONE_NO_SPIN 1\n";
  if (!(features & kBodyTimedPattern)) defines += "#define LIGHTCONE_NO_TIMED_PATTERNS 1\n";
  if (!(features & kBodySampleOffsets)) defines += "#define LIGHTCONE_NO_SAMPLE_OFFSETS 1\n";
  if (!(features & kBodyHueModel)) defines += "#define LIGHTCONE_NO_HUE 1\n";
  if (!(features & kBodyShadows)) defines += "#define LIGHTCONE_NO_SHADOWS 1\n";
  if (features & kBodyLitTextures) defines += "#define LIGHTCONE_LIT_TEXTURES 1\n";
  if (features & kBodyMeshClocks) defines += "#define LIGHTCONE_MESH_CLOCKS 1\n";
  if (features & kBodySpectralTextures) defines += "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n";
  if (features & kBodyMeshShadows) defines += "#define LIGHTCONE_MESH_SHADOWS 1\n";
  if (features & kBodySpinShadows) defines += "#define LIGHTCONE_SPIN_SHADOWS 1\n";
  return defines;
}

// What the lighting pass may also leave out (lighting.glsl): each kind of light but the point
// light where the frame has none, the glossy lobe where no lit body is glossy, under the
// spectral model the tables of lights moving relative to the bodies they light, and the
// velocities of lights and of lit surfaces where all are at rest in W (the laws then fold to
// their forms for beta = 0, which give the same values); and the table of lights in a texture,
// which only frames with more lights than kUniformLamps need.
inline constexpr int kUniformLamps = 16;  // lighting.glsl's lamp_texels
enum LightingFeature {
  kLightingSpot = 1,
  kLightingSun = 2,
  kLightingSphere = 4,
  kLightingGlossy = 8,
  kLightingMovingReflections = 16,
  kLightingMovingLights = 32,
  kLightingMovingSurfaces = 64,
  kLightingManyLights = 128,
  kAllLightingFeatures = 255,
};
inline std::string lighting_variant_defines(int features) {
  std::string defines;
  if (features & kLightingSpot) defines += "#define LIGHTCONE_SPOT_LIGHTS 1\n";
  if (features & kLightingSun) defines += "#define LIGHTCONE_SUN_LIGHTS 1\n";
  if (features & kLightingSphere) defines += "#define LIGHTCONE_SPHERE_LIGHTS 1\n";
  if (features & kLightingGlossy) defines += "#define LIGHTCONE_GLOSSY 1\n";
  if (features & kLightingMovingReflections)
    defines += "#define LIGHTCONE_MOVING_LIGHT_REFLECTIONS 1\n";
  if (features & kLightingMovingLights) defines += "#define LIGHTCONE_MOVING_LIGHTS 1\n";
  if (features & kLightingMovingSurfaces) defines += "#define LIGHTCONE_MOVING_SURFACES 1\n";
  if (features & kLightingManyLights) defines += "#define LIGHTCONE_MANY_LIGHTS 1\n";
  return defines;
}

}  // namespace lightcone
