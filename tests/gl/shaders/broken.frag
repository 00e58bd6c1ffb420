// Deliberately broken (line 4 uses an undeclared name) to test error reporting.
out vec4 fragColor;
void main() {
    fragColor = vec4(undeclaredThing, 1.0);
}
