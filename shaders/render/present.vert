#version 450
// Presentation of a finished frame (render/window/frame_presenter.h): one
// triangle that covers the viewport, made from gl_VertexID alone (drawn with an
// empty vertex array, no buffers). Its corners (−1,−1), (3,−1), (−1,3) in clip
// space contain the square [−1,1]²; frame_uv runs over [0,1]² across the
// viewport, (0,0) at its bottom left.

out vec2 frame_uv;

void main() {
  // gl_VertexID 0, 1, 2 → (0,0), (2,0), (0,2).
  const vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  frame_uv = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
