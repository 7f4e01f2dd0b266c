#version 410 core
// Silhouette lines in one flat colour (no anti-aliasing, so a line drawing turns into a pixel
// mask by comparing with the background).
uniform vec4 uLineColour;

out vec4 fragColour;

void main() {
    fragColour = uLineColour;
}
