// A star's image as a point sprite (frame/star_field.hpp): three pixels wide about its exact
// image point, the support of the pixel filter (the pixels whose centres it holds are those the
// filter weighs; one on its edge would get none). Few values pass to the fragments: on a
// software rasteriser each costs every sprite's setup.

// The image point in pixels, y down (pixel (i, j) centred at i+.5, j+.5), and the flux.
layout(location = 0) in vec2 star_point;
layout(location = 1) in vec3 flux;

uniform vec2 viewport_margin;  // pixels of the viewport past each edge of the picture

flat out vec3 star_radiance;  // the flux over a pixel's area on the image plane
flat out vec2 star_window;    // the image point in window coordinates (y up)

void main() {
  vec2 at = vec2(star_point.x, image_size.y - star_point.y);  // window coordinates, y up
  star_window = at;
  // Over a pixel's solid angle at unit distance: its area on the image plane (star.frag divides
  // by cos^3 of each pixel's angle from the forward direction).
  vec2 size = 2.0 * camera_tan_half / image_size;
  star_radiance = flux / (size.x * size.y);
  // At the far end of the depth range, as the sky: bodies in front hide it. The viewport reaches
  // past the picture's edges, so that no point whose sprite reaches into the picture is clipped
  // by its centre.
  gl_Position = vec4((at + viewport_margin) / (image_size + 2.0 * viewport_margin) * 2.0 - 1.0,
                     1.0, 1.0);
  gl_PointSize = 3.0;
}
