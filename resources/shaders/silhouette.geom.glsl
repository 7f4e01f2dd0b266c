#version 410 core
// Pass 2 of method 1 over triangles (all of them, or the host's candidates): each triangle's
// silhouette segment (silhouette_segment.glsl, which the renderer inserts after this line).
layout(triangles) in;
layout(line_strip, max_vertices = 2) out;

in vec3 vPosition[];
in vec3 vNormal[];

void main() {
    vec3 position[3] = vec3[3](vPosition[0], vPosition[1], vPosition[2]);
    vec3 normal[3] = vec3[3](vNormal[0], vNormal[1], vNormal[2]);
    vec4 lineStart, lineEnd;
    if (!silhouetteSegment(position, normal, lineStart, lineEnd))
        return;
    gl_Position = lineStart;
    EmitVertex();
    gl_Position = lineEnd;
    EmitVertex();
    EndPrimitive();
}
