// How the raster renderer's programs are put together from the embedded sources: a version line,
// the shared code (common.glsl, and for vertices where bodies are seen, body_projection.glsl),
// then the stage's own source.
#pragma once

#include <cstddef>
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
// A feature's define in a program's source: `name` where the frame has the feature (or, for
// `absent`, where it has not).
struct FeatureDefine {
  int feature;
  const char* name;
  bool absent = false;
};
template <std::size_t N>
std::string variant_defines(int features, const FeatureDefine (&table)[N]) {
  std::string defines;
  for (const FeatureDefine& d : table)
    if (((features & d.feature) != 0) != d.absent)
      defines += std::string("#define ") + d.name + " 1\n";
  return defines;
}

inline std::string body_variant_defines(int features) {
  static constexpr FeatureDefine kDefines[] = {
      {kBodySpin, "LIGHTCONE_NO_SPIN", true},
      {kBodyTimedPattern, "LIGHTCONE_NO_TIMED_PATTERNS", true},
      {kBodySampleOffsets, "LIGHTCONE_NO_SAMPLE_OFFSETS", true},
      {kBodyHueModel, "LIGHTCONE_NO_HUE", true},
      {kBodyShadows, "LIGHTCONE_NO_SHADOWS", true},
      {kBodyLitTextures, "LIGHTCONE_LIT_TEXTURES"},
      {kBodyMeshClocks, "LIGHTCONE_MESH_CLOCKS"},
      {kBodySpectralTextures, "LIGHTCONE_SPECTRAL_TEXTURES"},
      {kBodyMeshShadows, "LIGHTCONE_MESH_SHADOWS"},
      {kBodySpinShadows, "LIGHTCONE_SPIN_SHADOWS"}};
  return variant_defines(features, kDefines);
}

// What the lighting pass may also leave out (lighting.glsl): each kind of light but the point
// light where the frame has none, the glossy lobe where no lit body is glossy, under the
// spectral model the tables of lights moving relative to the bodies they light, and the
// velocities of lights and of lit surfaces where all are at rest in W (the laws then fold to
// their forms for beta = 0, which give the same values); the table of lights in a texture,
// which only frames with more lights than kUniformLamps need; the shadow rays met against
// bodies exactly, which only frames with such casters (raster/shadow_casters.hpp) need; and the
// code of the colour models a frame does not use (a program with both reads the uniform
// `spectral`).
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
  kLightingExactShadows = 256,
  kLightingSpectralModel = 512,
  kLightingOtherModels = 1024,
  kAllLightingFeatures = 2047,
};
inline std::string lighting_variant_defines(int features) {
  static constexpr FeatureDefine kDefines[] = {
      {kLightingSpot, "LIGHTCONE_SPOT_LIGHTS"},
      {kLightingSun, "LIGHTCONE_SUN_LIGHTS"},
      {kLightingSphere, "LIGHTCONE_SPHERE_LIGHTS"},
      {kLightingGlossy, "LIGHTCONE_GLOSSY"},
      {kLightingMovingReflections, "LIGHTCONE_MOVING_LIGHT_REFLECTIONS"},
      {kLightingMovingLights, "LIGHTCONE_MOVING_LIGHTS"},
      {kLightingMovingSurfaces, "LIGHTCONE_MOVING_SURFACES"},
      {kLightingManyLights, "LIGHTCONE_MANY_LIGHTS"},
      {kLightingExactShadows, "LIGHTCONE_EXACT_SHADOWS"},
      {kLightingSpectralModel, "LIGHTCONE_SPECTRAL_MODEL"},
      {kLightingOtherModels, "LIGHTCONE_OTHER_MODELS"}};
  return variant_defines(features, kDefines);
}

}  // namespace lightcone
