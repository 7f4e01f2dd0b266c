#version 430 core
// Pass 2 of method 1 over the GPU's candidates: one point a candidate, numbered by gl_VertexID;
// the geometry shader (silhouette_points.geom.glsl) fetches the triangle itself.
flat out uint vCandidate;

void main() {
    vCandidate = uint(gl_VertexID);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
