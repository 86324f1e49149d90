#pragma once
// Command-line parsing for amrvk subcommands: --name value... options with fixed arity,
// flags (arity 0), positionals. Errors are amrvk::Error with a one-line message.
#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace amrvk::cli {

struct OptionSpec {
    std::string name;     // without leading dashes, e.g. "field"
    int arity = 1;        // number of values; 0 = flag
    std::string metavar;  // e.g. "NAME"
    std::string help;
    bool repeatable = false;
};

class Args {
public:
    // Parses argv (after the subcommand). Throws on unknown options or missing values.
    Args(const std::string& command, const std::vector<std::string>& argv,
         const std::vector<OptionSpec>& specs, size_t minPositional, size_t maxPositional);

    bool has(const std::string& name) const { return mValues.count(name) > 0; }
    const std::vector<std::string>& positional() const { return mPositional; }
    // All values of an option (concatenated over repeats).
    std::vector<std::string> values(const std::string& name) const;
    std::string get(const std::string& name, const std::string& fallback = "") const;
    double getDouble(const std::string& name, double fallback) const;
    int64_t getInt(const std::string& name, int64_t fallback) const;

private:
    std::string mCommand;
    std::map<std::string, std::vector<std::string>> mValues;
    std::vector<std::string> mPositional;
};

// Parses a number; throws "--opt: 'x' is not a number".
double parseDouble(const std::string& option, const std::string& text);
int64_t parseInt(const std::string& option, const std::string& text);

// "WxH" with 1 <= W, H <= 16384; throws "OPTION 'text': expected WxH ...".
void parseSize(const std::string& option, const std::string& text, int& width, int& height);
// Three numbers v[at], v[at+1], v[at+2] of an option's values.
glm::dvec3 parseVec3(const std::string& option, const std::vector<std::string>& v, size_t at);

// Renders the option list for --help.
std::string formatOptions(const std::vector<OptionSpec>& specs);

}  // namespace amrvk::cli
