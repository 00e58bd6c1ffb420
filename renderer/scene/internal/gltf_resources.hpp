#pragma once
// PRIVATE to iblab_scene: where a glTF document's bytes come from, read as if every file
// were hostile. Files are read only from inside the model's folder (URIs are resolved with
// no schemes, absolute paths or climbing "..") and only when they are regular files; data
// URIs are decoded (base64 or percent-encoded) only after their size bound has been charged
// to the input budget, which counts everything read or decoded against
// ModelLoadOptions::maxInputBytes. Also base64 encoding, for the exporter's data URIs.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace iblab::scene_detail {

// Counts what has been read or decoded so far against ModelLoadOptions::maxInputBytes
// (at most kMaxGlbBytes is honoured).
class InputBudget {
public:
    explicit InputBudget(std::uint64_t limit);
    std::uint64_t left() const { return limit_ - used_; }
    std::uint64_t limit() const { return limit_; }
    // Throws naming `what` when `bytes` more would not fit.
    void take(const std::string& path, const std::string& what, std::uint64_t bytes);

private:
    std::uint64_t limit_;
    std::uint64_t used_ = 0;
};

// Reads up to `wantBytes` from the start of a regular file. FIFOs, devices and folders are
// refused (a FIFO named like a texture would block forever). On failure returns nullopt
// and says why in `problem` ("not found", ...).
std::optional<std::vector<std::uint8_t>> readFilePrefix(const std::filesystem::path& file, std::uint64_t wantBytes,
                                                        std::string& problem);

// The file's size, or 0 when it cannot be had (readFilePrefix then says why).
std::uint64_t fileSize(const std::filesystem::path& file);

// Percent-decoding as URIs need it ("my%20file.png"); malformed escapes stay literal.
std::string percentDecode(std::string_view text);

// A URI as written, quoted for a message; long data URIs and binary junk are cut short
// so that the message stays one readable line.
std::string quoteUri(std::string_view uri);

// Where a relative URI points inside `folder`, or why it may not be read. Only plain
// relative paths qualify: a scheme ("http:", "file:", also "C:"), an absolute path, or
// ".." components that climb above the folder are refused, so that a dropped model can
// only read files that came with it. Backslashes count as separators too (Windows
// exporters write them). Symlinks inside the folder are trusted: the artist made them.
std::optional<std::filesystem::path> resolveInsideFolder(const std::filesystem::path& folder, std::string_view uri,
                                                         std::string& problem);

// A "data:[mime][;base64],payload" URI, split; the payload views the URI's text.
struct DataUri {
    std::string mimeType;
    std::string_view payload;
    bool base64 = false;
};

// nullopt when `uri` is not a data URI at all.
std::optional<DataUri> parseDataUri(std::string_view uri);

// Decodes a data URI after checking its size bound against the budget, so a URI that
// claims or holds a huge payload fails before anything is allocated for it. Throws
// iblab::Error naming `path` and `what` for invalid base64.
std::vector<std::uint8_t> decodeDataUri(const DataUri& uri, const std::string& path, const std::string& what,
                                        InputBudget& budget);

// Standard base64 with padding.
std::string encodeBase64(const std::vector<std::uint8_t>& bytes);

} // namespace iblab::scene_detail
