// One triangle that covers the viewport; no vertex buffer needed (the VAO is empty).
out vec2 vUv;

void main()
{
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vUv = corner;
#ifdef AT_FAR_PLANE
    // Depth 1: drawn after the meshes with GL_LEQUAL, the sky only shades uncovered pixels.
    gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
#else
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
#endif
}
