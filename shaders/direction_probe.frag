// Evaluates the material's BRDF at the light and view directions stored in each texel of
// uLight and uView, for the normal uNormal: the GPU side of the GPU/CPU agreement tests. The
// directions are used as given (not renormalized), as the CPU reference sees them.
uniform sampler2D uLight;
uniform sampler2D uView;
uniform vec3 uNormal;
out vec4 outValue;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  outValue = vec4(evalMaterial(texelFetch(uLight, p, 0).xyz, texelFetch(uView, p, 0).xyz, uNormal),
                  1.0);
}
