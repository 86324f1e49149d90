#include "python/keyword_messages.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <vector>

#include "session/setting_table.h"

namespace amrvk::python {

namespace {

struct Rename {
    std::string_view option;   // as the CLI spells it
    std::string_view keyword;  // as Python spells it (Renderer, Volume, TransferFunction keywords)
};

// The options that are not settings of session::settingTable(), and those of its settings that
// Python names by more than their keyword; longest first where one is a prefix of another (--nan
// drop before --nan).
constexpr Rename kRenames[] = {
    {"--nan drop", "nan='drop'"},
    {"--frames", "frames"},
    {"--orbit", "orbit"},
    {"--series-range", "tf_range"},
    {"--size", "size (width, height)"},
    {"--light-dir", "lights (a directional light)"},
    {"--light-point", "lights (a point light)"},
    {"--device", "device"},
    {"--shader-dir", "shader_dir"},
    {"--gpu-timeout", "gpu_timeout"},
    {"--samples-per-invocation", "samples_per_invocation"},
    {"--scale", "scale"},
    {"--log-floor", "log_floor"},
    {"--nan", "nan"},
    {"--format", "format"},
    {"--field", "field"},
    {"--dims", "dims"},
    {"--type", "type"},
    {"--threshold", "threshold"},
};

bool optionChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// Every rename: the table's settings (session/setting_table.h), then the others above.
const std::vector<Rename>& renames() {
    static const std::vector<Rename> kAll = [] {
        std::vector<Rename> all;
        for (const session::Setting& st : session::settingTable()) {
            const bool said = std::any_of(std::begin(kRenames), std::end(kRenames),
                                          [&](const Rename& r) { return r.option == st.option; });
            if (!said && !st.keyword.empty() && st.keyword.find('|') == std::string_view::npos)
                all.push_back({st.option, st.keyword});
        }
        all.insert(all.end(), std::begin(kRenames), std::end(kRenames));
        return all;
    }();
    return kAll;
}

}  // namespace

std::string keywordMessage(std::string_view message) {
    std::string out;
    out.reserve(message.size());
    size_t i = 0;
    while (i < message.size()) {
        const bool tokenStart = message.compare(i, 2, "--") == 0 && (i == 0 || !optionChar(message[i - 1]));
        const Rename* hit = nullptr;
        if (tokenStart)
            for (const Rename& r : renames()) {
                const size_t end = i + r.option.size();
                if (message.compare(i, r.option.size(), r.option) == 0 &&
                    (end == message.size() || !optionChar(message[end]))) {
                    hit = &r;
                    break;
                }
            }
        if (hit) {
            out += hit->keyword;
            i += hit->option.size();
        } else {
            out += message[i++];
        }
    }
    return out;
}

}  // namespace amrvk::python
