#version 330 core
// A wall segment drawn as a quad; a_across is the signed distance from the centre line in
// pixels, for the anti-aliased sides.
layout(location = 0) in vec2 a_position;  // world metres, already offset on the CPU
layout(location = 1) in float a_across;

uniform vec2 u_origin;
uniform float u_scale;
uniform vec2 u_viewport;

out float v_across;

void main() {
  vec2 pos_px = (a_position - u_origin) * u_scale;
  gl_Position = vec4(pos_px / u_viewport * 2.0 - 1.0, 0.0, 1.0);
  v_across = a_across;
}
