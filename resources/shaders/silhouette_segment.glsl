// Method 1's silhouette segment of one triangle (Burns et al. 2005), shared by pass 2's geometry
// shader (silhouette.geom.glsl: over triangles) and the GPU's segment stage
// (line_segments.comp.glsl: every triangle, its segments drawn as lines); the renderer inserts it
// after their #version line. The rule
// is kernels/common/include/lw/kernels/silhouette_segment.h's: d = N . (eye - B) at each vertex
// (N . toViewer for an orthographic camera); d >= 0 counts as front-facing so both triangles of
// an edge classify it alike and neighbouring segments meet end to end; the endpoints lie on the
// two edges of the lone vertex, at t = d_lone / (d_lone - d_other).
// The segments go into the line depth buffer as one-pixel lines; the resolve pass
// (silhouette_resolve.frag.glsl) decides which are visible and widens them.
uniform mat4 uViewProjection;
uniform vec4 uViewer;       // see surface.frag.glsl
uniform vec2 uViewportSize; // pixels

vec4 projectToClip(vec3 p) {
    return uViewProjection * vec4(p, 1.0);
}

// The triangle's segment as the clip-space ends of a line, or false where it has none.
bool silhouetteSegment(vec3 position[3], vec3 normal[3], out vec4 lineStart, out vec4 lineEnd) {
    float d[3];
    for (int k = 0; k < 3; ++k)
        d[k] = dot(normal[k], uViewer.xyz - position[k] * uViewer.w);
    bool front0 = d[0] >= 0.0, front1 = d[1] >= 0.0, front2 = d[2] >= 0.0;
    if (front0 == front1 && front1 == front2)
        return false;
    int lone = (front0 == front1) ? 2 : (front0 == front2 ? 1 : 0);
    int other1 = (lone + 1) % 3, other2 = (lone + 2) % 3;
    float t1 = d[lone] / (d[lone] - d[other1]);
    float t2 = d[lone] / (d[lone] - d[other2]);
    vec4 a = projectToClip(position[lone] + t1 * (position[other1] - position[lone]));
    vec4 b = projectToClip(position[lone] + t2 * (position[other2] - position[lone]));
    // The fitted cameras keep the volume in front of the eye; a segment reaching behind it
    // (w <= 0) cannot be handled in screen space and is dropped.
    if (a.w <= 0.0 || b.w <= 0.0)
        return false;
    vec2 sa = a.xy / a.w * 0.5 * uViewportSize;
    vec2 sb = b.xy / b.w * 0.5 * uViewportSize;
    vec2 along = sb - sa;
    float len = length(along);
    along = len > 1e-6 ? along / len : vec2(1.0, 0.0);
    vec2 toNdc = 2.0 / uViewportSize;
    // Contour segments are often shorter than a pixel, and the diamond-exit rule draws no pixel
    // for a line that ends inside the diamond it started in: the contour would come out dotted.
    // Half a pixel past each end makes neighbouring segments overlap, so every joint is drawn.
    vec2 past = along * 0.5;
    lineStart = a + vec4(-past * toNdc * a.w, 0.0, 0.0);
    lineEnd = b + vec4(past * toNdc * b.w, 0.0, 0.0);
    return true;
}
