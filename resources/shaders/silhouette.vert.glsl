#version 410 core
// Pass 2 of method 1: vertices go to the geometry shader untransformed, because the silhouette
// test d = N . (eye - B) works in patient coordinates.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

out vec3 vPosition;
out vec3 vNormal;

void main() {
    vPosition = aPosition;
    vNormal = aNormal;
    gl_Position = vec4(aPosition, 1.0);
}
