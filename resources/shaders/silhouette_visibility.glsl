// Method 1's visibility rule, shared by pass 2 (silhouette.frag.glsl: one frame drawn in one call)
// and pass 3 (silhouette_resolve.frag.glsl: after a frame drawn in pieces). The renderer inserts
// this after a fragment shader's #version line. It is method 3's rule
// (lw/kernels/zbuffer_rules.h resolvePixel) in GL window depth, where smaller is nearer and 1 is
// empty: a line at `lineDepth` on pixel p is visible when
//     lineDepth <= max(surface depths of p's 3x3 neighbourhood) + uTolerance.
// At an occluding contour the surface turns edge-on, so the pixel centre next to the contour
// can see the surface far in front of the contour point; a neighbour across the contour sees
// the background or the surface behind the fold. An occluder covering the whole neighbourhood
// hides the line. For one pixel the test holds for some line fragment iff it holds for the
// nearest, so testing each fragment (pass 2) and testing the nearest (pass 3) agree.
uniform sampler2D uSurfaceDepth;
uniform float uTolerance;

bool lineVisible(float lineDepth, ivec2 p) {
    ivec2 last = textureSize(uSurfaceDepth, 0) - 1;
    float farthest = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), last);
            farthest = max(farthest, texelFetch(uSurfaceDepth, q, 0).r);
        }
    return lineDepth <= farthest + uTolerance;
}
