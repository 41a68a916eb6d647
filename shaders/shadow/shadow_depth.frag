#version 450 core
// Depth only: the shadow map keeps the nearest surface to the light.
void main() {
}
