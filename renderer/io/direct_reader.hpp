#pragma once
// What the OpenEXR and Radiance .hdr readers of the io layer share (image_codec_direct.cpp,
// hdr_codec_direct.cpp): a reader's header, its recorded error, and reads of the requested
// pixel type, decoded as float and converted for UInt8. Not part of the io layer's face.
#include <algorithm>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "io/error.hpp"
#include "io/image_codec.hpp"

namespace iblab::direct_codec {

// OpenImageIO's float -> uint8 conversion: clamp to [0, 1], scale, round to nearest.
inline void toUInt8(const std::vector<float>& values, void* out)
{
    auto* bytes = static_cast<std::uint8_t*>(out);
    for (std::size_t i = 0; i < values.size(); ++i)
        bytes[i] = std::uint8_t(std::clamp(values[i], 0.0f, 1.0f) * 255.0f + 0.5f);
}

// The part shared by both readers: header, the error they recorded, and the requested
// type, which is decoded as float and converted for UInt8.
class DirectReader : public ImageReader {
public:
    const ImageHeader& header() const override { return header_; }
    bool hasError() const override { return !error_.empty(); }
    std::string takeError() override { return std::exchange(error_, {}); }

    bool readRows(int y0, int y1, int channels, PixelType type, void* out) override
    {
        const ImageHeader& h = header_;
        if (y0 < h.y || y1 > h.y + h.height || y0 >= y1 || channels < 1 || channels > 3 || out == nullptr)
            return fail("rows " + std::to_string(y0) + ".." + std::to_string(y1) + " or " + std::to_string(channels) +
                        " channels are outside the image");
        if (type != PixelType::Float && type != PixelType::UInt8)
            return fail("only float and 8-bit reads are supported");
        try {
            if (type == PixelType::Float)
                return readFloatRows(y0, y1, channels, static_cast<float*>(out));
            std::vector<float> values(std::size_t(y1 - y0) * std::size_t(h.width) * std::size_t(channels));
            if (!readFloatRows(y0, y1, channels, values.data()))
                return false;
            toUInt8(values, out);
            return true;
        } catch (const std::bad_alloc&) {
            return fail("out of memory");
        } catch (const std::exception& e) {
            return fail(e.what());
        }
    }

    bool readImage(int channels, PixelType type, void* out) override
    {
        return readRows(header_.y, header_.y + header_.height, channels, type, out);
    }

protected:
    virtual bool readFloatRows(int y0, int y1, int channels, float* out) = 0;
    bool fail(std::string why)
    {
        error_ = oneLine(why);
        return false;
    }
    ImageHeader header_;

private:
    std::string error_;
};

} // namespace iblab::direct_codec
