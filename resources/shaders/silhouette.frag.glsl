#version 410 core
// Pass 2 of method 1 writes only depth (the line depth buffer has no colour attachment).
void main() {
}
