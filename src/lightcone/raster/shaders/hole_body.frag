// A body's fragment near a black hole: the surface point, shift g and clock interpolated
// between the vertices (each exact, and the edges split until the drawing lies within half a
// pixel of the image). An emitter's rest-frame pattern colour is received with g, which
// replaces the Doppler factor in the colour and searchlight laws (a texture's texel as the flat
// bodies' is, at the surface point's texture coordinates: a mesh face's interpolated between its
// vertices, where they are an affine map of the point); a lit body's colour is interpolated
// between its vertices' (each the ray tracer's lighting there; a lit texture's, at the texel
// there).
in vec3 shape_point;
in float log_shift;
in float proper_time;
in vec3 received_0;
in vec3 received_1;
in vec2 face_uv;
in float swept;

uniform int colour_row;  // an emitter's row of the pattern's first colour
uniform int lit;
// The colour's alpha: 2 on a body moving relative to the camera (the automatic exposure's
// subject), else 1, as body.frag's.
uniform float subject_alpha;
uniform sampler2D texture_image;

layout(location = 0) out vec4 colour;

void main() {
#if defined(LIGHTCONE_DISK_HIDES_BODIES)
  // The accretion disk hides what its pixel's ray meets past the disk's first crossing, as
  // follow_curved_ray sees a body only before it.
  HoleRay ray = follow_hole_ray(fragment_look_direction());
  if (ray.end == kHoleDisk && ray.phi < swept) discard;
#endif
  if (pattern == 2 && lit == 0) {  // an unlit texture
    vec2 uv = shape_kind == 0 ? face_uv : surface_uv(shape_point);
    colour = vec4(received_rgb(sample_bilinear(texture_image, uv, true), exp(log_shift)),
                  subject_alpha);
    return;
  }
  int k = pattern_index(shape_point, proper_time);
  // A clock on a mesh: its dial at the face's texture coordinates, as the tracer reads it.
  if (pattern == 4 && shape_kind == 0) k = clock_index(face_uv, proper_time);
  if (lit == 1)
    colour = vec4(k == 0 ? received_0 : received_1, subject_alpha);
  else
    colour = vec4(received_colour(colour_row + k, exp(log_shift)), subject_alpha);
}
