#pragma once
// One number in the lab's reports and labels, printf-style ("%g", "%.3g"), the same digits
// whatever locale a stream carries.
#include <cstdio>
#include <string>

namespace iblab::lab {

inline std::string formatNumber(double value, const char* format)
{
    char text[48];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

} // namespace iblab::lab
