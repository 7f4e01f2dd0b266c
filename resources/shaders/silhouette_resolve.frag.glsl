#version 410 core
// Pass 3 of method 1: which line pixels are visible, and the lines widened.
// The visibility rule is method 3's (lw/kernels/zbuffer_rules.h resolvePixel) in GL window
// depth, where smaller is nearer and 1 is empty: a line pixel is visible when
//     lineDepth <= max(surface depths of its 3x3 neighbourhood) + uTolerance.
// At an occluding contour the surface turns edge-on, so the pixel centre next to the contour
// can see the surface far in front of the contour point; a neighbour across the contour sees
// the background or the surface behind the fold. An occluder covering the whole neighbourhood
// hides the line.
uniform sampler2D uSurfaceDepth;
uniform sampler2D uLineDepth;
uniform float uTolerance;
uniform bool uVisibility;
uniform int uRadius; // square dilation radius of the widened line, pixels
uniform vec4 uLineColour;

out vec4 fragColour;

bool visibleLineAt(ivec2 p, ivec2 last) {
    float line = texelFetch(uLineDepth, p, 0).r;
    if (line >= 1.0)
        return false;
    if (!uVisibility)
        return true;
    float farthest = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), last);
            farthest = max(farthest, texelFetch(uSurfaceDepth, q, 0).r);
        }
    return line <= farthest + uTolerance;
}

void main() {
    ivec2 last = textureSize(uLineDepth, 0) - 1;
    ivec2 p = ivec2(gl_FragCoord.xy);
    for (int dy = -uRadius; dy <= uRadius; ++dy)
        for (int dx = -uRadius; dx <= uRadius; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThanEqual(q, last)) &&
                visibleLineAt(q, last)) {
                fragColour = uLineColour;
                return;
            }
        }
    discard;
}
