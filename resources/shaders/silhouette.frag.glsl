#version 410 core
// Pass 2 of method 1: the line's depth, and its colour where the renderer lets it write colour
// (one-pixel lines of a frame drawn in one call; otherwise pass 3 colours the lines). With
// LW_TEST_VISIBILITY (a frame drawn in one call, so the surface depth is complete) hidden line
// fragments are dropped here, where only line fragments pay for the test; a frame drawn in
// pieces leaves the test to pass 3. The renderer prepends the #defines and
// silhouette_visibility.glsl.
// With LW_STAMP (a frame read only as a line mask) the visible fragments write the frame's stamp
// into an integer texture instead: a pixel holds a line of this frame where it holds this
// frame's stamp, so that texture is never cleared (the mask's stage compares).
#if LW_STAMP
uniform uint uStamp;
out uvec4 fragStamp;
#else
uniform vec4 uLineColour;
out vec4 fragColour;
#endif

void main() {
#if LW_TEST_VISIBILITY
    if (!lineVisible(gl_FragCoord.z, ivec2(gl_FragCoord.xy)))
        discard;
#endif
#if LW_STAMP
    fragStamp = uvec4(uStamp);
#else
    fragColour = uLineColour;
#endif
}
