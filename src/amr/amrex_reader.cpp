// AMReX / BoxLib plotfiles (shared/data/amr/FORMATS.md 4.1): a text Header, one VisMF MultiFab
// per level (Level_<l>/Cell_H + Cell_D_<n> files of FABs), 2-D or 3-D, cell-centred data.
// VisMF version 1 puts an ASCII header before each FAB; versions 2-4 write raw FAB data described
// by one RealDescriptor at the end of Cell_H. FAB boxes may include ngrow ghost cells; only the
// valid box listed in Cell_H is kept.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>
#include <utility>

#include "amr/block_structured.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

// Cursor over AMReX's whitespace-separated text (Header, Cell_H, FAB header lines); every error
// names `mName` and the line.
class TextCursor {
public:
    TextCursor(std::string text, std::string name)
        : mText(std::move(text)), mName(std::move(name)) {}

    char peek() {
        skipSpace();
        return mPos < mText.size() ? mText[mPos] : '\0';
    }
    void expect(char c) {
        AMRVK_CHECK(peek() == c, where(), ": expected '", c, "'", found());
        ++mPos;
    }
    bool accept(char c) {
        if (peek() != c) return false;
        ++mPos;
        return true;
    }
    int64_t readInt64(const char* what) { return readNumber<int64_t>(what, "an integer"); }
    int readInt(const char* what) {
        int64_t v = readInt64(what);
        AMRVK_CHECK(v >= INT32_MIN && v <= INT32_MAX, where(), ": ", what, " ", v,
                    " is out of range");
        return static_cast<int>(v);
    }
    double readDouble(const char* what) { return readNumber<double>(what, "a number"); }
    std::string readWord(const char* what) {
        skipSpace();
        size_t end = mPos;
        while (end < mText.size() && !isSpace(mText[end])) ++end;
        AMRVK_CHECK(end > mPos, where(), ": expected ", what, " (end of file)");
        std::string word = mText.substr(mPos, end - mPos);
        mPos = end;
        return word;
    }
    // The rest of the current line, trimmed; moves to the start of the next line.
    std::string readLine() {
        size_t end = mText.find('\n', mPos);
        if (end == std::string::npos) end = mText.size();
        const std::string_view line(mText.data() + mPos, end - mPos);
        mPos = std::min(end + 1, mText.size());
        return trim(line);
    }
    // "(a,b,c)"
    std::vector<int> readIntVect(const char* what) {
        expect('(');
        std::vector<int> v{readInt(what)};
        while (accept(',')) v.push_back(readInt(what));
        expect(')');
        return v;
    }
    // "(a b c ...)"
    std::vector<int> readIntList(const char* what) {
        expect('(');
        std::vector<int> v;
        while (!accept(')')) {
            AMRVK_CHECK(mPos < mText.size(), where(), ": unterminated list (", what, ")");
            v.push_back(readInt(what));
        }
        return v;
    }
    bool seekTo(std::string_view token) {
        size_t at = mText.find(token, mPos);
        if (at == std::string::npos) return false;
        mPos = at;
        return true;
    }
    std::string where() const {
        return strCat(
            mName, ": line ",
            1 + std::count(mText.begin(), mText.begin() + static_cast<std::ptrdiff_t>(mPos), '\n'));
    }

private:
    // One number parsed by std::from_chars; `kind` names what was expected ("an integer").
    template <typename T>
    T readNumber(const char* what, const char* kind) {
        skipSpace();
        T v = 0;
        const char* begin = mText.data() + mPos;
        auto [ptr, ec] = std::from_chars(begin, mText.data() + mText.size(), v);
        AMRVK_CHECK(ec == std::errc(), where(), ": expected ", kind, " (", what, ")", found());
        mPos += static_cast<size_t>(ptr - begin);
        return v;
    }
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    void skipSpace() {
        while (mPos < mText.size() && isSpace(mText[mPos])) ++mPos;
    }
    std::string found() const {
        if (mPos >= mText.size()) return " (end of file)";
        return strCat(" (found '", mText.substr(mPos, std::min<size_t>(12, mText.size() - mPos)),
                      "')");
    }

    std::string mText;
    std::string mName;
    size_t mPos = 0;
};

// "((lo) (hi) (type))"; only cell-centred boxes (type all 0) are accepted.
IndexBox readBox(TextCursor& in, int dim) {
    in.expect('(');
    std::vector<int> lo = in.readIntVect("box lower corner");
    std::vector<int> hi = in.readIntVect("box upper corner");
    std::vector<int> type = in.readIntVect("box index type");
    in.expect(')');
    const size_t d = static_cast<size_t>(dim);
    AMRVK_CHECK(lo.size() == d && hi.size() == d && type.size() == d, in.where(), ": box has ",
                lo.size(), " coordinates, expected ", dim);
    AMRVK_CHECK(std::all_of(type.begin(), type.end(), [](int t) { return t == 0; }), in.where(),
                ": node-centred box (only cell-centred data is supported)");
    IndexBox box;
    for (size_t a = 0; a < d; ++a) {
        box.lo[static_cast<int>(a)] = lo[a];
        box.hi[static_cast<int>(a)] = hi[a];
    }
    checkedBoxCells(box.lo, box.hi, in.where());
    return box;
}

// How reals are stored: IEEE float32/float64, either byte order.
struct RealFormat {
    int bytes = 8;
    bool swap = false;  // file byte order differs from this machine's
};

// "(n, (a b c ...))": a size and a list.
std::pair<int, std::vector<int>> readSizedList(TextCursor& in, const char* sizeWhat, const char* listWhat) {
    in.expect('(');
    const int n = in.readInt(sizeWhat);
    in.expect(',');
    std::vector<int> list = in.readIntList(listWhat);
    in.expect(')');
    return {n, std::move(list)};
}

// "((8, (64 11 52 0 1 12 0 1023)),(8, (8 7 6 5 4 3 2 1)))"
RealFormat readRealDescriptor(TextCursor& in) {
    in.expect('(');
    const auto [bytes, format] = readSizedList(in, "real size", "real format");
    in.expect(',');
    const auto [orderBytes, order] = readSizedList(in, "byte order size", "byte order");
    in.expect(')');
    const std::vector<int> ieee64{64, 11, 52, 0, 1, 12, 0, 1023};
    const std::vector<int> ieee32{32, 8, 23, 0, 1, 9, 0, 127};
    AMRVK_CHECK((bytes == 8 && format == ieee64) || (bytes == 4 && format == ieee32), in.where(),
                ": unsupported real format (", bytes, " bytes, (", join(format),
                ")); only IEEE float32/float64 are supported");
    AMRVK_CHECK(orderBytes == bytes && order.size() == static_cast<size_t>(bytes), in.where(),
                ": byte order (", join(order), ") does not match the ", bytes, "-byte reals");
    bool little = true, big = true;
    for (int i = 0; i < bytes; ++i) {
        little = little && order[static_cast<size_t>(i)] == bytes - i;
        big = big && order[static_cast<size_t>(i)] == i + 1;
    }
    AMRVK_CHECK(little || big, in.where(), ": unsupported byte order (", join(order), ")");
    return {bytes, little != (std::endian::native == std::endian::little)};
}

float decodeReal(const unsigned char* p, const RealFormat& fmt) {
    unsigned char b[8];
    const size_t n = static_cast<size_t>(fmt.bytes);
    if (fmt.swap)
        std::reverse_copy(p, p + n, b);
    else
        std::memcpy(b, p, n);
    if (n == 8) {
        double d;
        std::memcpy(&d, b, 8);
        return static_cast<float>(d);
    }
    float f;
    std::memcpy(&f, b, 4);
    return f;
}

struct Header {
    std::string version;
    std::vector<std::string> names;
    int dim = 3;
    double time = 0;
    int finestLevel = 0;
    glm::dvec3 probLo{0.0}, probHi{0.0};
    std::vector<int> refRatio;      // ratio level l -> l+1
    std::vector<IndexBox> domains;  // per level
    int coordSys = 0;
    std::vector<int> boxCounts;         // per level
    std::vector<std::string> prefixes;  // per level, e.g. "Level_0/Cell"
};

Header readHeader(const fs::path& headerPath) {
    TextCursor in(readTextFile(headerPath), headerPath.string());
    Header h;
    h.version = in.readLine();
    AMRVK_CHECK(!h.version.empty(), headerPath.string(), ": empty plotfile version line");
    const int ncomp = in.readInt("number of components");
    AMRVK_CHECK(ncomp > 0, in.where(), ": ", ncomp, " components");
    in.readLine();
    for (int c = 0; c < ncomp; ++c) {
        h.names.push_back(in.readLine());
        AMRVK_CHECK(!h.names.back().empty(), in.where(), ": empty name for component ", c);
    }
    h.dim = in.readInt("dimension");
    AMRVK_CHECK(h.dim == 2 || h.dim == 3, in.where(), ": ", h.dim,
                "-D plotfile (only 2-D and 3-D are supported)");
    h.time = in.readDouble("time");
    h.finestLevel = in.readInt("finest level");
    AMRVK_CHECK(h.finestLevel >= 0 && h.finestLevel <= kMaxLevel, in.where(), ": finest level ",
                h.finestLevel, " is out of range");
    const int levels = h.finestLevel + 1;
    for (int a = 0; a < h.dim; ++a) h.probLo[a] = in.readDouble("prob_lo");
    for (int a = 0; a < h.dim; ++a) h.probHi[a] = in.readDouble("prob_hi");
    for (int a = 0; a < h.dim; ++a)
        AMRVK_CHECK(std::isfinite(h.probLo[a]) && std::isfinite(h.probHi[a]) && h.probLo[a] < h.probHi[a], in.where(),
                    ": prob_lo ", h.probLo[a], " and prob_hi ", h.probHi[a], " on axis ", a,
                    " are not a finite range with prob_lo < prob_hi");
    for (int l = 0; l < h.finestLevel; ++l) h.refRatio.push_back(in.readInt("refinement ratio"));
    for (int l = 0; l < levels; ++l) h.domains.push_back(readBox(in, h.dim));
    for (int l = 0; l < levels; ++l) in.readInt("level steps");
    for (int i = 0; i < levels * h.dim; ++i) in.readDouble("cell size");
    h.coordSys = in.readInt("coordinate system");
    in.readInt("boundary width");
    for (int l = 0; l < levels; ++l) {
        const int lev = in.readInt("level number");
        AMRVK_CHECK(lev == l, in.where(), ": expected level ", l, ", found ", lev);
        const int nboxes = in.readInt("box count");
        AMRVK_CHECK(nboxes >= 0, in.where(), ": negative box count");
        // A level without boxes is not written by AMReX; reading on would take the box extents
        // for the MultiFab prefix and blame a file that was never named.
        AMRVK_CHECK(nboxes > 0, in.where(), ": level ", l, " has no boxes");
        in.readDouble("level time");
        in.readInt("level step");
        for (int64_t i = 0; i < int64_t{nboxes} * 2 * h.dim; ++i) in.readDouble("physical box extent");
        h.boxCounts.push_back(nboxes);
        h.prefixes.push_back(in.readWord("MultiFab prefix (Level_<l>/Cell)"));
    }
    return h;
}

struct FabOnDisk {
    std::string file;
    uint64_t offset = 0;
};

struct CellHeader {
    int version = 1;
    int ncomp = 0;
    glm::ivec3 ngrow{0};
    std::vector<IndexBox> boxes;  // valid boxes
    std::vector<FabOnDisk> fabs;
    RealFormat rawFormat;  // versions 2-4
};

CellHeader readCellHeader(const fs::path& path, int dim) {
    TextCursor in(readTextFile(path), path.string());
    CellHeader h;
    h.version = in.readInt("VisMF version");
    AMRVK_CHECK(h.version >= 1 && h.version <= 4, in.where(), ": unsupported VisMF version ",
                h.version, " (expected 1-4)");
    in.readInt("how");
    h.ncomp = in.readInt("number of components");
    if (in.peek() == '(') {
        std::vector<int> g = in.readIntVect("ngrow");
        AMRVK_CHECK(g.size() == static_cast<size_t>(dim), in.where(), ": ngrow has ", g.size(),
                    " entries, expected ", dim);
        for (int a = 0; a < dim; ++a) h.ngrow[a] = g[static_cast<size_t>(a)];
    } else {
        const int g = in.readInt("ngrow");
        for (int a = 0; a < dim; ++a) h.ngrow[a] = g;
    }
    for (int a = 0; a < dim; ++a) checkedInRange(h.ngrow[a], 0, kMaxIndex, in.where() + ": ngrow");
    in.expect('(');
    const int nboxes = in.readInt("box count");
    AMRVK_CHECK(nboxes >= 0, in.where(), ": negative box count");
    in.readInt("box array hash");
    for (int b = 0; b < nboxes; ++b) h.boxes.push_back(readBox(in, dim));
    in.expect(')');
    const int nfabs = in.readInt("FabOnDisk count");
    AMRVK_CHECK(nfabs == nboxes, in.where(), ": ", nfabs, " FabOnDisk entries for ", nboxes,
                " boxes");
    for (int b = 0; b < nfabs; ++b) {
        const std::string tag = in.readWord("FabOnDisk:");
        AMRVK_CHECK(tag == "FabOnDisk:", in.where(), ": expected 'FabOnDisk:', found '", tag, "'");
        std::string file = in.readWord("FAB data file name");
        const int64_t offset = in.readInt64("FAB byte offset");
        AMRVK_CHECK(offset >= 0, in.where(), ": negative FAB offset");
        h.fabs.push_back({std::move(file), static_cast<uint64_t>(offset)});
    }
    if (h.version >= 2) {
        // Min/max lines (numbers and commas only) come first; the descriptor is the first "((".
        AMRVK_CHECK(in.seekTo("(("), path.string(), ": VisMF version ", h.version,
                    " header has no RealDescriptor after the FabOnDisk list");
        h.rawFormat = readRealDescriptor(in);
    }
    return h;
}

// Reads the ASCII line "FAB <RealDescriptor><box> <ncomp>\n" at the reader's position.
std::string readFabHeaderLine(BinaryReader& reader) {
    std::string line;
    const uint64_t start = reader.offset();
    for (;;) {
        char c = 0;
        reader.read(&c, 1);
        if (c == '\n') break;
        line += c;
        AMRVK_CHECK(line.size() < 4096, reader.path().string(),
                    ": no FAB header line ending at byte ", start, " (not a VisMF version 1 FAB?)");
    }
    return line;
}

// Reads FAB `b` listed in a level's Cell_H: the values of `components` in its valid box.
Block readFab(BinaryReader& reader, const CellHeader& cells, size_t b, int dim,
              const std::vector<size_t>& components, const std::string& cellHeaderName) {
    const IndexBox& valid = cells.boxes[b];
    const std::string dataName = reader.path().string();
    AMRVK_CHECK(cells.fabs[b].offset <= reader.size(), dataName, ": FAB ", b, " of ",
                cellHeaderName, " starts at byte ", cells.fabs[b].offset, " but the file has only ",
                reader.size(), " bytes (truncated?)");
    reader.seek(cells.fabs[b].offset);
    IndexBox fab;
    RealFormat fmt;
    int fabComps = cells.ncomp;
    if (cells.version == 1) {
        TextCursor line(readFabHeaderLine(reader),
                        strCat(dataName, ": FAB at byte ", cells.fabs[b].offset));
        const std::string tag = line.readWord("FAB");
        AMRVK_CHECK(tag == "FAB", line.where(), ": expected 'FAB', found '", tag, "'");
        fmt = readRealDescriptor(line);
        fab = readBox(line, dim);
        fabComps = line.readInt("component count");
    } else {
        fmt = cells.rawFormat;
        const glm::i64vec3 lo = glm::i64vec3(valid.lo) - glm::i64vec3(cells.ngrow);
        const glm::i64vec3 hi = glm::i64vec3(valid.hi) + glm::i64vec3(cells.ngrow);
        checkedBoxCells(lo, hi, strCat(dataName, ": FAB ", b, " grown by ngrow"));
        fab = {glm::ivec3(lo), glm::ivec3(hi)};
    }
    AMRVK_CHECK(fab.contains(valid), dataName, ": FAB ", b, " does not contain its valid box from ",
                cellHeaderName);
    AMRVK_CHECK(fabComps == cells.ncomp, dataName, ": FAB ", b, " has ", fabComps,
                " components, expected ", cells.ncomp);
    const std::string fabName = strCat(dataName, ": FAB ", b);
    const uint64_t compBytes = checkedProduct({fab.cellCount(), uint64_t(fmt.bytes)}, fabName);
    const uint64_t dataStart = reader.offset();
    const uint64_t needed = checkedProduct({compBytes, uint64_t(fabComps)}, fabName);
    AMRVK_CHECK(needed <= reader.size() - dataStart, dataName, ": truncated FAB ", b, " (", needed,
                " bytes of data from byte ", dataStart, ", file has ", reader.size(), ")");

    // Each component is the whole FAB box, x fastest; keep the valid part.
    Block block{.lo = valid.lo, .hi = valid.hi};
    std::vector<unsigned char> raw(compBytes);
    for (size_t comp : components) {
        reader.seek(dataStart + comp * compBytes);
        reader.read(raw.data(), compBytes);
        block.values.push_back(cropBox(fab.dims(), valid.lo - fab.lo, valid.dims(), [&](size_t i) {
            return decodeReal(raw.data() + i * size_t(fmt.bytes), fmt);
        }));
    }
    return block;
}

}  // namespace

Model readAmrex(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "amrex", .source = path.string()};
    std::error_code ec;
    const bool isDir = fs::is_directory(path, ec);
    const fs::path dir = isDir ? path : path.parent_path();
    const fs::path headerPath = isDir ? path / "Header" : path;
    fileSize(headerPath);
    const Header header = readHeader(headerPath);
    model.availableFields = header.names;
    const std::vector<size_t> components = addSelectedFields(model, options.fields);

    const int levelCount = header.finestLevel + 1;
    std::vector<BlockLevel> levels = levelsWithCellWidths(header.refRatio, headerPath.string());
    std::vector<std::string> vismfVersions;
    for (int l = 0; l < levelCount; ++l) {
        const size_t li = static_cast<size_t>(l);
        const fs::path cellHeaderPath = dir / (header.prefixes[li] + "_H");
        const CellHeader cells = readCellHeader(cellHeaderPath, header.dim);
        vismfVersions.push_back(std::to_string(cells.version));
        AMRVK_CHECK(cells.ncomp == static_cast<int>(header.names.size()), cellHeaderPath.string(),
                    ": ", cells.ncomp, " components but the Header names ", header.names.size());
        AMRVK_CHECK(static_cast<int>(cells.boxes.size()) == header.boxCounts[li],
                    cellHeaderPath.string(), ": ", cells.boxes.size(),
                    " boxes but the Header lists ", header.boxCounts[li], " on level ", l);
        BlockLevel& level = levels[li];
        level.indexOrigin = header.domains[li].lo;
        const fs::path dataDir = (dir / header.prefixes[li]).parent_path();
        std::unique_ptr<BinaryReader> reader;
        for (size_t b = 0; b < cells.boxes.size(); ++b) {
            const fs::path dataPath = dataDir / cells.fabs[b].file;
            if (!reader || reader->path() != dataPath)
                reader = std::make_unique<BinaryReader>(dataPath);
            level.blocks.push_back(readFab(*reader, cells, b, header.dim, components,
                                           cellHeaderPath.filename().string()));
        }
    }
    appendLeafCells(model, levels, header.dim == 2);

    // world = prob_lo + voxel * (finest cell size); 2-D slabs use the x cell size for z.
    const IndexBox& finest = header.domains.back();
    for (int a = 0; a < header.dim; ++a) {
        model.voxelToWorld.origin[a] = header.probLo[a];
        model.voxelToWorld.scale[a] = (header.probHi[a] - header.probLo[a]) / finest.dims()[a];
    }
    if (header.dim == 2) model.voxelToWorld.scale.z = model.voxelToWorld.scale.x;

    const char* coordNames[] = {"cartesian", "rz", "spherical"};
    model.attributes = {
        {"plotfileVersion", header.version},
        {"dimensions", std::to_string(header.dim)},
        {"time", formatDouble(header.time)},
        {"levels", std::to_string(levelCount)},
        {"boxesPerLevel", join(blockCounts(levels))},
        {"refinementRatios", join(header.refRatio)},
        {"coordinateSystem", header.coordSys >= 0 && header.coordSys <= 2
                                 ? coordNames[header.coordSys]
                                 : std::to_string(header.coordSys)},
        {"vismfVersion", join(vismfVersions)},
    };
    return model;
}

}  // namespace amrvk::amr
