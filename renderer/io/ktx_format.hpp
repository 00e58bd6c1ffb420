#pragma once
// Constants of the KTX containers that iblab writes (and may read): the file identifiers,
// the OpenGL enums of KTX 1.1 headers and the Vulkan formats of KTX 2.0 headers, for the
// float formats iblab's bakes use. Values from the specifications (KTX 1.1 section 2,
// KTX 2.0 section 3) and the registries they name (OpenGL's gl.xml, Vulkan's VkFormat).
#include <array>
#include <cstdint>

namespace iblab::ktx {

// KTX 1.1 section 2.1: "«KTX 11»\r\n\x1A\n".
inline constexpr std::array<std::uint8_t, 12> kKtx1Identifier{0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
// KTX 2.0 section 3.1: "«KTX 20»\r\n\x1A\n".
inline constexpr std::array<std::uint8_t, 12> kKtx2Identifier{0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
// KTX 1.1 section 2.2: written in the writer's byte order, read back as this value when the
// reader's order is the same.
inline constexpr std::uint32_t kKtx1Endianness = 0x04030201u;

// OpenGL enums (KTX 1.1 sections 2.3-2.7).
inline constexpr std::uint32_t kGlHalfFloat = 0x140B; // GL_HALF_FLOAT (glType)
inline constexpr std::uint32_t kGlFloat = 0x1406;     // GL_FLOAT (glType)
inline constexpr std::uint32_t kGlRgba = 0x1908;      // GL_RGBA (glFormat, glBaseInternalFormat)
inline constexpr std::uint32_t kGlRg = 0x8227;        // GL_RG
inline constexpr std::uint32_t kGlRgba16f = 0x881A;   // GL_RGBA16F (glInternalFormat)
inline constexpr std::uint32_t kGlRgba32f = 0x8814;   // GL_RGBA32F
inline constexpr std::uint32_t kGlR11fG11fB10f = 0x8C3A; // GL_R11F_G11F_B10F: what cmgen writes

// Vulkan formats (KTX 2.0 section 3.2, vkFormat).
inline constexpr std::uint32_t kVkR16g16b16a16Sfloat = 97;  // VK_FORMAT_R16G16B16A16_SFLOAT
inline constexpr std::uint32_t kVkR32g32b32a32Sfloat = 109; // VK_FORMAT_R32G32B32A32_SFLOAT

// KTX 2.0 header size (section 3: identifier, nine uint32 fields, the index of four uint32
// and two uint64) and one level index entry (section 3.9: three uint64).
inline constexpr std::size_t kKtx2HeaderBytes = 80;
inline constexpr std::size_t kKtx2LevelIndexEntryBytes = 24;

// Khronos Data Format 1.3 (the KTX 2.0 DFD, section 3.10): the basic descriptor block's
// values for linear RGBA floats.
inline constexpr std::uint32_t kDfdModelRgbsda = 1;
inline constexpr std::uint32_t kDfdPrimariesBt709 = 1;
inline constexpr std::uint32_t kDfdTransferLinear = 1;
inline constexpr std::uint32_t kDfdChannelR = 0, kDfdChannelG = 1, kDfdChannelB = 2, kDfdChannelA = 15;
inline constexpr std::uint32_t kDfdQualifierFloat = 0x80, kDfdQualifierSigned = 0x40;
inline constexpr std::uint32_t kDfdVersion = 2; // KHR_DF_VERSIONNUMBER_1_3

// Texel storage of the writers: half floats (GL_RGBA16F / VK_FORMAT_R16G16B16A16_SFLOAT)
// or 32-bit floats (GL_RGBA32F / VK_FORMAT_R32G32B32A32_SFLOAT).
enum class PixelType { Half, Float };

} // namespace iblab::ktx
