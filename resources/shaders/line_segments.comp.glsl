#version 430 core
// Method 1's pass-2 segments, on the GPU that draws them: one invocation a triangle computes its
// silhouette segment (silhouette_segment.glsl, which the renderer inserts after this line: the
// rule and the arithmetic of the geometry shader over triangles) and appends the segment's two
// clip-space ends to the segment buffer. Pass 2 then draws those ends as plain lines
// (silhouette_segments.vert.glsl), their vertex count read from the indirect draw command this
// stage fills: the host never waits for it. Computing the segment here, where the triangle is
// read anyway, replaced a geometry shader over the contour's candidates (0.8 ms for 316 k of
// them on the H200).
// A work group counts its segments in shared memory and reserves their slots with one atomic on
// the command (one global atomic per 256 triangles, not one per segment). The count keeps
// growing past the buffer's capacity, where nothing is written: the vertex shader moves such
// vertices out of view, and the host, which reads the count once the frame is done, grows the
// buffer and draws the lines again.
// Every segment found, drawn or dropped as hidden, is counted as well: the frame's segment count.
layout(local_size_x = 256) in;

layout(std430, binding = 0) restrict readonly buffer Positions { float positions[]; };
layout(std430, binding = 1) restrict readonly buffer Normals { float normals[]; };
layout(std430, binding = 2) restrict readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) restrict writeonly buffer Segments { vec4 segmentEnds[]; };
// A DrawArraysIndirectCommand: the vertex count (two a segment drawn), then instances, first
// vertex and base instance (set by the host before the dispatch); then the count of every segment
// found, hidden ones included.
layout(std430, binding = 4) buffer Command { uint vertexCount; uint otherFields[3]; uint found; };

uniform uint uTriangleCount;
uniform uint uSegmentCapacity;
// Where the frame's pass 1 is drawn and pass 2 discards hidden fragments (a frame drawn in one
// call), segments that the visibility rule would hide in every pixel they can touch are dropped
// here rather than drawn and discarded: the test of silhouette_visibility.glsl.
uniform bool uCullHidden;
uniform sampler2D uSurfaceDepth;
uniform float uTolerance;

shared uint groupSegments;
shared uint groupFound;
shared uint groupFirst;

vec3 position(uint v) {
    return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]);
}

vec3 normal(uint v) {
    return vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u]);
}

// Whether any fragment of the line from a to b (clip space) can pass lineVisible. A line's
// fragments have centres within half a pixel of it, and their window depth between its ends';
// the test takes a pixel more on each side and a margin in depth, so that the rasterizer's own
// rounding cannot make a dropped line visible. Long lines are kept untested.
bool mayBeVisible(vec4 a, vec4 b) {
    vec3 ndcA = a.xyz / a.w, ndcB = b.xyz / b.w;
    vec2 windowA = (ndcA.xy * 0.5 + 0.5) * uViewportSize;
    vec2 windowB = (ndcB.xy * 0.5 + 0.5) * uViewportSize;
    float nearest = min(ndcA.z, ndcB.z) * 0.5 + 0.5 - 1e-5;
    ivec2 last = textureSize(uSurfaceDepth, 0) - 1;
    ivec2 low = clamp(ivec2(floor(min(windowA, windowB))) - 2, ivec2(0), last);
    ivec2 high = clamp(ivec2(floor(max(windowA, windowB))) + 2, ivec2(0), last);
    if ((high.x - low.x + 1) * (high.y - low.y + 1) > 36)
        return true;
    float farthest = 0.0;
    for (int y = low.y; y <= high.y; ++y)
        for (int x = low.x; x <= high.x; ++x)
            farthest = max(farthest, texelFetch(uSurfaceDepth, ivec2(x, y), 0).r);
    return nearest <= farthest + uTolerance;
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        groupSegments = 0u;
        groupFound = 0u;
    }
    memoryBarrierShared();
    barrier();
    // Groups are laid out in two dimensions (a dimension holds at most 65535).
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint t = group * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    vec4 lineStart = vec4(0.0), lineEnd = vec4(0.0);
    bool hasSegment = false;
    if (t < uTriangleCount) {
        vec3 corner[3], cornerNormal[3];
        for (int k = 0; k < 3; ++k) {
            uint v = indices[3u * t + uint(k)];
            corner[k] = position(v);
            cornerNormal[k] = normal(v);
        }
        if (silhouetteSegment(corner, cornerNormal, lineStart, lineEnd)) {
            atomicAdd(groupFound, 1u);
            hasSegment = !uCullHidden || mayBeVisible(lineStart, lineEnd);
        }
    }
    uint slot = hasSegment ? atomicAdd(groupSegments, 1u) : 0u;
    memoryBarrierShared();
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupSegments > 0u)
        groupFirst = atomicAdd(vertexCount, 2u * groupSegments) / 2u;
    if (gl_LocalInvocationIndex == 0u && groupFound > 0u)
        atomicAdd(found, groupFound);
    memoryBarrierShared();
    barrier();
    uint segment = groupFirst + slot;
    if (hasSegment && segment < uSegmentCapacity) {
        segmentEnds[2u * segment] = lineStart;
        segmentEnds[2u * segment + 1u] = lineEnd;
    }
}
