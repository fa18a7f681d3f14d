// The real-time renderer's shader sources (src/lightcone/raster/shaders/), embedded at build
// time, without their version lines.
#pragma once

namespace lightcone::shader_sources {

extern const char* const common_glsl;
extern const char* const body_vert;
extern const char* const body_projection_glsl;
extern const char* const patch_vert;
extern const char* const body_tesc;
extern const char* const body_tese;
extern const char* const body_frag;
extern const char* const patterns_glsl;
extern const char* const hole_body_vert;
extern const char* const hole_body_frag;
extern const char* const lighting_glsl;
extern const char* const lit_surfaces_frag;
extern const char* const fullscreen_vert;
extern const char* const display_frag;
extern const char* const sky_frag;
extern const char* const black_hole_glsl;
extern const char* const star_vert;
extern const char* const star_frag;
extern const char* const star_filter_glsl;
extern const char* const tone_map_glsl;
extern const char* const baseline_vert;
extern const char* const baseline_frag;
extern const char* const shadow_vert;
extern const char* const shadow_frag;

}  // namespace lightcone::shader_sources
