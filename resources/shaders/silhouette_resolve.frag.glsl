#version 410 core
// Pass 3 of method 1: the visible line pixels as antialiased strokes of the line width through
// their centres, the rule of lw::render::PixelMask::strokeCoverage (the panels' strokes):
// coverage = clamp(uReach - d, 0, 1), d the distance to the nearest visible line pixel within
// LW_RADIUS, uReach = line width / 2 + 0.5; the renderer blends the line colour by it.
// With LW_VISIBILITY (a frame drawn in pieces) the nearest line of each pixel is tested here
// (silhouette_visibility.glsl); otherwise pass 2 has dropped the hidden ones already. The
// renderer prepends the #defines and that file: constant loop bounds, which a software
// rasterizer (llvmpipe) runs several times faster than loops over uniforms.
uniform sampler2D uLineDepth;
uniform vec4 uLineColour;
uniform float uReach;

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
    float coverage = 0.0;
    for (int dy = -LW_RADIUS; dy <= LW_RADIUS; ++dy)
        for (int dx = -LW_RADIUS; dx <= LW_RADIUS; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThanEqual(q, last)) &&
                visibleLineAt(q))
                coverage = max(coverage, clamp(uReach - length(vec2(dx, dy)), 0.0, 1.0));
        }
    if (coverage <= 0.0)
        discard;
    fragColour = vec4(uLineColour.rgb, uLineColour.a * coverage);
}
