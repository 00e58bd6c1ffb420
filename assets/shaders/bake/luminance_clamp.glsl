// A texel's radiance with its luminance clamped to a threshold, chroma kept: the bright-texel
// split's base (renderer/bake/bright_texels.hpp). A texel that is not finite (a half float
// that overflowed) becomes grey at the threshold: its flux is in the lights, summed from the
// float map. Needs common/luminance.glsl.
vec3 clamped(vec3 rgb, float y, float threshold)
{
    if (isinf(y) || isnan(y))
        return vec3(threshold);
    return y > threshold ? rgb * (threshold / y) : rgb;
}
