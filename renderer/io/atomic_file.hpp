#pragma once
// Atomic file replacement: readers (and a crash half-way) see either the complete old file
// or the complete new one, never a torn mix. The new content goes to a temporary file in
// the SAME directory (rename(2) is atomic only within one file system), is flushed to disk
// (unless the caller says it need not be: Durability), then renamed over the target. On any
// failure the temporary file is removed, the target is left as it was, and iblab::Error says why ("out/a.png: cannot create a temporary
// file in 'out': No such file or directory").
#include <functional>
#include <string>
#include <string_view>

#include "io/error.hpp"

namespace iblab {

// Flush: the new content is flushed to disk (fsync, and the directory) before and after
// the rename, so that a power cut leaves the old file or the complete new one.
// NoFlush: the rename is as atomic for every reader while the system runs, but after a
// power cut the file may be empty or short. Only for files that are checked when read and
// can be made again: the bake cache, whose corrupt entries are reported and rebuilt, and
// whose ~11 files a bake would otherwise wait ~10 ms each for (ext4 here: docs/bake.md).
enum class Durability { Flush, NoFlush };

// Reserves a fresh temporary path next to `path`, calls writeTemp(tempPath) to fill it
// (the callback may overwrite or truncate the file, e.g. through an image library that
// opens the path itself), then renames it onto `path`. Exceptions thrown by writeTemp
// propagate after the temporary file is removed; other failures throw iblab::Error.
void writeFileAtomic(const std::string& path, const std::function<void(const std::string& tempPath)>& writeTemp,
                     Durability durability = Durability::Flush);

// Creates or truncates `path` and writes `contents` to it, not atomically (a writeTemp
// callback's last step); throws iblab::Error naming the path.
void writeWholeFile(const std::string& path, std::string_view contents);

// writeFileAtomic for a whole text (or binary) payload.
void writeTextFileAtomic(const std::string& path, std::string_view contents, Durability durability = Durability::Flush);

// Reads a whole file; throws iblab::Error naming the file when it cannot.
std::string readTextFile(const std::string& path);

// Throws iblab::Error naming `path` where it is missing ("no such file") or a directory ("is a
// directory, not a file"), before a reader opens it: a stream opens a directory on Linux, reads
// it as nothing and reports a size it does not have.
void requireFile(const std::string& path);

// Why `path` could not be opened for reading, after an open that failed with `error` (errno):
// requireFile's reasons where they apply (it may have changed since), else the system's.
Error cannotOpenForReading(const std::string& path, int error);

} // namespace iblab
