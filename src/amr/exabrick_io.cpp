// ExaBrick cells + scalars (exabrick-reference.md 1.1, 1.2): raw little-endian records, no header.
#include <algorithm>
#include <cstring>

#include "amr/block_structured.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {
fs::path cellsPathOf(const fs::path& path) {
    if (path.extension() == ".cells") return path;
    fs::path p = path;
    p += ".cells";
    return p;
}
// "<base>.scalars" -> "scalars"; "<base>.<name>.scalars" -> "<name>".
std::vector<std::pair<std::string, fs::path>> findScalarFiles(const fs::path& cellsPath) {
    std::vector<std::pair<std::string, fs::path>> out;
    const fs::path given = cellsPath.parent_path();
    const fs::path dir = given.empty() ? fs::path(".") : given;
    const std::string stem = cellsPath.stem().string();
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        const fs::path path = given / entry.path().filename();
        std::error_code statusError;  // a link loop or a dangling link beside the data is not a scalar file
        if (!entry.is_regular_file(statusError) || name.size() <= stem.size() + 8) {
            if (name == stem + ".scalars") out.emplace_back("scalars", path);
            continue;
        }
        if (name.rfind(stem + ".", 0) != 0 || name.substr(name.size() - 8) != ".scalars") continue;
        std::string middle = name.substr(stem.size() + 1, name.size() - stem.size() - 9);
        out.emplace_back(middle.empty() ? "scalars" : middle, path);
    }
    std::sort(out.begin(), out.end());
    return out;
}
// The checks both readers make before reading: the cell file's size, the scalar files beside it.
struct Opened {
    fs::path cellsPath;
    uint64_t count = 0;
    std::vector<std::pair<std::string, fs::path>> scalarFiles;
};
Opened openExaBrick(const fs::path& path, Model& model) {
    Opened o{.cellsPath = cellsPathOf(path)};
    model.format = "exabrick";
    model.source = o.cellsPath.string();
    const uint64_t bytes = fileSize(o.cellsPath);
    AMRVK_CHECK(bytes > 0, o.cellsPath.string(), ": empty file (no cells)");
    AMRVK_CHECK(bytes % sizeof(Cell) == 0, o.cellsPath.string(), ": size ", bytes,
                " bytes is not a multiple of the 16-byte cell record (truncated file?)");
    o.count = bytes / sizeof(Cell);
    o.scalarFiles = findScalarFiles(o.cellsPath);
    for (const auto& [name, p] : o.scalarFiles) model.availableFields.push_back(name);
    AMRVK_CHECK(!model.availableFields.empty(), o.cellsPath.string(), ": no scalar file beside it (expected ",
                o.cellsPath.stem().string(), ".scalars or ", o.cellsPath.stem().string(), ".<field>.scalars)");
    return o;
}

// Checks that a scalar file holds one float per cell.
void checkScalars(const fs::path& p, uint64_t count, const fs::path& cellsPath) {
    const uint64_t sbytes = fileSize(p);
    AMRVK_CHECK(sbytes % sizeof(float) == 0, p.string(), ": size ", sbytes,
                " bytes is not a multiple of 4 (truncated float32 file?)");
    AMRVK_CHECK(sbytes / sizeof(float) == count, p.string(), ": ", sbytes / sizeof(float), " values but ",
                cellsPath.filename().string(), " has ", count, " cells");
}
}  // namespace

Model readExaBrick(const fs::path& path, const ReadOptions& options) {
    Model model;
    const Opened o = openExaBrick(path, model);
    const fs::path& cellsPath = o.cellsPath;
    const uint64_t count = o.count;
    const auto& scalarFiles = o.scalarFiles;
    const std::vector<size_t> components = addSelectedFields(model, options.fields);

    // Every size checked before anything is read or allocated: a 4 GiB .cells beside a short
    // .scalars used to be read whole first, and the cells were never held to the memory budget.
    for (const size_t c : components) checkScalars(scalarFiles[c].second, count, cellsPath);
    const uint64_t bytes =
        checkedProduct({count, sizeof(Cell) + components.size() * sizeof(float)}, cellsPath.string());
    checkAllocation(bytes, cellsPath.string() + ": the cells and their values");
    BinaryReader cells(cellsPath);
    readCells(cells, count, model.cells);
    for (size_t i = 0; i < components.size(); ++i)
        BinaryReader(scalarFiles[components[i]].second).readArray(model.fields[i].values, count);
    return model;
}

void visitExaBrick(const fs::path& path, const ReadOptions& options, uint64_t chunkCells,
                   const std::function<void(Model& chunk)>& visit, Model* head) {
    AMRVK_CHECK(options.fields.size() <= 1, "internal: visitExaBrick takes one field");
    Model model;
    const Opened o = openExaBrick(path, model);
    std::vector<std::string> wanted = options.fields;
    if (wanted.empty()) wanted = {model.availableFields.front()};
    const std::vector<size_t> components = addSelectedFields(model, wanted);
    const fs::path& scalarsPath = o.scalarFiles[components.at(0)].second;
    checkScalars(scalarsPath, o.count, o.cellsPath);
    if (head) *head = model;
    BinaryReader cells(o.cellsPath), values(scalarsPath);
    for (uint64_t at = 0; at < o.count; at += chunkCells) {
        const uint64_t n = std::min(chunkCells, o.count - at);
        readCells(cells, n, model.cells);
        values.readArray(model.fields[0].values, n);
        visit(model);
    }
}

std::string scalarsName(const std::string& field) {
    std::string out = field;
    for (char& c : out)
        if (c == '/' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
    return out;
}

std::vector<fs::path> exaBrickFiles(const Model& model, const fs::path& base, bool writeSingleAsPlain) {
    std::vector<fs::path> out;
    out.push_back(fs::path(base) += ".cells");
    for (const Field& f : model.fields)
        out.push_back(fs::path(base) += (writeSingleAsPlain && model.fields.size() == 1)
                                            ? std::string(".scalars")
                                            : strCat(".", scalarsName(f.name), ".scalars"));  // GCC 12: no false -Wrestrict
    for (size_t i = 1; i < out.size(); ++i)
        for (size_t j = 1; j < i; ++j)
            AMRVK_CHECK(out[i] != out[j], "fields '", model.fields[j - 1].name, "' and '", model.fields[i - 1].name,
                        "' would both be written to ", out[i].string());
    return out;
}

void writeExaBrick(const Model& model, const fs::path& base, bool writeSingleAsPlain) {
    for (const Field& f : model.fields)
        AMRVK_CHECK(f.values.size() == model.cells.size(), "field '", f.name, "' has ", f.values.size(),
                    " values for ", model.cells.size(), " cells");
    const std::vector<fs::path> files = exaBrickFiles(model, base, writeSingleAsPlain);
    // Every file is written under its temporary name first; all are committed only once all are
    // written, so a failure leaves none of them behind.
    std::vector<std::unique_ptr<AtomicFileWriter>> writers;
    writers.push_back(std::make_unique<AtomicFileWriter>(files[0]));
    writeCells(*writers.back(), model.cells);
    for (size_t i = 0; i < model.fields.size(); ++i) {
        writers.push_back(std::make_unique<AtomicFileWriter>(files[i + 1]));
        writers.back()->writeSpan(std::span<const float>(model.fields[i].values));
    }
    commitAll(writers);
}

}  // namespace amrvk::amr
