// A shadow map's face (raster/shadow_maps.hpp): a body at rest relative to the light, placed in
// the light's rest frame R about the light, seen from it along one of the cube's six axes.
layout(location = 0) in vec3 shape_position;

uniform mat3 shape_to_light;  // the body's rotation times its scale
uniform vec3 body_offset;     // its origin, from the light, in R
uniform vec3 face_forward;
uniform vec3 face_right;
uniform vec3 face_up;

out vec3 from_light;

void main() {
  from_light = body_offset + shape_to_light * shape_position;
  // 90 degrees across; z = 0 keeps what lies in front (w > 0), the fragments write the depth.
  gl_Position = vec4(dot(from_light, face_right), dot(from_light, face_up), 0.0,
                     dot(from_light, face_forward));
}
