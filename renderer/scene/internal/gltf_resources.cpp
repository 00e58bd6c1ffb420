// Reading a glTF's external bytes safely: the input budget, regular files inside the
// model's folder, URIs (percent-decoding, resolution, quoting for messages) and data URIs
// with base64 in both directions.
#include "scene/internal/gltf_resources.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/error.hpp"
#include "scene/internal/glb_container.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab::scene_detail {

namespace fs = std::filesystem;

InputBudget::InputBudget(std::uint64_t limit) : limit_(std::min(limit, kMaxGlbBytes)) {}

void InputBudget::take(const std::string& path, const std::string& what, std::uint64_t bytes)
{
    if (bytes > left())
        throw Error(path, what + " needs " + bytesText(bytes) + ", more than the " + bytesText(left()) +
                              " left of the " + bytesText(limit_) + " input budget (ModelLoadOptions::maxInputBytes)");
    used_ += bytes;
}

std::optional<std::vector<std::uint8_t>> readFilePrefix(const fs::path& file, std::uint64_t wantBytes,
                                                        std::string& problem)
{
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (ec || !fs::exists(status)) {
        problem = "not found";
        return std::nullopt;
    }
    if (!fs::is_regular_file(status)) {
        problem = fs::is_directory(status) ? "is a folder, not a file" : "is not a regular file";
        return std::nullopt;
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        problem = std::string("cannot be opened: ") + std::strerror(errno);
        return std::nullopt;
    }
    std::vector<std::uint8_t> bytes(wantBytes);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(wantBytes));
    bytes.resize(std::size_t(in.gcount()));
    if (in.bad()) {
        problem = "cannot be read";
        return std::nullopt;
    }
    return bytes;
}

std::uint64_t fileSize(const fs::path& file)
{
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    return ec ? 0 : std::uint64_t(size);
}

std::string percentDecode(std::string_view text)
{
    const auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size() && hex(text[i + 1]) >= 0 && hex(text[i + 2]) >= 0) {
            out += char(hex(text[i + 1]) * 16 + hex(text[i + 2]));
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out;
}

std::string quoteUri(std::string_view uri)
{
    std::string out = "'";
    for (char c : uri.substr(0, 80)) out += (std::isprint(static_cast<unsigned char>(c)) ? c : '?');
    if (uri.size() > 80)
        out += "...";
    return out + "'";
}

std::optional<fs::path> resolveInsideFolder(const fs::path& folder, std::string_view uri, std::string& problem)
{
    const std::string decoded = percentDecode(uri);
    if (decoded.empty()) {
        problem = "is empty";
        return std::nullopt;
    }
    if (decoded.find('\0') != std::string::npos) {
        problem = "contains a NUL character";
        return std::nullopt;
    }
    const std::size_t colon = decoded.find(':');
    const std::size_t firstSeparator = decoded.find_first_of("/\\");
    if (colon != std::string::npos && colon < firstSeparator) {
        problem = "uses the scheme '" + decoded.substr(0, colon) + ":'; only relative file paths and data: URIs are read";
        return std::nullopt;
    }
    if (decoded.front() == '/' || decoded.front() == '\\') {
        problem = "is an absolute path; only paths relative to the model's folder are read";
        return std::nullopt;
    }
    fs::path relative;
    int depth = 0;
    std::size_t start = 0;
    while (start <= decoded.size()) {
        const std::size_t end = std::min(decoded.find_first_of("/\\", start), decoded.size());
        const std::string part = decoded.substr(start, end - start);
        start = end + 1;
        if (part.empty() || part == ".")
            continue;
        if (part == "..") {
            if (--depth < 0) {
                problem = "points outside the model's folder";
                return std::nullopt;
            }
        } else {
            ++depth;
        }
        relative /= part;
    }
    return folder / relative;
}

std::optional<DataUri> parseDataUri(std::string_view uri)
{
    if (uri.size() < 5 || !std::equal(uri.begin(), uri.begin() + 5, "data:", [](char a, char b) {
            return std::tolower(static_cast<unsigned char>(a)) == b;
        }))
        return std::nullopt;
    const std::size_t comma = uri.find(',');
    if (comma == std::string_view::npos)
        return DataUri{};
    std::string_view header = uri.substr(5, comma - 5);
    DataUri d;
    d.payload = uri.substr(comma + 1);
    if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
        d.base64 = true;
        header.remove_suffix(7);
    }
    d.mimeType = std::string(header.substr(0, header.find(';')));
    return d;
}

namespace {

// An upper bound of the decoded size, known before decoding: what the budget checks.
std::uint64_t decodedSizeBound(const DataUri& d) { return d.base64 ? (d.payload.size() / 4 + 1) * 3 : d.payload.size(); }

bool decodeBase64(std::string_view text, std::vector<std::uint8_t>& out)
{
    static const std::array<std::int8_t, 256> table = [] {
        std::array<std::int8_t, 256> t{};
        t.fill(-1);
        const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(alphabet[i])] = std::int8_t(i);
        t['-'] = 62; // base64url, which some writers use
        t['_'] = 63;
        return t;
    }();
    while (!text.empty() && text.back() == '=') text.remove_suffix(1);
    out.clear();
    out.reserve(text.size() / 4 * 3 + 3);
    std::uint32_t acc = 0;
    int bits = 0;
    for (char c : text) {
        const int v = table[static_cast<unsigned char>(c)];
        if (v < 0)
            return false;
        acc = (acc << 6) | std::uint32_t(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(std::uint8_t((acc >> bits) & 0xFF));
        }
    }
    return true;
}

} // namespace

std::vector<std::uint8_t> decodeDataUri(const DataUri& d, const std::string& path, const std::string& what,
                                        InputBudget& budget)
{
    budget.take(path, what + " (data URI)", decodedSizeBound(d));
    std::vector<std::uint8_t> bytes;
    if (d.base64) {
        if (!decodeBase64(d.payload, bytes))
            throw Error(path, what + " is a data URI that is not valid base64");
    } else {
        const std::string text = percentDecode(d.payload);
        bytes.assign(text.begin(), text.end());
    }
    return bytes;
}

std::string encodeBase64(const std::vector<std::uint8_t>& bytes)
{
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t n = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0u);
        out += alphabet[(n >> 18) & 63];
        out += alphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
    }
    return out;
}

} // namespace iblab::scene_detail
