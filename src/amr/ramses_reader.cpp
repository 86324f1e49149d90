// RAMSES outputs (shared/data/amr/FORMATS.md 4.4): a directory output_NNNNN with info_NNNNN.txt
// (text), per MPI domain C = 1..ncpu an AMR file amr_NNNNN.outCCCCC and a hydro file
// hydro_NNNNN.outCCCCC (Fortran sequential unformatted records: int32 length, payload, the same
// int32 length), and hydro_file_descriptor.txt (the variables' names; absent in old outputs).
// The mesh is a fully threaded octree: an oct of RAMSES level l has 2^ndim cells of width
// 2^-l coarse cells; a cell with no son oct is a leaf, and the leaves tile the domain. Each domain
// file also lists the other domains' (ghost) and boundary octs: only its own octs are kept.
// Leaves become amrvk cells: with L the deepest leaf level, a level-l leaf has amrvk level L - l
// and lower corner (centre - dx_l / 2) / dx_L. 2-D outputs become one-cell-thick slabs (z from 0
// to the cell's width), as the AMReX and Chombo readers make them. Values are code units.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "amr/block_structured.h"
#include "amr/field_units.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

// Fortran sequential records of one file, checked: the leading length fits in what is left of the
// file, the trailing length equals it, and every record has the size its contents need.
class RecordReader {
public:
    explicit RecordReader(const fs::path& path) : mIn(path), mName(path.string()) {}

    const std::string& name() const { return mName; }
    uint64_t offset() const { return mIn.offset(); }

    // Opens the next record and returns its payload length.
    uint64_t open(const char* what) {
        mStart = mIn.offset();
        mWhat = what;
        AMRVK_CHECK(mIn.size() - mStart >= 4, mName, ": truncated at byte ", mStart, " (record '", what, "' expected)");
        int32_t length = 0;
        mIn.read(&length, 4);
        AMRVK_CHECK(length >= 0, mName, ": record '", what, "' at byte ", mStart, " has length ", length,
                    " (negative: Fortran subrecords and big-endian files are not supported)");
        const uint64_t left = mIn.size() - mIn.offset();
        AMRVK_CHECK(uint64_t(length) <= left && left - uint64_t(length) >= 4, mName, ": record '", what, "' at byte ",
                    mStart, " has length ", length, " but only ", left, " bytes follow (truncated file?)");
        mLength = uint64_t(length);
        return mLength;
    }
    // Moves past the payload and checks the trailing length.
    void close() {
        mIn.seek(mStart + 4 + mLength);
        int32_t trailing = 0;
        mIn.read(&trailing, 4);
        AMRVK_CHECK(trailing >= 0 && uint64_t(trailing) == mLength, mName, ": record '", mWhat, "' at byte ", mStart,
                    ": leading length ", mLength, " differs from trailing length ", trailing);
    }
    void skip(const char* what) {
        open(what);
        close();
    }
    // A record of exactly `count` values of `bytes` bytes each, skipped.
    void skipValues(const char* what, uint64_t count, uint64_t bytes) {
        open(what);
        expectLength(count, bytes);
        close();
    }
    // A record of exactly `count` values of T.
    template <class T>
    std::vector<T> values(const char* what, uint64_t count) {
        open(what);
        expectLength(count, sizeof(T));
        std::vector<T> out;
        mIn.readArray(out, count);
        close();
        return out;
    }
    template <class T>
    T scalar(const char* what) {
        return values<T>(what, 1)[0];
    }
    // A record of `count` reals of `realBytes` (4 or 8) bytes, as doubles.
    std::vector<double> reals(const char* what, uint64_t count, int realBytes) {
        if (realBytes == 8) return values<double>(what, count);
        const std::vector<float> f = values<float>(what, count);
        return {f.begin(), f.end()};
    }
    // One real whose record length (4 or 8) gives the file's real size.
    double realScalar(const char* what, int& realBytes) {
        const uint64_t length = open(what);
        AMRVK_CHECK(length == 4 || length == 8, mName, ": record '", what, "' at byte ", mStart, " has length ", length,
                    " (expected one 4- or 8-byte real)");
        realBytes = int(length);
        double v = 0;
        if (length == 8) {
            mIn.read(&v, 8);
        } else {
            float f = 0;
            mIn.read(&f, 4);
            v = f;
        }
        close();
        return v;
    }
    // The whole record as text, trailing blanks removed (Fortran character variables).
    std::string text(const char* what) {
        const uint64_t length = open(what);
        AMRVK_CHECK(length <= 4096, mName, ": record '", what, "' at byte ", mStart, " has length ", length,
                    " (expected at most 4096 characters)");
        std::string s(length, '\0');
        mIn.read(s.data(), length);
        close();
        return trim(s);
    }

private:
    void expectLength(uint64_t count, uint64_t bytes) {
        const uint64_t expected = checkedProduct({count, bytes}, mName + ": record size");
        AMRVK_CHECK(mLength == expected, mName, ": record '", mWhat, "' at byte ", mStart, " has length ", mLength,
                    ", expected ", expected, " (", count, " values of ", bytes, " bytes)");
    }

    BinaryReader mIn;
    std::string mName;
    uint64_t mStart = 0, mLength = 0;
    const char* mWhat = "";
};

// Where an output's files are: its directory and its number NNNNN.
struct Output {
    fs::path dir;
    std::string number;
    fs::path info;
    fs::path file(const char* kind, int domain) const {
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, ".out%05d", domain);
        return dir / (std::string(kind) + "_" + number + suffix);
    }
};

// "info_NNNNN.txt" -> "NNNNN" (digits only), else "".
std::string infoNumber(const std::string& filename) {
    if (filename.size() <= 9 || filename.rfind("info_", 0) != 0 || filename.substr(filename.size() - 4) != ".txt")
        return {};
    const std::string digits = filename.substr(5, filename.size() - 9);
    return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ? digits : "";
}

std::optional<Output> findOutput(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        // output_NNNNN names its info file; other directory names: the one info_NNNNN.txt inside.
        const std::string name = path.filename().string();
        if (name.rfind("output_", 0) == 0) {
            const fs::path info = path / ("info_" + name.substr(7) + ".txt");
            if (fs::is_regular_file(info, ec) && !infoNumber(info.filename().string()).empty())
                return Output{path, name.substr(7), info};
        }
        std::vector<fs::path> infos;
        for (const auto& entry : fs::directory_iterator(path, ec))
            if (!infoNumber(entry.path().filename().string()).empty()) infos.push_back(entry.path());
        if (infos.empty()) return std::nullopt;
        // Several outputs: ambiguous, said as such (naming them), not as "no info file".
        std::sort(infos.begin(), infos.end());
        std::vector<std::string> names;
        for (const fs::path& p : infos) names.push_back(p.filename().string());
        const std::string first = names.front();
        if (names.size() > 4) names = {names[0], names[1], names[2], "...", names.back()};
        AMRVK_CHECK(infos.size() == 1, path.string(), ": ", infos.size(), " RAMSES info files (", join(names, ", "),
                    "): name the one to read, e.g. ", infos.front().string());
        return Output{path, infoNumber(first), infos.front()};
    }
    const std::string number = infoNumber(path.filename().string());
    if (number.empty()) return std::nullopt;
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    return Output{dir, number, path};
}

// info_NNNNN.txt: "key = value" lines.
struct Info {
    int ncpu = 0, ndim = 0, levelmin = 0, levelmax = 0;
    double boxlen = 0, time = 0, unitL = 0, unitD = 0, unitT = 0;
    std::string ordering;
};

Info readInfo(const fs::path& path) {
    std::map<std::string, std::string> values;  // the last of a key wins
    for (auto& [key, value] : keyValueLines(readTextFile(path), false)) values[key] = std::move(value);
    auto get = [&](const char* key) -> const std::string& {
        auto it = values.find(key);
        AMRVK_CHECK(it != values.end(), path.string(), ": no '", key, " =' line");
        return it->second;
    };
    auto integer = [&](const char* key, int lo, int hi) {
        const std::string& s = get(key);
        int64_t v = 0;
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        AMRVK_CHECK(ec == std::errc() && ptr == s.data() + s.size(), path.string(), ": ", key, " '", s,
                    "' is not an integer");
        return int(checkedInRange(v, lo, hi, path.string() + ": " + key));
    };
    auto real = [&](const char* key) {
        const std::string& s = get(key);
        double v = 0;
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        AMRVK_CHECK(ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(v), path.string(), ": ", key, " '",
                    s, "' is not a finite number");
        return v;
    };
    Info info;
    info.ncpu = integer("ncpu", 1, INT32_MAX);
    info.ndim = integer("ndim", 1, 3);
    AMRVK_CHECK(info.ndim >= 2, path.string(), ": ndim 1 (only 2-D and 3-D RAMSES outputs are supported)");
    info.levelmin = integer("levelmin", 0, INT32_MAX);
    info.levelmax = integer("levelmax", 1, INT32_MAX);
    info.boxlen = real("boxlen");
    AMRVK_CHECK(info.boxlen > 0, path.string(), ": boxlen ", info.boxlen, " is not positive");
    info.time = real("time");
    if (values.count("unit_l")) info.unitL = real("unit_l");
    if (values.count("unit_d")) info.unitD = real("unit_d");
    if (values.count("unit_t")) info.unitT = real("unit_t");
    if (values.count("ordering type")) info.ordering = values["ordering type"];
    return info;
}

// The hydro variables' names: hydro_file_descriptor.txt, new ("# version: 1", then
// "ivar, name, type" lines) or old ("nvar = N", then "variable #  i: name") format; without the
// file, RAMSES's own names: density, velocity_x/y[/z], pressure, then scalar_00, scalar_01, ...
std::vector<std::string> variableNames(const fs::path& descriptor, int nvar, int ndim) {
    std::vector<std::string> names;
    std::error_code ec;
    if (!fs::exists(descriptor, ec)) {
        const char* axes[] = {"velocity_x", "velocity_y", "velocity_z"};
        names.push_back("density");
        for (int a = 0; a < ndim && int(names.size()) < nvar; ++a) names.push_back(axes[a]);
        if (int(names.size()) < nvar) names.push_back("pressure");
        for (int s = 0; int(names.size()) < nvar; ++s) names.push_back(strCat(s < 10 ? "scalar_0" : "scalar_", s));
        return names;
    }
    const std::string text = readTextFile(descriptor);
    std::set<std::string> seen;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string line = trim(std::string_view(text.data() + pos, end - pos));
        pos = end + 1;
        if (line.empty() || line[0] == '#' || line.rfind("nvar", 0) == 0) continue;
        std::string name;
        if (line.rfind("variable #", 0) == 0) {  // old: "variable #  1: density"
            const size_t colon = line.find(':');
            AMRVK_CHECK(colon != std::string::npos, descriptor.string(), ": line '", line,
                        "' is not 'variable #  i: name'");
            name = trim(std::string_view(line).substr(colon + 1));
        } else {  // new: " 1, density, d"
            const size_t a = line.find(',');
            const size_t b = a == std::string::npos ? a : line.find(',', a + 1);
            AMRVK_CHECK(b != std::string::npos, descriptor.string(), ": line '", line, "' is not 'ivar, name, type'");
            name = trim(std::string_view(line).substr(a + 1, b - a - 1));
        }
        AMRVK_CHECK(!name.empty(), descriptor.string(), ": empty variable name in line '", line, "'");
        AMRVK_CHECK(seen.insert(name).second, descriptor.string(), ": variable '", name, "' is named twice");
        AMRVK_CHECK(int(names.size()) < nvar, descriptor.string(), ": names more than the ", nvar,
                    " variables of the hydro files");
        names.push_back(std::move(name));
    }
    AMRVK_CHECK(int(names.size()) == nvar, descriptor.string(), ": names ", names.size(),
                " variables, the hydro files hold ", nvar);
    return names;
}

// What the AMR files of all domains share (the first one read sets it; the others must match).
struct Mesh {
    int ncpu = 0, ndim = 0, nlevelmax = 0, nboundary = 0;
    glm::ivec3 n{1};       // coarse cells per axis (nx, ny, nz)
    glm::ivec3 skip{0};    // coarse boundary cells below the domain (nx/2 with boundaries)
    glm::ivec3 extent{1};  // coarse cells of the domain per axis
    double boxlen = 0;
};

// A leaf read from a domain file: its RAMSES level and integer index on that level (the lower
// corner in units of 2^-level coarse cells, from the domain's lower corner).
struct Leaf {
    int level;
    glm::i64vec3 index;
};

// The octs a domain file owns on one level, as the hydro file needs them.
struct OwnLevel {
    std::vector<std::pair<uint32_t, uint8_t>> leaves;  // (oct, cell 0..2^ndim-1), in cell order
};

struct DomainAmr {
    std::vector<int32_t> ncache;  // [level][ibound]: octs listed per level and ibound (1-based order)
    std::vector<OwnLevel> own;    // per level 1..nlevelmax (index level - 1)
};

const char* kAxisNames[] = {"xg(x)", "xg(y)", "xg(z)"};

// The header of one domain's AMR file up to its octs: checked against `info` and `mesh` (set
// from the first file), with the oct counts per level and domain (numbl) and boundary (numbb).
struct AmrHeader {
    int32_t ncpu = 0, ndim = 0, nlevelmax = 0;
    int realBytes = 8;
    std::vector<int32_t> numbl, numbb;
};
AmrHeader readAmrHeader(RecordReader& in, int domain, const Info& info, const std::string& infoName, Mesh& mesh) {
    const std::string& name = in.name();
    const bool first = domain == 1;
    AmrHeader hd;
    auto same = [&](const char* what, int64_t value, int64_t expected, const std::string& from) {
        AMRVK_CHECK(value == expected, name, ": ", what, " ", value, " differs from ", expected, " in ", from);
    };
    const int32_t ncpu = hd.ncpu = in.scalar<int32_t>("ncpu");
    same("ncpu", ncpu, info.ncpu, infoName);
    const int32_t ndim = hd.ndim = in.scalar<int32_t>("ndim");
    same("ndim", ndim, info.ndim, infoName);
    const std::vector<int32_t> n = in.values<int32_t>("nx ny nz", 3);
    const int32_t nlevelmax = hd.nlevelmax = in.scalar<int32_t>("nlevelmax");
    same("nlevelmax", nlevelmax, info.levelmax, infoName);
    in.skip("ngridmax");
    const int32_t nboundary = in.scalar<int32_t>("nboundary");
    in.skip("ngrid_current");
    const double boxlen = in.realScalar("boxlen", hd.realBytes);
    if (first) {
        mesh.ncpu = ncpu;
        mesh.ndim = ndim;
        mesh.nlevelmax = nlevelmax;
        mesh.nboundary = int(checkedInRange(nboundary, 0, INT32_MAX, name + ": nboundary"));
        for (int a = 0; a < 3; ++a) {
            mesh.n[a] = int(checkedInRange(n[size_t(a)], 1, kMaxIndex, name + ": nx ny nz"));
            // With boundary regions the domain is the coarse grid less nx/2 cells on each side
            // (nx = 3: its centre cell), as RAMSES's own outputs place it.
            mesh.skip[a] = mesh.nboundary > 0 ? mesh.n[a] / 2 : 0;
            mesh.extent[a] = mesh.n[a] - 2 * mesh.skip[a];
            AMRVK_CHECK(mesh.extent[a] >= 1, name, ": ", mesh.n[a], " coarse cells on axis ", a,
                        " leave no domain inside ", mesh.nboundary, " boundary regions");
        }
        AMRVK_CHECK(ndim == 3 || mesh.n.z == 1, name, ": 2-D output with nz ", mesh.n.z, " (expected 1)");
        mesh.boxlen = boxlen;
    } else {
        const std::string firstName = "the first domain file";
        same("nx", n[0], mesh.n.x, firstName);
        same("ny", n[1], mesh.n.y, firstName);
        same("nz", n[2], mesh.n.z, firstName);
        same("nboundary", nboundary, mesh.nboundary, firstName);
    }
    AMRVK_CHECK(std::isfinite(boxlen) && boxlen > 0, name, ": boxlen ", boxlen, " is not positive");
    // noutput iout ifout | tout | aout | t | dtold | dtnew | nstep nstep_coarse | einit mass_tot_0
    // rho_tot | omega_m ... boxlen_ini | aexp hexp aexp_old epot_tot_int epot_tot_old | mass_sph
    const char* skipped[] = {
        "noutput iout ifout",       "tout",      "aout",      "t",       "dtold", "dtnew", "nstep nstep_coarse",
        "einit mass_tot_0 rho_tot", "cosmology", "aexp hexp", "mass_sph"};
    for (const char* what : skipped) in.skip(what);

    const uint64_t levels = uint64_t(nlevelmax);
    const uint64_t perLevel = checkedProduct({uint64_t(ncpu), levels}, name + ": ncpu x nlevelmax");
    in.skipValues("headl", perLevel, 4);
    in.skipValues("taill", perLevel, 4);
    hd.numbl = in.values<int32_t>("numbl", perLevel);  // cpu fastest
    in.skipValues("numbtot", checkedProduct({10, levels}, name + ": numbtot"), 4);
    const uint64_t boundaries = uint64_t(mesh.nboundary);
    if (boundaries > 0) {
        const uint64_t perBoundary = checkedProduct({boundaries, levels}, name + ": nboundary x nlevelmax");
        in.skipValues("headb", perBoundary, 4);
        in.skipValues("tailb", perBoundary, 4);
        hd.numbb = in.values<int32_t>("numbb", perBoundary);
    }
    in.skip("headf tailf numbf used_mem used_mem_tot");
    const std::string ordering = in.text("ordering");
    if (ordering == "bisection") {
        const char* bisection[] = {"bisec_wall", "bisec_next", "bisec_indx", "bisec_cpubox_min", "bisec_cpubox_max"};
        for (const char* what : bisection) in.skip(what);
    } else {
        in.skip("bound_key");  // 8 or 16-byte reals: skipped by its length
    }
    const uint64_t ncoarse =
        checkedProduct({uint64_t(mesh.n.x), uint64_t(mesh.n.y), uint64_t(mesh.n.z)}, name + ": nx ny nz");
    in.skipValues("son (coarse)", ncoarse, 4);
    in.skipValues("flag1 (coarse)", ncoarse, 4);
    in.skipValues("cpu_map (coarse)", ncoarse, 4);

    return hd;
}

// The leaf cells of `count` own octs of level l (centres xg per axis, son per child; 0: a leaf),
// appended to `leaves` and, by oct and child, to `mine`. Every centre is checked to be a level-l
// oct's inside the domain.
void addOwnLeaves(const std::string& name, int l, uint64_t count, int ndim, const std::vector<std::vector<double>>& xg,
                  const std::vector<std::vector<int32_t>>& son, const Mesh& mesh, std::vector<Leaf>& leaves,
                  OwnLevel& mine) {
    const int twotondim = 1 << ndim;
    const double scale = std::ldexp(1.0, l);  // level-l cells per coarse cell
    for (uint64_t i = 0; i < count; ++i) {
        // The oct's lower corner on level l: (xg - skip) * 2^l - 1, an even integer inside the domain.
        glm::i64vec3 corner(0);
        bool hasLeaf = false;
        for (int ind = 0; ind < twotondim; ++ind) hasLeaf = hasLeaf || son[size_t(ind)][i] == 0;
        if (!hasLeaf) continue;
        AMRVK_CHECK(l <= kMaxLevel, name, ": leaf cells on RAMSES level ", l, " (amrvk holds at most ",
                    kMaxLevel, " levels of refinement below the coarse grid)");
        for (int a = 0; a < ndim; ++a) {
            const double g = (xg[size_t(a)][i] - mesh.skip[a]) * scale - 1.0;
            const double hi = mesh.extent[a] * scale - 2.0;
            AMRVK_CHECK(std::isfinite(g) && g >= 0 && g <= hi && g == std::floor(g) && std::fmod(g, 2.0) == 0,
                        name, ": oct ", i, " of level ", l, " has centre ", xg[size_t(a)][i], " on axis ", a,
                        ", not the centre of a level-", l, " oct inside the domain");
            corner[a] = int64_t(g);
        }
        for (int ind = 0; ind < twotondim; ++ind) {
            if (son[size_t(ind)][i] != 0) continue;
            const glm::i64vec3 offset(ind & 1, (ind >> 1) & 1, ndim == 3 ? (ind >> 2) & 1 : 0);
            leaves.push_back({l, corner + offset});
            mine.leaves.emplace_back(uint32_t(i), uint8_t(ind));
        }
    }
}

// Reads one domain's AMR file: checks it against `mesh` (set from the first file), appends its
// own leaves to `leaves`.
DomainAmr readAmrFile(const fs::path& path, int domain, const Info& info, const std::string& infoName, Mesh& mesh,
                      std::vector<Leaf>& leaves, std::vector<uint64_t>& octsPerLevel) {
    RecordReader in(path);
    const std::string& name = in.name();
    const AmrHeader hd = readAmrHeader(in, domain, info, infoName, mesh);
    const int32_t ncpu = hd.ncpu, ndim = hd.ndim, nlevelmax = hd.nlevelmax;
    const int realBytes = hd.realBytes;
    const std::vector<int32_t>& numbl = hd.numbl;
    const std::vector<int32_t>& numbb = hd.numbb;
    const uint64_t levels = uint64_t(nlevelmax), boundaries = uint64_t(mesh.nboundary);
    octsPerLevel.resize(levels, 0);  // every file has nlevelmax == info's levelmax
    DomainAmr amr;
    const uint64_t bounds = uint64_t(ncpu) + boundaries;
    amr.ncache.resize(checkedProduct({levels, bounds}, name + ": levels x domains"));
    amr.own.resize(levels);
    const int twotondim = 1 << ndim;
    for (int l = 1; l <= nlevelmax; ++l) {
        const size_t li = size_t(l - 1);
        for (uint64_t ib = 1; ib <= bounds; ++ib) {
            const int32_t ncache = ib <= uint64_t(ncpu) ? numbl[li * uint64_t(ncpu) + ib - 1]
                                                        : numbb[li * boundaries + ib - uint64_t(ncpu) - 1];
            AMRVK_CHECK(ncache >= 0, name, ": negative oct count ", ncache, " on level ", l);
            amr.ncache[li * bounds + ib - 1] = ncache;
            if (ncache == 0) continue;
            const uint64_t count = uint64_t(ncache);
            const bool own = ib == uint64_t(domain);
            in.skipValues("ind_grid", count, 4);
            in.skipValues("next", count, 4);
            in.skipValues("prev", count, 4);
            std::vector<std::vector<double>> xg(static_cast<size_t>(ndim));
            for (int a = 0; a < ndim; ++a) {
                if (own)
                    xg[size_t(a)] = in.reals(kAxisNames[a], count, realBytes);
                else
                    in.skipValues(kAxisNames[a], count, uint64_t(realBytes));
            }
            in.skipValues("father", count, 4);
            for (int k = 0; k < 2 * ndim; ++k) in.skipValues("nbor", count, 4);
            std::vector<std::vector<int32_t>> son(static_cast<size_t>(twotondim));
            for (int ind = 0; ind < twotondim; ++ind) {
                if (own)
                    son[size_t(ind)] = in.values<int32_t>("son", count);
                else
                    in.skipValues("son", count, 4);
            }
            for (int k = 0; k < 2 * twotondim; ++k) in.skipValues(k < twotondim ? "cpu_map" : "flag1", count, 4);
            if (!own) continue;

            octsPerLevel[li] += count;
            addOwnLeaves(name, l, count, ndim, xg, son, mesh, leaves, amr.own[li]);
        }
    }
    return amr;
}

// Reads one domain's hydro file: the selected variables of its own leaves, written to
// fields[f][base + k] for the k-th leaf of `amr` (level by level, in cell order).
void readHydroFile(const fs::path& path, const Mesh& mesh, int nvar, const DomainAmr& amr, int domain,
                   const std::vector<size_t>& components, std::vector<Field>& fields, size_t base) {
    RecordReader in(path);
    const std::string& name = in.name();
    auto same = [&](const char* what, int64_t value, int64_t expected, const char* from) {
        AMRVK_CHECK(value == expected, name, ": ", what, " ", value, " differs from ", expected, " in ", from);
    };
    same("ncpu", in.scalar<int32_t>("ncpu"), mesh.ncpu, "the AMR files");
    same("nvar", in.scalar<int32_t>("nvar"), nvar, "the first hydro file");
    same("ndim", in.scalar<int32_t>("ndim"), mesh.ndim, "the AMR files");
    same("nlevelmax", in.scalar<int32_t>("nlevelmax"), mesh.nlevelmax, "the AMR files");
    same("nboundary", in.scalar<int32_t>("nboundary"), mesh.nboundary, "the AMR files");
    int realBytes = 8;
    in.realScalar("gamma", realBytes);
    const uint64_t bounds = uint64_t(mesh.ncpu) + uint64_t(mesh.nboundary);
    const int twotondim = 1 << mesh.ndim;
    std::vector<int> slot(size_t(nvar), -1);  // variable -> index in `fields`, -1 when not loaded
    for (size_t f = 0; f < components.size(); ++f) slot[components[f]] = int(f);
    size_t next = base;
    for (int l = 1; l <= mesh.nlevelmax; ++l) {
        const size_t li = size_t(l - 1);
        for (uint64_t ib = 1; ib <= bounds; ++ib) {
            same("level", in.scalar<int32_t>("ilevel"), l, "the record order");
            const int32_t expected = amr.ncache[li * bounds + ib - 1];
            const int32_t ncache = in.scalar<int32_t>("ncache");
            AMRVK_CHECK(ncache == expected, name, ": ", ncache, " octs on level ", l, " for domain ", ib,
                        ", the AMR file lists ", expected);
            if (ncache == 0) continue;
            const bool own = ib == uint64_t(domain);
            const OwnLevel& mine = amr.own[li];
            for (int ind = 0; ind < twotondim; ++ind)
                for (int v = 0; v < nvar; ++v) {
                    const int f = slot[size_t(v)];
                    if (!own || f < 0 || mine.leaves.empty()) {
                        in.skipValues("hydro variable", uint64_t(ncache), uint64_t(realBytes));
                        continue;
                    }
                    const std::vector<double> values = in.reals("hydro variable", uint64_t(ncache), realBytes);
                    std::vector<float>& out = fields[size_t(f)].values;
                    for (size_t k = 0; k < mine.leaves.size(); ++k)
                        if (mine.leaves[k].second == ind) out[next + k] = float(values[mine.leaves[k].first]);
                }
            if (own) next += mine.leaves.size();
        }
    }
}

}  // namespace

fs::path ramsesInfoFile(const fs::path& path) {
    const std::optional<Output> out = findOutput(path);
    return out ? out->info : fs::path();
}

Model readRamses(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "ramses", .source = path.string()};
    const std::optional<Output> found = findOutput(path);
    AMRVK_CHECK(found, path.string(),
                ": not a RAMSES output (expected an output_NNNNN directory or its info_NNNNN.txt)");
    const Output& out = *found;
    const Info info = readInfo(out.info);
    const std::string infoName = out.info.filename().string();
    // Every domain's files exist before any is read.
    for (int c = 1; c <= info.ncpu; ++c)
        for (const char* kind : {"amr", "hydro"}) {
            const fs::path p = out.file(kind, c);
            std::error_code ec;
            AMRVK_CHECK(fs::exists(p, ec), p.string(), ": no such file (", infoName, " lists ", info.ncpu, " domains)");
        }

    int nvar = 0;
    {
        RecordReader hydro(out.file("hydro", 1));
        hydro.skip("ncpu");
        nvar = int(checkedInRange(hydro.scalar<int32_t>("nvar"), 1, 1 << 16, hydro.name() + ": nvar"));
    }
    model.availableFields = variableNames(out.dir / "hydro_file_descriptor.txt", nvar, info.ndim);
    const std::vector<size_t> components = addSelectedFields(model, options.fields);
    // Code units: unit_d g/cm^3, unit_l / unit_t cm/s (0: the info file does not say).
    const CodeUnits units{.density = info.unitD,
                          .velocity = info.unitL > 0 && info.unitT > 0 ? info.unitL / info.unitT : 0};
    for (Field& f : model.fields) f.units = fieldUnits(ramsesQuantity(f.name), units);

    Mesh mesh;
    std::vector<Leaf> leaves;
    std::vector<uint64_t> octsPerLevel;  // sized by the first AMR file, once its records hold the levels
    for (int c = 1; c <= info.ncpu; ++c) {
        const size_t base = leaves.size();
        const DomainAmr amr = readAmrFile(out.file("amr", c), c, info, infoName, mesh, leaves, octsPerLevel);
        checkAllocation(checkedProduct({leaves.size(), sizeof(float), model.fields.size()}, "RAMSES leaf values"),
                        "RAMSES leaf values");
        for (Field& f : model.fields) f.values.resize(leaves.size());
        readHydroFile(out.file("hydro", c), mesh, nvar, amr, c, components, model.fields, base);
    }
    AMRVK_CHECK(!leaves.empty(), out.dir.string(), ": no leaf cells in ", info.ncpu, " domain files");

    // amrvk cells: the deepest leaf level L is amrvk level 0; level l has width 2^(L - l).
    int deepest = 0, coarsest = INT32_MAX;
    for (const Leaf& leaf : leaves) {
        deepest = std::max(deepest, leaf.level);
        coarsest = std::min(coarsest, leaf.level);
    }
    for (int a = 0; a < mesh.ndim; ++a)
        AMRVK_CHECK((int64_t(mesh.extent[a]) << deepest) <= INT32_MAX, out.dir.string(), ": ", mesh.extent[a],
                    " coarse cells refined to RAMSES level ", deepest, " exceed amrvk's 2^31 voxels per axis");
    model.cells.reserve(leaves.size());
    for (const Leaf& leaf : leaves) {
        const int shift = deepest - leaf.level;
        model.cells.push_back({glm::ivec3(leaf.index * (int64_t(1) << shift)), shift});
    }

    // world = boxlen * position in the domain (code units): a finest cell is boxlen / (extent_x 2^L).
    const double voxel = mesh.boxlen / (double(mesh.extent.x) * std::ldexp(1.0, deepest));
    model.voxelToWorld.scale = glm::dvec3(voxel);
    model.voxelToWorld.origin = glm::dvec3(0.0);

    model.attributes = {
        {"dimensions", std::to_string(mesh.ndim)},
        {"domains", std::to_string(mesh.ncpu)},
        {"levels", strCat(info.levelmin, "..", info.levelmax)},
        {"leafLevels", strCat(coarsest, "..", deepest)},
        {"octsPerLevel", join(octsPerLevel)},
        {"time", formatDouble(info.time)},
        {"boxlen", formatDouble(mesh.boxlen)},
    };
    if (info.unitL > 0) model.attributes.emplace_back("unit_l", formatDouble(info.unitL));
    if (info.unitD > 0) model.attributes.emplace_back("unit_d", formatDouble(info.unitD));
    if (info.unitT > 0) model.attributes.emplace_back("unit_t", formatDouble(info.unitT));
    if (!info.ordering.empty()) model.attributes.emplace_back("ordering", info.ordering);
    return model;
}

}  // namespace amrvk::amr
