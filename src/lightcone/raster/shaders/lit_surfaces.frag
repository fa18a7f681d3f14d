// The lighting pass (deferred shading): each pixel whose nearest surface is lit, as the lit
// bodies wrote it (body.frag under LIGHTCONE_LIT), lit once by every light, with its shadows.
// Surfaces hidden behind it never reach the lights' code: on a software rasteriser, which
// shades whole blocks of fragments, that was most of a lit frame.
uniform highp sampler2D lit_surface;   // the normal in the body's rest frame, s
uniform highp sampler2D lit_motion;    // the surface's velocity in W, D_camera
uniform highp sampler2D lit_albedo;    // the albedo, k (-1: a texel's, to be fitted)
uniform highp sampler2D lit_material;  // reflection_body, roughness (-1: matte), specular,
                                       // the colour's alpha (0: no lit surface here)

layout(location = 0) out vec4 colour;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 material = texelFetch(lit_material, pixel, 0);
  if (material.w == 0.0) discard;  // the sky or an unlit body is nearest here
  vec4 surface = texelFetch(lit_surface, pixel, 0);
  vec4 motion = texelFetch(lit_motion, pixel, 0);
  vec4 albedo = texelFetch(lit_albedo, pixel, 0);
  int k = int(albedo.w);
#if defined(LIGHTCONE_SPECTRAL_TEXTURES)
  if (k < 0) texel_reflectance = rgb_to_sigmoid(albedo.rgb);
#endif
  Finish finish = Finish(material.y >= 0.0, material.y, material.z, int(material.x));
  float d = motion.w;
#if defined(LIGHTCONE_MOVING_SURFACES)
  vec3 surface_velocity = motion.xyz;
#else
  const vec3 surface_velocity = vec3(0.0);  // every lit surface at rest in W
#endif
  vec3 c = lit_colour(albedo.rgb, k, finish, fragment_look_direction(), surface.w, d,
                      surface_velocity, surface.xyz, fragment_light_sample());
  colour = vec4(spectral == 1 ? c * spectral_searchlight(d, searchlight_model) : c, material.w);
}
