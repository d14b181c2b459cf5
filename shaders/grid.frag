// Evaluates the slice model at the (theta_in, theta) pair stored in each texel of uAngles:
// the GPU side of the GPU/CPU agreement test.
uniform sampler2D uAngles;
out vec4 outValue;
void main() {
  vec2 a = texelFetch(uAngles, ivec2(gl_FragCoord.xy), 0).rg;
  outValue = vec4(evalSliceModel(a.x, a.y), 1.0);
}
