#version 430 core
// Method 1's line mask for the host, made where the frame is: byte i of the output (pixels in
// rows, the top row first, as PixelMask holds them) is 1 where the colour texture's red differs
// from the background's, else 0; or, for a frame read only as a mask, where the stamp texture
// holds the frame's stamp (silhouette.frag.glsl, LW_STAMP). GL's rows run bottom-up, hence the
// flip. Each invocation packs four bytes into one uint, which the host reads back as bytes
// (little-endian).
layout(local_size_x = 256) in;

layout(binding = 0) uniform sampler2D uColour;
layout(binding = 1) uniform usampler2D uStamps;
layout(std430, binding = 0) writeonly buffer Mask { uint words[]; };

uniform ivec2 uSize;
uniform uint uBackgroundRed;
uniform uint uStamp; // 0: the colour texture

void main() {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint word = group * gl_WorkGroupSize.x + gl_LocalInvocationIndex;
    uint pixels = uint(uSize.x) * uint(uSize.y);
    if (4u * word >= pixels)
        return;
    uint bits = 0u;
    for (uint k = 0u; k < 4u; ++k) {
        uint i = 4u * word + k;
        if (i >= pixels)
            break;
        int x = int(i % uint(uSize.x));
        int y = int(i / uint(uSize.x));
        ivec2 texel = ivec2(x, uSize.y - 1 - y);
        bool line = uStamp != 0u
                        ? texelFetch(uStamps, texel, 0).r == uStamp
                        : uint(round(texelFetch(uColour, texel, 0).r * 255.0)) != uBackgroundRed;
        bits |= (line ? 1u : 0u) << (8u * k);
    }
    words[word] = bits;
}
