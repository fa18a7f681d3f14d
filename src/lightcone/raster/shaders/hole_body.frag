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

#if defined(LIGHTCONE_SURFACE_VARIABLES)
// What the output variables need of the nearest image at each pixel's centre
// (raster/surface_variables.cpp): the surface's normal in shape coordinates, facing the light
// that leaves it for the camera, and the light's coordinate time of flight; the body's index,
// ln g and the image's order (alpha 1: an image, 0: none).
in float flight;
uniform float body_index;
layout(location = 0) out vec4 surface_normal_flight;
layout(location = 1) out vec4 surface_object_shift;

// The normal at shape point p (a sphere's, a box's face, a plane's, a mesh face's: the drawn
// triangle's, which lies in the face), on the side the light leaves it for the camera: the
// side the drawn triangle shows, which the image of order 1 mirrors.
vec3 normal_toward_camera(vec3 p, int order) {
  vec3 drawn = cross(dFdx(p), dFdy(p)) * (order == 1 ? -1.0 : 1.0);
  vec3 n = drawn;
  if (shape_kind == 3) {
    n = p;
  } else if (shape_kind == 1) {
    vec3 rel = abs(p / box_size);
    if (rel.x >= rel.y && rel.x >= rel.z) n = vec3(sign(p.x), 0.0, 0.0);
    else if (rel.y >= rel.z) n = vec3(0.0, sign(p.y), 0.0);
    else n = vec3(0.0, 0.0, sign(p.z));
  } else if (shape_kind == 2) {
    n = vec3(0.0, 1.0, 0.0);
  }
  return dot(n, drawn) < 0.0 ? -n : n;
}
#else
layout(location = 0) out vec4 colour;
#endif

void main() {
#if defined(LIGHTCONE_DISK_HIDES_BODIES)
  // The accretion disk hides what its pixel's ray meets past the disk's first crossing, as
  // follow_curved_ray sees a body only before it.
  HoleRay ray = follow_hole_ray(fragment_look_direction());
  if (ray.end == kHoleDisk && ray.phi < swept) discard;
#endif
#if defined(LIGHTCONE_SURFACE_VARIABLES)
  // hole_swept_angle: up to pi for the direct image, beyond it round the far side.
  int order = swept > 3.14159265 ? 1 : 0;
  surface_normal_flight = vec4(normal_toward_camera(shape_point, order), flight);
  surface_object_shift = vec4(body_index, log_shift, float(order), 1.0);
#else
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
#endif
}
