#version 330 core
in float v_across;
uniform float u_half_width_px;
uniform vec4 u_colour;
out vec4 frag;

void main() {
  float coverage = clamp(u_half_width_px - abs(v_across) + 0.5, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  float a = coverage * u_colour.a;
  frag = vec4(u_colour.rgb * a, a);
}
