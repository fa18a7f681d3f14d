// A body's fragment: the colour its rest-frame pattern has at the shape point, received with
// the Doppler factor of the exact look direction through the sample.
in vec3 shape_point;

uniform vec3 doppler_velocity;  // the body's velocity in F (0 for the classical picture)
uniform float doppler_gamma;
uniform int colour_row;      // the row of the pattern's first colour
uniform int pattern;         // 0: one colour; 1: checker
uniform float checker_size;

layout(location = 0) out vec4 colour;

// frame/shading.cpp, checker_index: (floor(x/s) + floor(y/s) + floor(z/s)) mod 2.
int checker_index(vec3 p, float size) {
  vec3 cell = floor(p / size);
  return int(mod(cell.x + cell.y + cell.z, 2.0));
}

void main() {
  vec3 u = fragment_look_direction();
  float d = doppler_factor(u, doppler_velocity, doppler_gamma);
  int row = colour_row + (pattern == 1 ? checker_index(shape_point, checker_size) : 0);
  colour = vec4(received_colour(row, d), 1.0);
}
