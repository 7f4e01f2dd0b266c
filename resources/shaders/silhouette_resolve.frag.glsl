#version 410 core
// Pass 3 of method 1: colours the line pixels, widened by a square dilation of radius LW_RADIUS.
// With LW_VISIBILITY (a frame drawn in pieces) the nearest line of each pixel is tested here
// (silhouette_visibility.glsl); otherwise pass 2 has dropped the hidden ones already. The
// renderer prepends the #defines and that file: constant loop bounds, which a software
// rasterizer (llvmpipe) runs several times faster than loops over uniforms.
uniform sampler2D uLineDepth;
uniform vec4 uLineColour;

out vec4 fragColour;

bool visibleLineAt(ivec2 p) {
    float line = texelFetch(uLineDepth, p, 0).r;
#if LW_VISIBILITY
    return line < 1.0 && lineVisible(line, p);
#else
    return line < 1.0;
#endif
}

void main() {
    ivec2 last = textureSize(uLineDepth, 0) - 1;
    ivec2 p = ivec2(gl_FragCoord.xy);
    for (int dy = -LW_RADIUS; dy <= LW_RADIUS; ++dy)
        for (int dx = -LW_RADIUS; dx <= LW_RADIUS; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThanEqual(q, last)) &&
                visibleLineAt(q)) {
                fragColour = uLineColour;
                return;
            }
        }
    discard;
}
