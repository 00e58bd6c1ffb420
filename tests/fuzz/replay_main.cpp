// Replays inputs through a libFuzzer target without libFuzzer, so that every test run (built
// with the normal compiler, no clang needed) feeds the target the committed corpus under
// tests/fuzz/corpus/: the seeds, and each input that once made the target fail, kept there
// once fixed. A failing input traps (the targets __builtin_trap on a broken contract) or
// crashes, which fails the test.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <sys/resource.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv)
{
    // libFuzzer fails an input that needs more than -rss_limit_mb (2 GB in scripts/fuzz.sh).
    // Here a 1 GB address-space limit (the corpus files are all tiny) turns such a request
    // into a failed allocation, which the loaders must report as their own error.
#ifndef __SANITIZE_ADDRESS__ // AddressSanitizer reserves terabytes of shadow address space
    const rlimit addressSpace{.rlim_cur = rlim_t(1) << 30, .rlim_max = rlim_t(1) << 30};
    setrlimit(RLIMIT_AS, &addressSpace);
#endif
    namespace fs = std::filesystem;
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i) {
        if (fs::is_directory(argv[i])) {
            for (const auto& entry : fs::directory_iterator(argv[i]))
                if (entry.is_regular_file()) inputs.push_back(entry.path());
        } else {
            inputs.emplace_back(argv[i]);
        }
    }
    std::sort(inputs.begin(), inputs.end());
    if (inputs.empty()) {
        std::fprintf(stderr, "replay: no inputs given\n");
        return 2;
    }
    for (const fs::path& input : inputs) {
        std::ifstream file(input, std::ios::binary);
        if (!file) {
            std::fprintf(stderr, "replay: cannot read %s\n", input.c_str());
            return 2;
        }
        const std::vector<char> bytes{std::istreambuf_iterator<char>(file), {}};
        std::printf("replay: %s (%zu bytes)\n", input.c_str(), bytes.size());
        std::fflush(stdout); // so that a crash names the input it died on
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("replay: %zu inputs, all handled\n", inputs.size());
    return 0;
}
