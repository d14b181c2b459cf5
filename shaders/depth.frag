// Depth pre-pass: writes depth only, so the expensive material shader then runs once per pixel.
void main() {}
