layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uClipFromWorld;
out vec3 vPosition;
out vec3 vNormal;
// The depth pre-pass and the shading pass must produce identical depths (GL_EQUAL test).
invariant gl_Position;
void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  gl_Position = uClipFromWorld * vec4(aPosition, 1.0);
}
