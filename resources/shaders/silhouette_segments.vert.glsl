#version 430 core
// Pass 2 of method 1 over the segments the GPU computed this frame (line_segments.comp.glsl):
// drawn as lines, two vertices a segment, numbered by gl_VertexID. A vertex past the buffer's
// capacity (the frame had more segments than room; the host draws again with more) goes beyond
// the far plane, so its line is clipped away.
layout(std430, binding = 3) restrict readonly buffer Segments { vec4 segmentEnds[]; };

uniform uint uVertexCapacity;

void main() {
    uint v = uint(gl_VertexID);
    gl_Position = v < uVertexCapacity ? segmentEnds[v] : vec4(0.0, 0.0, 2.0, 1.0);
}
