// The rest-frame patterns of a body's surface, shared by the body programs (body.frag,
// hole_body.frag): which of the pattern's colours a surface point shows at the body's clock.
uniform int pattern;  // 0: one colour; 1: checker; 2: texture; 3: blink; 4: clock
uniform float checker_size;
uniform float pattern_period;  // blink, clock
uniform float blink_duty;
uniform int shape_kind;  // 0: mesh; 1: box; 2: plane; 3: sphere
uniform vec3 box_size;

const float kTwoPi = 6.283185307179586;
const float kHalfTurn = 3.141592653589793;

// frame/shading.cpp, checker_index: (floor(x/s) + floor(y/s) + floor(z/s)) mod 2.
int checker_index(vec3 p, float size) {
  vec3 cell = floor(p / size);
  return int(mod(cell.x + cell.y + cell.z, 2.0));
}

// frame/shading.cpp's period_phase, blink_index and clock_index.
float period_phase(float proper_time) {
  float cycles = proper_time / pattern_period;
  return clamp(cycles - floor(cycles), 0.0, 0.99999994);
}

int blink_index(float proper_time) {
  return period_phase(proper_time) < blink_duty ? 1 : 0;
}

int clock_index(vec2 uv, float proper_time) {
  vec2 p = vec2(uv.x - 0.5, 0.5 - uv.y);
  float r = length(p);
  if (r > 0.5) return 0;
  if (r >= 0.45) return 1;
  float angle = 6.283185307179586 * period_phase(proper_time);
  vec2 hand = vec2(sin(angle), cos(angle));
  float along = dot(p, hand), across = abs(p.x * hand.y - p.y * hand.x);
  return (along >= 0.0 && along <= 0.4 && across <= 0.025) || r <= 0.04 ? 1 : 0;
}

// trace/tracer.cpp's texture coordinates of a surface point: sphere_uv, box_uv, the plane's.
vec2 surface_uv(vec3 p) {
  if (shape_kind == 3) {
    vec3 n = normalize(p);
    return vec2(0.5 + atan(n.x, n.z) / kTwoPi, atan(length(n.xz), n.y) / kHalfTurn);
  }
  if (shape_kind == 1) {
    vec3 rel = p / box_size, a = abs(rel);
    vec3 outward = sign(rel);  // the face's own component is +-0.5, never 0
    if (a.x >= a.y && a.x >= a.z) return vec2(0.5 - outward.x * rel.z, 0.5 - rel.y);
    if (a.y >= a.z) return vec2(0.5 + rel.x, 0.5 + outward.y * rel.z);
    return vec2(0.5 + outward.z * rel.x, 0.5 - rel.y);
  }
  return vec2(0.5 + p.x / box_size.x, 0.5 + p.z / box_size.z);  // a plane's size in x and z
}

// Which of the pattern's colours (0 or 1) surface point p shows at the body's clock.
// (LIGHTCONE_NO_TIMED_PATTERNS: a frame without blinks and clocks.)
int pattern_index(vec3 p, float proper_time) {
#if defined(LIGHTCONE_NO_TIMED_PATTERNS)
  return pattern == 1 ? checker_index(p, checker_size) : 0;
#else
  return pattern == 1                     ? checker_index(p, checker_size)
         : pattern == 3                   ? blink_index(proper_time)
         : pattern == 4 && shape_kind > 0 ? clock_index(surface_uv(p), proper_time)
                                          : 0;
#endif
}
