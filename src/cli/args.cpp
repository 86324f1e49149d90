#include "cli/args.h"

#include <cstdio>

#include <charconv>
#include <cstdlib>

#include "core/error.h"

namespace amrvk::cli {

Args::Args(const std::string& command, const std::vector<std::string>& argv,
           const std::vector<OptionSpec>& specs, size_t minPositional, size_t maxPositional)
    : mCommand(command) {
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() > 2 && a.rfind("--", 0) == 0) {
            std::string name = a.substr(2), inlineValue;
            bool hasInline = false;
            if (auto eq = name.find('='); eq != std::string::npos) {
                inlineValue = name.substr(eq + 1);
                name = name.substr(0, eq);
                hasInline = true;
            }
            const OptionSpec* spec = nullptr;
            for (const auto& s : specs)
                if (s.name == name) spec = &s;
            AMRVK_CHECK(spec, "unknown option '--", name, "' for 'amrvk ", command,
                        "' (see amrvk ", command, " --help)");
            AMRVK_CHECK(spec->repeatable || !mValues.count(name), "option --", name,
                        " given twice");
            auto& vals = mValues[name];
            if (hasInline) {
                AMRVK_CHECK(spec->arity == 1, "option --", name, " takes ", spec->arity,
                            " values, not name=value");
                vals.push_back(inlineValue);
                continue;
            }
            for (int k = 0; k < spec->arity; ++k) {
                AMRVK_CHECK(i + 1 < argv.size(), "option --", name, " needs ", spec->arity,
                            " value(s): ", spec->metavar);
                vals.push_back(argv[++i]);
            }
        } else if (a == "-o") {
            AMRVK_CHECK(i + 1 < argv.size(), "option -o needs a value");
            const OptionSpec* spec = nullptr;
            for (const auto& s : specs)
                if (s.name == "output") spec = &s;
            AMRVK_CHECK(spec, "unknown option '-o' for 'amrvk ", command, "'");
            mValues["output"].push_back(argv[++i]);
        } else {
            mPositional.push_back(a);
        }
    }
    AMRVK_CHECK(mPositional.size() >= minPositional, "amrvk ", command, ": missing argument (see amrvk ",
                command, " --help)");
    AMRVK_CHECK(mPositional.size() <= maxPositional, "amrvk ", command, ": unexpected argument '",
                mPositional.size() > maxPositional ? mPositional[maxPositional] : "", "'");
}

std::vector<std::string> Args::values(const std::string& name) const {
    auto it = mValues.find(name);
    return it == mValues.end() ? std::vector<std::string>{} : it->second;
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
    auto it = mValues.find(name);
    return it == mValues.end() || it->second.empty() ? fallback : it->second.front();
}

double Args::getDouble(const std::string& name, double fallback) const {
    return has(name) ? parseDouble("--" + name, get(name)) : fallback;
}

int64_t Args::getInt(const std::string& name, int64_t fallback) const {
    return has(name) ? parseInt("--" + name, get(name)) : fallback;
}

double parseDouble(const std::string& option, const std::string& text) {
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    AMRVK_CHECK(!text.empty() && end && *end == '\0', option, ": '", text, "' is not a number");
    return v;
}

int64_t parseInt(const std::string& option, const std::string& text) {
    int64_t v = 0;
    std::string t = text;
    // Accept 1e7-style integers for cell counts.
    if (t.find_first_of("eE") != std::string::npos) {
        double d = parseDouble(option, t);
        AMRVK_CHECK(d == static_cast<double>(static_cast<int64_t>(d)), option, ": '", text,
                    "' is not an integer");
        return static_cast<int64_t>(d);
    }
    auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    AMRVK_CHECK(ec == std::errc() && ptr == t.data() + t.size(), option, ": '", text,
                "' is not an integer");
    return v;
}

void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
    int a = 0, b = 0;
    char x = 0, tail = 0;
    const int n = std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &tail);
    AMRVK_CHECK(n == 3 && (x == 'x' || x == 'X') && a > 0 && b > 0 && a <= 16384 && b <= 16384, option, " '", text,
                "': expected WxH with 1 <= W, H <= 16384");
    width = a;
    height = b;
}

glm::dvec3 parseVec3(const std::string& option, const std::vector<std::string>& v, size_t at) {
    return {parseDouble(option, v[at]), parseDouble(option, v[at + 1]), parseDouble(option, v[at + 2])};
}

std::string formatOptions(const std::vector<OptionSpec>& specs) {
    std::string out;
    for (const auto& s : specs) {
        std::string head = "  --" + s.name + (s.metavar.empty() ? "" : " " + s.metavar);
        if (head.size() < 30) head.resize(30, ' ');
        else head += "\n" + std::string(30, ' ');
        out += head + s.help + "\n";
    }
    return out;
}

}  // namespace amrvk::cli
