// The lighting pass (deferred shading): each pixel whose nearest surface is lit, as the lit
// bodies wrote it (body.frag under LIGHTCONE_LIT), lit once by every light, with its shadows.
// Surfaces hidden behind it never reach the lights' code: on a software rasteriser, which
// shades whole blocks of fragments, that was most of a lit frame.
uniform highp sampler2D lit_surface;  // the normal in the body's rest frame, s
uniform highp sampler2D lit_motion;   // the surface's velocity in W, D_camera
uniform highp sampler2D lit_albedo;   // the albedo, body.frag's lit_code (0: no lit surface)

layout(location = 0) out vec4 colour;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 albedo = texelFetch(lit_albedo, pixel, 0);
  if (albedo.w == 0.0) discard;  // the sky or an unlit body is nearest here
  // lit_code's parts: the colour's alpha, the fixed colour k, the body's row of reflection_index,
  // whose last texel holds its finish (roughness, -1 for matte; specular).
  int code = int(albedo.w) - 1;
  float alpha = code % 2 == 1 ? 2.0 : 1.0;
  int k = (code / 2) % 4 - 1;
  int body = code / 8;
  int finish_column = textureSize(reflection_index, 0).x - 1;
  vec2 finish = texelFetch(reflection_index, ivec2(finish_column, body), 0).xy;
  vec4 surface = texelFetch(lit_surface, pixel, 0);
  vec4 motion = texelFetch(lit_motion, pixel, 0);
#if defined(LIGHTCONE_SPECTRAL_TEXTURES)
  if (k < 0) texel_reflectance = rgb_to_sigmoid(albedo.rgb);
#endif
  Finish surface_finish = Finish(finish.x >= 0.0, finish.x, finish.y, body);
  float d = motion.w;
#if defined(LIGHTCONE_MOVING_SURFACES)
  vec3 surface_velocity = motion.xyz;
#else
  const vec3 surface_velocity = vec3(0.0);  // every lit surface at rest in W
#endif
  vec3 c = lit_colour(albedo.rgb, k, surface_finish, fragment_look_direction(), surface.w, d,
                      surface_velocity, surface.xyz, fragment_light_sample());
  colour = vec4(spectral == 1 ? c * spectral_searchlight(d, searchlight_model) : c, alpha);
}
