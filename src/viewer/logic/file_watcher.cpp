#include "viewer/logic/file_watcher.h"

namespace fs = std::filesystem;

namespace amrvk::viewer {

FileWatcher::FileWatcher(std::vector<fs::path> roots) : mRoots(std::move(roots)) { mStamps = scan(); }

std::map<fs::path, FileWatcher::Stamp> FileWatcher::scan() const {
    std::map<fs::path, Stamp> out;
    for (const fs::path& root : mRoots) {
        std::error_code ec;
        for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end; it.increment(ec)) {
            const fs::path& p = it->path();
            const std::string ext = p.extension().string();
            if (ext != ".comp" && ext != ".glsl" && ext != ".h") continue;
            std::error_code e1, e2;
            const auto time = fs::last_write_time(p, e1);
            const auto size = fs::file_size(p, e2);
            if (!e1 && !e2) out[fs::weakly_canonical(p, e1)] = {time, size};
        }
    }
    return out;
}

std::vector<fs::path> FileWatcher::poll() {
    std::map<fs::path, Stamp> now = scan();
    std::vector<fs::path> changed;
    for (const auto& [p, stamp] : now) {
        auto it = mStamps.find(p);
        if (it == mStamps.end() || !(it->second == stamp)) changed.push_back(p);
    }
    for (const auto& [p, stamp] : mStamps)
        if (!now.count(p)) changed.push_back(p);
    mStamps = std::move(now);
    return changed;
}

}  // namespace amrvk::viewer
