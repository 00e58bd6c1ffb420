#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include <unistd.h>

#include "cli.hpp"

namespace {

// `iblab bake` spends much of its time faulting in fresh memory: the decoded map, llvmpipe's
// textures, the read-backs (tens of MB, 4 KiB page by page). Where transparent huge pages are
// in "madvise" mode (the kernel default), glibc's malloc asks for them only when its
// glibc.malloc.hugetlb tunable is 1, and tunables are read once, when a process starts. So a
// bake restarts itself once with the tunable set: `scripts/measure-bake.sh hugepages` measures
// both ways in one run (about 10% of the process time on the machine the README names). A
// GLIBC_TUNABLES that already names the tunable (the restarted process, or a user who set it,
// to 0 for instance) is left as it is; so is a failed exec, which runs the bake without.
void restartWithHugePagesForBake(char** argv)
{
    bool bake = false;
    for (char** arg = argv + 1; *arg; ++arg) {
        const std::string_view a(*arg);
        if (a == "--help" || a == "-h" || a == "--version") return; // prints, allocates nothing much
        bake = bake || a == "bake";
    }
    if (!bake) return;
    const char* current = std::getenv("GLIBC_TUNABLES");
    if (current && std::strstr(current, "glibc.malloc.hugetlb")) return;
    const std::string previous = current ? current : "";
    const std::string tunables = (previous.empty() ? "" : previous + ":") + "glibc.malloc.hugetlb=1";
    if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
    ::execv("/proc/self/exe", argv);
    if (previous.empty())
        ::unsetenv("GLIBC_TUNABLES");
    else
        ::setenv("GLIBC_TUNABLES", previous.c_str(), 1);
}

} // namespace

int main(int argc, char** argv)
{
    restartWithHugePagesForBake(argv);
    return iblab::app::runCommandLine(argc, argv);
}
