// The glTF test models and their writers (a one-triangle model, .gltf + .bin and .glb), and
// the checks on load errors and warnings, shared by the glTF robustness and features tests.
#include "gltf_test_files.hpp"

#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "io/error.hpp"

namespace iblab::testing {

using nlohmann::json;

int GltfBuilder::accessor(int view, int componentType, std::size_t count, const char* type, bool normalized)
{
    json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (view >= 0)
        a["bufferView"] = view;
    if (normalized)
        a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size() - 1);
}

GltfBuilder triangle()
{
    GltfBuilder b;
    const int position = b.accessor(b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}), kFloat, 3, "VEC3");
    const int uv = b.accessor(b.view(std::vector<float>{0, 1, 1, 1, 0, 0}), kFloat, 3, "VEC2");
    const int indices = b.accessor(b.view(std::vector<std::uint16_t>{0, 1, 2}), kUShort, 3, "SCALAR");
    const json primitive = {{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}, {"indices", indices}};
    b.doc["meshes"] = json::array({json::object({{"primitives", json::array({primitive})}})});
    b.doc["nodes"] = {{{"mesh", 0}}};
    b.doc["scenes"] = {{{"nodes", {0}}}};
    return b;
}

void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string writeGltf(const TempDir& dir, GltfBuilder b, const std::string& name)
{
    if (!b.doc.contains("buffers")) {
        const std::string binName = name.substr(0, name.find('.')) + ".bin";
        writeBytes(dir.file(binName), std::string(b.bin.begin(), b.bin.end()));
        b.doc["buffers"] = {{{"uri", binName}, {"byteLength", b.bin.size()}}};
    }
    writeBytes(dir.file(name), b.doc.dump());
    return dir.file(name);
}

namespace {

void appendU32(std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

} // namespace

std::string glbBytes(GltfBuilder b)
{
    b.doc["buffers"] = {{{"byteLength", b.bin.size()}}};
    std::string text = b.doc.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    b.bin.resize((b.bin.size() + 3) / 4 * 4, 0);
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, std::uint32_t(12 + 8 + text.size() + 8 + b.bin.size()));
    appendU32(out, std::uint32_t(text.size()));
    appendU32(out, 0x4E4F534A);
    out += text;
    appendU32(out, std::uint32_t(b.bin.size()));
    appendU32(out, 0x004E4942);
    out.append(b.bin.begin(), b.bin.end());
    return out;
}

std::string writeGlb(const TempDir& dir, const GltfBuilder& b, const std::string& name)
{
    writeBytes(dir.file(name), glbBytes(b));
    return dir.file(name);
}

std::string expectLoadError(const std::string& path, std::initializer_list<std::string> fragments,
                            const ModelLoadOptions& options)
{
    try {
        const ModelData m = loadGltfModel(path, options);
        ADD_FAILURE() << path << " loaded (" << m.instances.size() << " instances) but should not";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << "does not start with the path: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        for (const std::string& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
        return what;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not an iblab::Error: " << e.what();
    }
    return "";
}

void expectTriangleWithFails(const TempDir& dir, const std::string& pointer, const json& value,
                             std::initializer_list<std::string> fragments)
{
    GltfBuilder b = triangle();
    b.doc[json::json_pointer(pointer)] = value;
    SCOPED_TRACE(pointer + " = " + value.dump());
    expectLoadError(writeGltf(dir, b), fragments);
}

bool anyWarningContains(const ModelData& m, std::initializer_list<std::string> fragments)
{
    return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const std::string& w) {
        return std::all_of(fragments.begin(), fragments.end(), [&](const std::string& f) { return w.find(f) != std::string::npos; });
    });
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string joined(const std::vector<std::string>& lines)
{
    std::string out;
    for (const std::string& line : lines) out += line + "\n";
    return out;
}

void addTexturedMaterial(GltfBuilder& b, const std::string& uri)
{
    b.doc["images"] = {{{"uri", uri}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}}}}};
    b.primitive()["material"] = 0;
}

void writePng(const std::string& path, int w, int h, const std::vector<std::uint8_t>& rgba)
{
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgba.data()));
    ASSERT_TRUE(out->close());
}

} // namespace iblab::testing
