#version 430 core
// Pass 2 of method 1 over the candidates the GPU culled this frame (line_candidates.comp.glsl):
// one point a candidate, whose triangle this shader fetches from the mesh buffers, then its
// silhouette segment (silhouette_segment.glsl, which the renderer inserts after this line).
// Points instead of the candidate triangles: no vertex shader run and no triangle assembled per
// corner, which took a fifth of pass 2 on the H200 (0.98 -> 0.78 ms for 316 k candidates).
layout(points) in;
layout(line_strip, max_vertices = 2) out;

flat in uint vCandidate[];

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) readonly buffer Normals { float normals[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) readonly buffer Candidates { uint candidates[]; }; // triangle numbers

void main() {
    uint triangle = candidates[vCandidate[0]];
    vec3 position[3], normal[3];
    for (int k = 0; k < 3; ++k) {
        uint v = indices[3u * triangle + uint(k)];
        position[k] = vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]);
        normal[k] = vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u]);
    }
    emitSilhouetteSegment(position, normal);
}
