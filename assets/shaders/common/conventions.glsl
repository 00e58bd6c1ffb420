// iblab's coordinate conventions: ONE definition, compiled both as GLSL (through the
// shader library) and as C++ (renderer/ibl/conventions.hpp includes this file with glm
// in scope). Keep it in the common subset of both languages: no swizzles, no out
// parameters, float literals with an f suffix, functions marked IBL_FN.
//
// World: right-handed, +Y up, the default camera looks down -Z.
// Equirectangular image: row 0 (the first scanline in memory and in the file, GL texture
// coordinate v = 0) is the zenith +Y; the last row is the nadir -Y.
// Longitude: u = 0.5 is -Z (the centre of the panorama is straight ahead of the default
// camera) and u grows towards +X, so a panorama viewed from the inside is not mirrored:
//   u = 0.5 + atan(x, -z) / (2 pi),   v = acos(y) / pi.
// Cube faces follow the OpenGL cube-map table (GL 4.6 spec, table 8.19): face index
// 0..5 = +X, -X, +Y, -Y, +Z, -Z, with face-local (s, t) in [0, 1] where t = 0 is the
// first row stored for that face.

const float IBL_PI = 3.14159265358979f;

IBL_FN vec2 directionToEquirectUv(vec3 d)
{
    float u = 0.5f + atan(d.x, -d.z) * (0.5f / IBL_PI);
    float v = acos(clamp(d.y, -1.0f, 1.0f)) * (1.0f / IBL_PI);
    return vec2(u, v);
}

IBL_FN vec3 equirectUvToDirection(vec2 uv)
{
    float phi = (uv.x - 0.5f) * (2.0f * IBL_PI);
    float theta = uv.y * IBL_PI;
    float sinTheta = sin(theta);
    return vec3(sinTheta * sin(phi), cos(theta), -sinTheta * cos(phi));
}

// Face-local (s, t) in [0, 1] to a unit direction, per the GL table: the major axis picks
// the face, sc/tc are the two remaining axes with the signs the table prescribes.
IBL_FN vec3 cubeFaceUvToDirection(int face, vec2 st)
{
    float sc = 2.0f * st.x - 1.0f;
    float tc = 2.0f * st.y - 1.0f;
    vec3 d = vec3(0.0f);
    if (face == 0) d = vec3(1.0f, -tc, -sc);
    else if (face == 1) d = vec3(-1.0f, -tc, sc);
    else if (face == 2) d = vec3(sc, 1.0f, tc);
    else if (face == 3) d = vec3(sc, -1.0f, -tc);
    else if (face == 4) d = vec3(sc, -tc, 1.0f);
    else d = vec3(-sc, -tc, -1.0f);
    return normalize(d);
}

// The inverse of cubeFaceUvToDirection: returns (face, s, t) with the face as a float so
// that the result fits one vector type in both languages.
IBL_FN vec3 directionToCubeFaceUv(vec3 d)
{
    vec3 a = abs(d);
    float face = 0.0f;
    float sc = 0.0f;
    float tc = 0.0f;
    float ma = 1.0f;
    if (a.x >= a.y && a.x >= a.z) {
        ma = a.x;
        face = d.x > 0.0f ? 0.0f : 1.0f;
        sc = d.x > 0.0f ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        ma = a.y;
        face = d.y > 0.0f ? 2.0f : 3.0f;
        sc = d.x;
        tc = d.y > 0.0f ? d.z : -d.z;
    } else {
        ma = a.z;
        face = d.z > 0.0f ? 4.0f : 5.0f;
        sc = d.z > 0.0f ? d.x : -d.x;
        tc = -d.y;
    }
    return vec3(face, 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f));
}

// Right-handed rotation about +Y by yaw radians (counter-clockwise seen from above: +X
// goes to -Z). An environment turned by +yaw shows the feature that was at azimuth +yaw
// (from -Z towards +X) straight ahead, so lookups rotate the query direction by -yaw.
IBL_FN vec3 rotateAboutY(vec3 d, float yaw)
{
    float c = cos(yaw);
    float s = sin(yaw);
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}
