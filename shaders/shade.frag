// Radiance towards the camera from point lights: L = sum f(l, v, n) I cos(theta_in) / d^2.
in vec3 vPosition;
in vec3 vNormal;
uniform vec3 uCameraCenter;
uniform int uLightCount;
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightIntensity[MAX_LIGHTS];  // W/sr per channel
out vec4 outRadiance;
void main() {
  vec3 n = normalize(vNormal);
  vec3 v = normalize(uCameraCenter - vPosition);
  vec3 radiance = vec3(0.0);
  if (dot(n, v) > 0.0) {
    for (int k = 0; k < uLightCount; ++k) {
      vec3 toLight = uLightPosition[k] - vPosition;
      float d2 = dot(toLight, toLight);
      vec3 l = toLight * inversesqrt(d2);
      float cosIn = dot(n, l);
      if (cosIn > 0.0) radiance += evalMaterial(l, v, n) * uLightIntensity[k] * cosIn / d2;
    }
  }
  outRadiance = vec4(radiance, 1.0);
}
