// Every lit mesh: world-space position, normal and tangent for the material shader.
// Attribute locations are renderer/gpu_mesh.hpp's MeshAttribute.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec2 aUv0;
layout(location = 4) in vec2 aUv1;

uniform mat4 uModel;
uniform mat3 uNormalMatrix; // inverse transpose of uModel's upper 3x3: normals stay normal under non-uniform scale
uniform mat4 uViewProjection;

// pbr.frag chooses where they are interpolated (pixel centre or centroid): see there.
out vec3 vWorldPosition;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv0;
out vec2 vUv1;

void main()
{
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    vTangent = vec4(mat3(uModel) * aTangent.xyz, aTangent.w);
    vUv0 = aUv0;
    vUv1 = aUv1;
    gl_Position = uViewProjection * world;
}
