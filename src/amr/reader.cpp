#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {
bool hasHdf5Magic(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::array<char, 8> magic{};
    in.read(magic.data(), magic.size());
    return in && std::memcmp(magic.data(), "\x89HDF\r\n\x1a\n", 8) == 0;
}
std::string firstLine(const fs::path& p) {
    std::ifstream in(p);
    std::string line;
    std::getline(in, line);
    return line;
}
// With no field named, every field is read; under a log scale without a floor, a field other
// than the first (the default) that has no positive value cannot be logged and is not loaded
// (RAMSES's passive scalars are often zero everywhere), recorded in the "logSkipped" attribute.
// A named field, or the first, with no positive value stays an error (applyFieldScale).
void dropFieldsWithoutLog(Model& model) {
    std::vector<std::string> skipped;
    for (size_t f = model.fields.size(); f-- > 1;)
        if (smallestPositive(model.fields[f].values) == 0) {
            skipped.insert(skipped.begin(), model.fields[f].name);
            model.fields.erase(model.fields.begin() + static_cast<std::ptrdiff_t>(f));
        }
    if (!skipped.empty())
        model.attributes.emplace_back("logSkipped", join(skipped, ", ") + " (no positive value; name it with --field "
                                                                           "and give --log-floor)");
}
}  // namespace

std::string detectFormat(const fs::path& path) {
    std::error_code ec;
    const bool exists = fs::exists(path, ec);
    if (fs::is_directory(path, ec)) {
        if (fs::exists(path / "Header")) return "amrex";
        if (!ramsesInfoFile(path).empty()) return "ramses";
        AMRVK_CHECK(false, path.string(),
                    ": directory is neither an AMReX plotfile (no Header file) nor a RAMSES output (no info_NNNNN.txt)");
    }
    const std::string ext = path.extension().string();
    if (ext == ".cells") return "exabrick";
    if (ext == ".raw") return "raw";
    if (ext == ".hierarchy") return "enzo";
    if (!exists) {
        fs::path cells = path;
        cells += ".cells";
        if (fs::exists(cells)) return "exabrick";
        AMRVK_CHECK(false, path.string(), ": no such file");
    }
    if (!ramsesInfoFile(path).empty()) return "ramses";  // info_NNNNN.txt
    fileSize(path);  // a regular file, checked before it is opened: a FIFO or device would block the peeks below
    if (path.filename() == "Header" && firstLine(path).rfind("HyperCLaw", 0) == 0) return "amrex";
    fs::path hierarchy = path;
    hierarchy += ".hierarchy";
    if (fs::exists(hierarchy)) return "enzo";
    if (hasHdf5Magic(path)) return isCarpetFile(path) ? "carpet" : "chombo";
    AMRVK_CHECK(false, path.string(),
                ": unrecognised AMR format (use --format exabrick|amrex|enzo|chombo|carpet|ramses|raw)");
    return {};
}

Model readModel(const fs::path& path, const ReadOptions& options) {
    std::string format = options.format.empty() || options.format == "auto" ? detectFormat(path)
                                                                            : options.format;
    Model model;
    if (format == "exabrick") model = readExaBrick(path, options);
    else if (format == "amrex") model = readAmrex(path, options);
    else if (format == "enzo") model = readEnzo(path, options);
    else if (format == "chombo") model = readChombo(path, options);
    else if (format == "carpet") model = readCarpet(path, options);
    else if (format == "ramses") model = readRamses(path, options);
    else if (format == "raw") model = readRaw(path, options);
    else AMRVK_CHECK(false, "unknown format '", format, "' (expected auto, exabrick, amrex, enzo, chombo, carpet, ramses or raw)");
    model = checkedModel(std::move(model), options.nanPolicy);
    // Auto: the field shown (the named one, else the default) decides for every field loaded.
    const FieldScale scale = options.scale == FieldScale::Auto ? autoScaleOf(model.defaultField().values) : options.scale;
    if (scale == FieldScale::Log && options.fields.empty() && options.logFloor == 0)
        dropFieldsWithoutLog(model);
    applyFieldScale(model, scale, options.logFloor);
    return model;
}

FieldScale resolvedScale(const fs::path& path, const ReadOptions& options) {
    if (options.scale != FieldScale::Auto) return options.scale;
    const std::string format = options.format.empty() || options.format == "auto" ? detectFormat(path) : options.format;
    if (format != "exabrick") return scaleOf(readModel(path, options));
    // The whole field's extremes: one streamed pass over the values.
    ReadOptions linear = options;
    linear.scale = FieldScale::Linear;
    FiniteExtremes extremes;
    visitExaBrick(path, linear, uint64_t(1) << 20, [&](Model& chunk) { extremes.add(chunk.fields[0].values); }, nullptr);
    return extremes.autoScale();
}

double logFloorOf(const fs::path& path, const ReadOptions& options) {
    AMRVK_CHECK(options.scale != FieldScale::Auto, "internal: logFloorOf before the scale is resolved");
    if (options.scale != FieldScale::Log || options.logFloor != 0) return options.logFloor;
    const std::string format = options.format.empty() || options.format == "auto" ? detectFormat(path) : options.format;
    if (format != "exabrick") return 0;  // read whole: applyFieldScale finds it
    // The whole field's smallest positive value: one streamed pass over the values.
    float lo = 0;
    visitExaBrick(path, options, uint64_t(1) << 20, [&](Model& chunk) {
        const float c = smallestPositive(chunk.fields[0].values);
        if (c > 0 && (lo == 0 || c < lo)) lo = c;
    }, nullptr);
    AMRVK_CHECK(lo > 0, path.string(), ": the field has no positive value: log scale needs one (or --log-floor)");
    return lo;
}

void visitCells(const fs::path& path, const ReadOptions& given, const std::function<void(const Model& chunk)>& visit,
                Model* head) {
    AMRVK_CHECK(given.fields.size() <= 1, "internal: visitCells takes one field");
    ReadOptions options = given;
    const std::string format = options.format.empty() || options.format == "auto" ? detectFormat(path) : options.format;
    if (format == "exabrick") {
        options.scale = resolvedScale(path, given);  // chunks need it before the first (readModel decides alone)
        const double floor = logFloorOf(path, options);
        uint64_t kept = 0, dropped = 0;
        visitExaBrick(
            path, options, uint64_t(1) << 20,
            [&](Model& chunk) {
                const size_t read = chunk.cells.size();
                applyNanPolicy(chunk, options.nanPolicy);
                dropped += read - chunk.cells.size();
                kept += chunk.cells.size();
                if (chunk.cells.empty()) return;  // every cell of it dropped
                validateCells(chunk);
                applyFieldScale(chunk, options.scale, floor);
                visit(chunk);
            },
            head);
        AMRVK_CHECK(kept > 0 || dropped == 0, path.string(), ": every one of its ", dropped,
                    " cells has a non-finite value, and --nan drop dropped them all");
        return;
    }
    Model model = readModel(path, options);
    if (model.fields.size() > 1) {  // the default field only
        Field kept = std::move(model.fields[size_t(&model.defaultField() - model.fields.data())]);
        model.fields.assign(1, std::move(kept));
    }
    if (head) {
        *head = model;
        head->cells.clear();
        head->fields[0].values.clear();
    }
    visit(model);
}

Model checkedModel(Model model, NanPolicy nanPolicy) {
    applyNanPolicy(model, nanPolicy);
    validateCells(model);  // overlaps: found by the brick build (or amr::validate)
    return model;
}

}  // namespace amrvk::amr
