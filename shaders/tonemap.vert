#version 450
// One triangle that covers the screen (no vertex input).
void main() {
  vec2 corner = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
  gl_Position = vec4(corner * 2.0f - 1.0f, 0.0f, 1.0f);
}
