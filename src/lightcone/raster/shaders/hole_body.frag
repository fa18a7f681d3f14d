// A body's fragment near a black hole: the surface point, shift g and clock interpolated
// between the vertices (each exact, and the edges split until the drawing lies within half a
// pixel of the image); the pattern's rest-frame colour is received with g, which replaces the
// Doppler factor in the colour and searchlight laws.
in vec3 shape_point;
in float log_shift;
in float proper_time;

uniform int colour_row;  // the row of the pattern's first colour

layout(location = 0) out vec4 colour;

void main() {
  colour = vec4(received_colour(colour_row + pattern_index(shape_point, proper_time),
                                exp(log_shift)),
                1.0);
}
