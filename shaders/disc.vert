#version 330 core
// One disc per point sprite, or per quad of two triangles (the same shader serves both).
// Positions and radii arrive in world metres and are mapped to pixels here.
layout(location = 0) in vec2 a_centre;
layout(location = 1) in float a_radius;
layout(location = 2) in vec4 a_colour;
layout(location = 3) in float a_angle;
layout(location = 4) in vec2 a_corner;  // quads only: a corner in [-1, 1]^2

uniform vec2 u_origin;    // world point at the lower-left pixel of the viewport (guard band included)
uniform float u_scale;    // pixels per metre
uniform vec2 u_viewport;  // viewport size in pixels
uniform bool u_sprites;

// One value per disc: flat, so llvmpipe sets up no interpolation for them.
flat out vec4 v_colour;
flat out float v_radius_px;
flat out float v_angle;
out vec2 v_local_px;  // quads: offset from the centre in pixels

void main() {
  float r_px = a_radius * u_scale;
  float half_px = r_px + 1.0;  // one pixel of margin for the anti-aliased edge
  vec2 pos_px = (a_centre - u_origin) * u_scale;
  if (u_sprites) {
    gl_PointSize = 2.0 * half_px;
    v_local_px = vec2(0.0);
  } else {
    pos_px += a_corner * half_px;
    v_local_px = a_corner * half_px;
  }
  gl_Position = vec4(pos_px / u_viewport * 2.0 - 1.0, 0.0, 1.0);
  v_colour = a_colour;
  v_radius_px = r_px;
  v_angle = a_angle;
}
