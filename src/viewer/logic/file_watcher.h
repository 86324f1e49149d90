#pragma once
// Notices saved edits to shader sources (--shader-dir): remembers the size and modification time of
// every *.comp, *.glsl and *.h file under its folders (recursively) and reports which changed,
// appeared or disappeared since the last poll. Polling (cheap for a few dozen files) keeps it
// portable and free of threads.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace amrvk::viewer {

class FileWatcher {
public:
    explicit FileWatcher(std::vector<std::filesystem::path> roots);
    // Files changed since the last call (or since construction), sorted.
    std::vector<std::filesystem::path> poll();

private:
    struct Stamp {
        std::filesystem::file_time_type time;
        uintmax_t size = 0;
        bool operator==(const Stamp&) const = default;
    };
    std::map<std::filesystem::path, Stamp> scan() const;

    std::vector<std::filesystem::path> mRoots;
    std::map<std::filesystem::path, Stamp> mStamps;
};

}  // namespace amrvk::viewer
