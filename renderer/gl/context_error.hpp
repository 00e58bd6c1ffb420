#pragma once
#include <stdexcept>

namespace iblab::gl {
// No usable GL context (missing driver feature, no display, wrong version): one line.
struct ContextError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
}
