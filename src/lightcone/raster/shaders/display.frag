// The display pass of the interactive viewer: linear radiance (from the frame's float
// framebuffer) times 2^exposure, tone-mapped (tone_map.glsl) and sRGB-encoded as
// io/image_file.cpp's srgb_encode does for a PNG. With `split`, the left half shows the
// classical picture.
uniform sampler2D relativistic_image;
uniform sampler2D classical_image;
uniform int split;
uniform float exposure_scale;
uniform int tone_curve;  // 0: clamp; 1: reinhard; 2: filmic

layout(location = 0) out vec4 colour;

// io/image_file.cpp, srgb_encode.
vec3 srgb_encode(vec3 l) {
  return mix(12.92 * l, 1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), l));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool left = split == 1 && gl_FragCoord.x < 0.5 * image_size.x;
  vec3 c = (left ? texelFetch(classical_image, p, 0) : texelFetch(relativistic_image, p, 0)).rgb;
  colour = vec4(srgb_encode(tone_map(c * exposure_scale, tone_curve)), 1.0);
}
