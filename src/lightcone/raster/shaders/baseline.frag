// The pass-through baseline: one colour, the rasterised depth (early depth tests apply).
layout(location = 0) out vec4 colour;

void main() {
  colour = vec4(1.0);
}
