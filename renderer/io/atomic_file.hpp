#pragma once
// Atomic file replacement: readers (and a crash half-way) see either the complete old file
// or the complete new one, never a torn mix. The new content goes to a temporary file in
// the SAME directory (rename(2) is atomic only within one file system), is flushed to disk,
// then renamed over the target. On any failure the temporary file is removed, the target
// is left as it was, and iblab::Error says why ("out/a.png: cannot create a temporary
// file in 'out': No such file or directory").
#include <functional>
#include <string>
#include <string_view>

namespace iblab {

// Reserves a fresh temporary path next to `path`, calls writeTemp(tempPath) to fill it
// (the callback may overwrite or truncate the file, e.g. through an image library that
// opens the path itself), then renames it onto `path`. Exceptions thrown by writeTemp
// propagate after the temporary file is removed; other failures throw iblab::Error.
void writeFileAtomic(const std::string& path, const std::function<void(const std::string& tempPath)>& writeTemp);

// writeFileAtomic for a whole text (or binary) payload.
void writeTextFileAtomic(const std::string& path, std::string_view contents);

// Reads a whole file; throws iblab::Error naming the file when it cannot.
std::string readTextFile(const std::string& path);

} // namespace iblab
