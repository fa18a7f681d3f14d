// A star's image as a sprite (frame/star_field.hpp): a square of four pixels about its exact
// image point, which holds the three-pixel footprint of the pixel filter wherever the point
// lies, one instance a star. Quads rather than GL points: points are clipped whole when their
// centre leaves the picture and their largest size may be one pixel; quads are not, and have
// none.
layout(location = 0) in vec2 image_point;  // pixels, y down (pixel (i, j) centred at i+.5, j+.5)
layout(location = 1) in vec3 flux;         // received flux


flat out vec2 star_window;  // the image point in window coordinates (y up)
flat out vec3 star_flux;

void main() {
  star_window = vec2(image_point.x, image_size.y - image_point.y);
  star_flux = flux;
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 4.0 - 2.0;
  // At the far end of the depth range, as the sky: bodies in front hide it.
  gl_Position = vec4((star_window + corner) / image_size * 2.0 - 1.0, 1.0, 1.0);
}
