#version 330 core
// Analytic anti-aliased disc: coverage from the distance to the edge in pixels. Optional thin
// outline (a darker rim) and a spoke from the centre showing the rotation angle.
// One value per disc: flat, so llvmpipe sets up no interpolation for them.
flat in vec4 v_colour;
flat in float v_radius_px;
flat in float v_angle;
in vec2 v_local_px;

uniform bool u_sprites;
uniform float u_outline_px;  // 0: no outline
uniform bool u_spokes;
uniform vec3 u_ink;

out vec4 frag;

void main() {
  vec2 p = u_sprites ? (gl_PointCoord - 0.5) * vec2(1.0, -1.0) * (2.0 * (v_radius_px + 1.0))
                     : v_local_px;
  float d = length(p);
  float coverage = clamp(v_radius_px - d + 0.5, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  vec3 c = v_colour.rgb;
  if (u_outline_px > 0.0) {
    float rim = clamp(d - (v_radius_px - u_outline_px) + 0.5, 0.0, 1.0);
    c = mix(c, c * 0.55, rim);
  }
  if (u_spokes && v_radius_px >= 3.0) {
    vec2 dir = vec2(cos(v_angle), sin(v_angle));
    float along = dot(p, dir);
    float across = abs(p.x * dir.y - p.y * dir.x);
    float half_width = max(0.6, 0.09 * v_radius_px);
    float spoke = clamp(half_width - across + 0.5, 0.0, 1.0) * step(0.0, along);
    c = mix(c, u_ink, spoke);
  }
  float a = coverage * v_colour.a;
  frag = vec4(c * a, a);  // premultiplied alpha
}
