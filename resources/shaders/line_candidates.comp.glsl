#version 430 core
// Method 1's pass-2 candidates, on the GPU that draws them: one invocation a triangle keeps the
// triangles whose facing can change for the viewer and appends their numbers to the candidate
// buffer. The rule is mayHoldContour (lw/kernels/silhouette_segment.h): a triangle is dropped
// only when all three d = N . (eye - B) lie beyond the same side of a margin of
// 1e-4 |N| |eye - B|, far more than the rounding by which this compiler and the geometry
// shader's may differ, so every triangle that shader would emit a segment for is kept.
// The count goes into the indirect draw command pass 2 draws with (a point per candidate,
// silhouette_points.geom.glsl): the host never waits for it.
// A work group counts its kept triangles in shared memory and reserves their slots with one
// atomic on the command (one global atomic per 256 triangles, not one per candidate).
layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) readonly buffer Normals { float normals[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) writeonly buffer Candidates { uint candidates[]; };
// A DrawArraysIndirectCommand: the point count, then instances, first point and base instance
// (set by the host before the dispatch).
layout(std430, binding = 4) buffer Command { uint pointCount; uint otherFields[3]; };

uniform vec4 uViewer; // the eye (w = 1) or the direction toward the viewer (w = 0)
uniform uint uTriangleCount;

shared uint groupKept;
shared uint groupFirst;

vec3 position(uint v) {
    return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]);
}

vec3 normal(uint v) {
    return vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u]);
}

bool mayHoldContour(uint v[3]) {
    int front = 0, back = 0;
    for (int k = 0; k < 3; ++k) {
        vec3 n = normal(v[k]);
        vec3 toEye = uViewer.xyz - position(v[k]) * uViewer.w;
        float d = dot(n, toEye);
        float margin = 1e-4 * length(n) * length(toEye) + 1e-30;
        front += d > margin ? 1 : 0;
        back += d < -margin ? 1 : 0;
    }
    return front != 3 && back != 3;
}

void main() {
    if (gl_LocalInvocationIndex == 0u)
        groupKept = 0u;
    memoryBarrierShared();
    barrier();
    // Groups are laid out in two dimensions (a dimension holds at most 65535).
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint t = group * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    bool keep = t < uTriangleCount &&
                mayHoldContour(uint[3](indices[3u * t], indices[3u * t + 1u], indices[3u * t + 2u]));
    uint slot = keep ? atomicAdd(groupKept, 1u) : 0u;
    memoryBarrierShared();
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupKept > 0u)
        groupFirst = atomicAdd(pointCount, groupKept);
    memoryBarrierShared();
    barrier();
    if (keep)
        candidates[groupFirst + slot] = t;
}
