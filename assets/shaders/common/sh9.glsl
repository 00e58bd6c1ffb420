// Order-3 real spherical harmonics, GLSL side of renderer/ibl/sh.hpp: the same nine
// functions in the same order and signs (kSh9Convention: Sloan 2008's constants, no
// Condon-Shortley phase, evaluated on world axes x, y, z with +Y up):
//   (0,0), (1,-1) y, (1,0) z, (1,1) x, (2,-2) xy, (2,-1) yz, (2,0) 3z^2-1, (2,1) xz, (2,2) x^2-y^2.
// Whether coefficients are radiance L_lm or irradiance E_lm is the caller's business;
// sh9Evaluate returns whichever quantity they encode.

void sh9Basis(vec3 d, out float Y[9])
{
    Y[0] = 0.28209479177387814;  // 1/2 sqrt(1/pi)
    Y[1] = 0.4886025119029199 * d.y; // sqrt(3/(4 pi))
    Y[2] = 0.4886025119029199 * d.z;
    Y[3] = 0.4886025119029199 * d.x;
    Y[4] = 1.0925484305920792 * d.x * d.y; // 1/2 sqrt(15/pi)
    Y[5] = 1.0925484305920792 * d.y * d.z;
    Y[6] = 0.31539156525252005 * (3.0 * d.z * d.z - 1.0); // 1/4 sqrt(5/pi)
    Y[7] = 1.0925484305920792 * d.x * d.z;
    Y[8] = 0.5462742152960396 * (d.x * d.x - d.y * d.y); // 1/4 sqrt(15/pi)
}

vec3 sh9Evaluate(vec3 coefficients[9], vec3 direction)
{
    float Y[9];
    sh9Basis(normalize(direction), Y);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 9; ++i)
        sum += coefficients[i] * Y[i];
    return sum;
}
