#include "session/script.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/file_io.h"

namespace amrvk::session {

namespace {

// Argument count and which arguments are numbers, per action.
struct Signature {
    size_t count;
    std::vector<size_t> numbers;
};

const std::map<std::string, Signature>& signatures() {
    static const std::map<std::string, Signature> table = {
        {"orbit", {2, {0, 1}}},   {"pan", {2, {0, 1}}},      {"zoom", {1, {0}}},    {"tf-preset", {1, {}}},
        {"tf-range", {2, {0, 1}}}, {"density", {1, {0}}},    {"mode", {1, {}}},     {"traversal", {1, {}}},
        {"sampler", {1, {}}},     {"backend", {1, {}}},      {"grid", {1, {}}},     {"edit-shader", {3, {}}},
        {"reload", {0, {}}},      {"screenshot", {1, {}}},   {"capture-window", {1, {}}}, {"save-session", {1, {}}},   {"quit", {0, {}}}};
    return table;
}

bool parseNumber(const std::string& s, double& out) {
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, out);
    return ec == std::errc() && ptr == end && std::isfinite(out);
}

// Splits a line into words; "..." groups words, \" and \\ escape inside quotes.
std::vector<std::string> words(const std::string& line, const std::string& where) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < line.size()) {
        if (std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
            continue;
        }
        if (line[i] == '#') break;
        std::string w;
        if (line[i] == '"') {
            ++i;
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '\\' && i + 1 < line.size() && (line[i + 1] == '"' || line[i + 1] == '\\')) {
                    w += line[i + 1];
                    i += 2;
                } else if (line[i] == '"') {
                    closed = true;
                    ++i;
                    break;
                } else {
                    w += line[i++];
                }
            }
            AMRVK_CHECK(closed, where, ": unterminated quote");
        } else {
            while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) w += line[i++];
        }
        out.push_back(w);
    }
    return out;
}

}  // namespace

double ScriptAction::number(size_t i) const {
    double v = 0;
    AMRVK_CHECK(i < args.size() && parseNumber(args[i], v), where, ": argument ", i + 1, " of ", name,
                " is not a number");
    return v;
}

std::vector<ScriptAction> parseScript(const std::string& text, const std::string& fileName) {
    std::vector<ScriptAction> out;
    std::istringstream in(text);
    std::string line;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        const std::string where = fileName + ":" + std::to_string(lineNo);
        std::vector<std::string> w = words(line, where);
        if (w.empty()) continue;
        AMRVK_CHECK(w.size() >= 2, where, ": expected FRAME ACTION [ARGS...]");
        double frame = 0;
        AMRVK_CHECK(parseNumber(w[0], frame) && frame >= 0 && frame == std::floor(frame) && frame < 1e15, where,
                    ": frame '", w[0], "' is not a whole number >= 0");
        ScriptAction a;
        a.frame = uint64_t(frame);
        a.name = w[1];
        a.args.assign(w.begin() + 2, w.end());
        a.where = where;
        auto sig = signatures().find(a.name);
        if (sig == signatures().end()) {
            std::string known;
            for (const auto& entry : signatures()) known += (known.empty() ? "" : ", ") + entry.first;
            AMRVK_CHECK(false, where, ": unknown action '", a.name, "' (actions: ", known, ")");
        }
        AMRVK_CHECK(a.args.size() == sig->second.count, where, ": ", a.name, " takes ", sig->second.count,
                    " argument(s), not ", a.args.size());
        for (size_t k : sig->second.numbers) a.number(k);
        AMRVK_CHECK(out.empty() || a.frame >= out.back().frame, where, ": frame ", a.frame, " comes before frame ",
                    out.back().frame, " of the line above");
        out.push_back(std::move(a));
    }
    return out;
}

std::vector<ScriptAction> loadScript(const std::filesystem::path& path) {
    std::error_code ec;
    AMRVK_CHECK(std::filesystem::is_regular_file(path, ec), path.string(), ": no such script file");
    return parseScript(readTextFile(path), path.string());
}

}  // namespace amrvk::session
