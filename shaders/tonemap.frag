// Display only: exposure, a filmic-free exponential tone curve, sRGB encoding by the
// framebuffer (GL_FRAMEBUFFER_SRGB). Measurements use the linear float target instead.
uniform sampler2D uRadiance;
uniform float uExposure;
uniform int uOffsetX;  // the pane's first window column
out vec4 outColor;
void main() {
  vec3 l = texelFetch(uRadiance, ivec2(gl_FragCoord.xy) - ivec2(uOffsetX, 0), 0).rgb;
  outColor = vec4(vec3(1.0) - exp(-uExposure * l), 1.0);
}
