// The display pass of the interactive viewer: linear radiance (from the frame's float
// framebuffer) times 2^exposure, tone-mapped and sRGB-encoded as frame/tone_map.cpp and
// io/image_file.cpp's srgb_encode do for a PNG. With `split`, the left half shows the
// classical picture.
uniform sampler2D relativistic_image;
uniform sampler2D classical_image;
uniform int split;
uniform float exposure_scale;
uniform int tone_curve;  // 0: clamp; 1: reinhard; 2: filmic

layout(location = 0) out vec4 colour;

float luminance(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// frame/tone_map.cpp, tone_map.
vec3 tone_map(vec3 c) {
  if (tone_curve == 1) return clamp(c / (1.0 + max(0.0, luminance(c))), 0.0, 1.0);
  if (tone_curve == 2) {
    vec3 x = max(c, vec3(0.0));
    return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  }
  return clamp(c, 0.0, 1.0);
}

// io/image_file.cpp, srgb_encode.
vec3 srgb_encode(vec3 l) {
  return mix(12.92 * l, 1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), l));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  bool left = split == 1 && gl_FragCoord.x < 0.5 * image_size.x;
  vec3 c = (left ? texelFetch(classical_image, p, 0) : texelFetch(relativistic_image, p, 0)).rgb;
  colour = vec4(srgb_encode(tone_map(c * exposure_scale)), 1.0);
}
