// A body's vertex near a black hole, seen along one image order's exact ray from its own
// retarded event (solved on the CPU in double precision, raster/hole_bodies.cpp): its apparent
// position is its look direction times the coordinate time its light took, which orders what
// one ray meets (the depth).
layout(location = 0) in vec3 apparent_position;
layout(location = 1) in vec3 shape_position;
layout(location = 2) in vec2 shift_and_clock;  // ln g, the body's clock at the emission
// A lit body: what the vertex sends the camera in each of its material's two fixed colours.
layout(location = 3) in vec3 lit_colour_0;
layout(location = 4) in vec3 lit_colour_1;
// A mesh face's texture coordinates at the vertex (zero for other shapes).
layout(location = 5) in vec2 face_texture_uv;
// The angle its light swept about the hole from the camera (raster/hole_bodies.hpp,
// hole_swept_angle).
layout(location = 6) in float swept_angle;

out vec3 shape_point;
out float log_shift;
out float proper_time;
out vec3 received_0;
out vec3 received_1;
out vec2 face_uv;
out float swept;
#if defined(LIGHTCONE_SURFACE_VARIABLES)
out float flight;  // the light's coordinate time of flight, its apparent position's length
#endif

void main() {
  gl_Position = clip_of(vec4(apparent_position, length(apparent_position)));
  shape_point = shape_position;
  log_shift = shift_and_clock.x;
  proper_time = shift_and_clock.y;
  received_0 = lit_colour_0;
  received_1 = lit_colour_1;
  face_uv = face_texture_uv;
  swept = swept_angle;
#if defined(LIGHTCONE_SURFACE_VARIABLES)
  flight = length(apparent_position);
#endif
}
