#pragma once
// Small synthetic RAMSES outputs for what the three real ones lack (float32 reals, bisection
// ordering, boundary regions, a boxlen other than 1, the old descriptor format, leaves whose owner
// is another domain in every file): the reader tests write them to disk, the fuzz seed generator
// joins them into fuzz_ramses inputs. One coarse cell (three per axis with boundaries), levels 1
// and 2: the level-1 oct's first cell is refined into a level-2 oct; domain 1 owns the level-1
// oct, domain 2 (when there are two) the level-2 one, and each file lists the other's oct as a
// ghost, as RAMSES does. Layout: shared/data/amr/FORMATS.md 4.4.
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

namespace amrvk::test::ramses {

struct Synthetic {
    int ndim = 3;
    int ncpu = 1;       // 1 or 2
    int realBytes = 8;  // 4 or 8
    bool bisection = false;
    bool boundaries = false;  // nx = 3 with 2 * ndim boundary regions: the domain is the centre cell
    double boxlen = 1.0;
    enum Descriptor { None, Old, New } descriptor = New;
};

// Value of variable v at a leaf centred at c (coarse-cell units in [0, 1]; 2-D: c.z = 0).
inline double synthValue(int v, glm::dvec3 c) { return 1 + v + 10 * c.x + 100 * c.y + 1000 * c.z; }

inline int nvarOf(const Synthetic& s) { return s.ndim + 2; }

struct SynthOct {
    int level;
    glm::dvec3 centre;  // in coarse-grid units, boundary cells included
    int owner;          // 1-based domain
    int refinedCell;    // cell index 0..2^ndim-1 refined into the next level's oct, or -1
};

inline std::vector<SynthOct> synthOcts(const Synthetic& s) {
    const double skip = s.boundaries ? 1.0 : 0.0;
    const glm::dvec3 off(skip, skip, s.ndim == 3 ? skip : 0.0);
    const glm::dvec3 c1 = off + glm::dvec3(0.5, 0.5, s.ndim == 3 ? 0.5 : 0.0);
    const glm::dvec3 c2 = off + glm::dvec3(0.25, 0.25, s.ndim == 3 ? 0.25 : 0.0);
    return {{1, c1, 1, 0}, {2, c2, s.ncpu, -1}};
}

inline void record(std::string& out, const void* data, size_t bytes) {
    const int32_t n = int32_t(bytes);
    out.append(reinterpret_cast<const char*>(&n), 4);
    out.append(static_cast<const char*>(data), bytes);
    out.append(reinterpret_cast<const char*>(&n), 4);
}
inline void ints(std::string& out, const std::vector<int32_t>& v) { record(out, v.data(), v.size() * 4); }
inline void reals(std::string& out, const std::vector<double>& v, int realBytes) {
    if (realBytes == 8) return record(out, v.data(), v.size() * 8);
    const std::vector<float> f(v.begin(), v.end());
    record(out, f.data(), f.size() * 4);
}

inline std::string amrFile(const Synthetic& s, int domain) {
    const int nlevelmax = 2, nb = s.boundaries ? 2 * s.ndim : 0, r = s.realBytes;
    const int n = s.boundaries ? 3 : 1, nz = s.ndim == 3 ? n : 1;
    const std::vector<SynthOct> octs = synthOcts(s);
    std::string o;
    ints(o, {s.ncpu});
    ints(o, {s.ndim});
    ints(o, {n, n, nz});
    ints(o, {nlevelmax});
    ints(o, {100});
    ints(o, {nb});
    ints(o, {int32_t(octs.size())});
    reals(o, {s.boxlen}, r);
    ints(o, {1, 1, 1});
    reals(o, {0.0}, r);
    reals(o, {1.0}, r);
    reals(o, {0.0}, r);
    reals(o, {0.0, 0.0}, r);
    reals(o, {0.0, 0.0}, r);
    ints(o, {0, 0});
    reals(o, {0, 0, 0}, r);
    reals(o, {1, 0, 0, 0, 1, 1, s.boxlen}, r);
    reals(o, {1, 0, 1, 0, 0}, r);
    reals(o, {0.0}, r);
    std::vector<int32_t> numbl(size_t(s.ncpu * nlevelmax), 0);
    for (const SynthOct& oct : octs) ++numbl[size_t((oct.level - 1) * s.ncpu + oct.owner - 1)];
    ints(o, std::vector<int32_t>(numbl.size(), 1));  // headl
    ints(o, std::vector<int32_t>(numbl.size(), 1));  // taill
    ints(o, numbl);
    ints(o, std::vector<int32_t>(size_t(10 * nlevelmax), 0));
    if (nb > 0) {
        const std::vector<int32_t> zeros(size_t(nb * nlevelmax), 0);
        ints(o, zeros);
        ints(o, zeros);
        ints(o, zeros);
    }
    ints(o, {0, 0, 0, 0, 0});
    std::string ordering(128, ' ');
    const char* name = s.bisection ? "bisection" : "hilbert";
    std::memcpy(ordering.data(), name, std::strlen(name));
    record(o, ordering.data(), ordering.size());
    if (s.bisection) {
        for (int k = 0; k < 5; ++k) reals(o, std::vector<double>(size_t(s.ncpu + 1), 0.0), 8);
    } else {
        reals(o, std::vector<double>(size_t(s.ncpu + 1), 0.0), 8);
    }
    const size_t ncoarse = size_t(n * n * nz);
    ints(o, std::vector<int32_t>(ncoarse, 0));
    ints(o, std::vector<int32_t>(ncoarse, 0));
    ints(o, std::vector<int32_t>(ncoarse, 1));
    const int cells = 1 << s.ndim;
    for (int l = 1; l <= nlevelmax; ++l)
        for (int ib = 1; ib <= s.ncpu + nb; ++ib)
            for (const SynthOct& oct : octs) {
                if (oct.level != l || oct.owner != ib) continue;
                (void)domain;  // every file lists every oct; readers keep their own domain's
                ints(o, {1});
                ints(o, {0});
                ints(o, {0});
                for (int a = 0; a < s.ndim; ++a) reals(o, {oct.centre[a]}, r);
                ints(o, {0});
                for (int k = 0; k < 2 * s.ndim; ++k) ints(o, {0});
                for (int ind = 0; ind < cells; ++ind) ints(o, {ind == oct.refinedCell ? 2 : 0});
                for (int ind = 0; ind < cells; ++ind) ints(o, {oct.owner});
                for (int ind = 0; ind < cells; ++ind) ints(o, {0});
            }
    return o;
}

// Centre of cell `ind` of an oct (coarse units, boundary offset removed; 2-D: z = 0).
inline glm::dvec3 cellCentre(const Synthetic& s, const SynthOct& oct, int ind) {
    const double skip = s.boundaries ? 1.0 : 0.0;
    const double dx = std::ldexp(1.0, -oct.level);
    glm::dvec3 c = oct.centre - glm::dvec3(skip, skip, s.ndim == 3 ? skip : 0.0);
    c.x += ((ind & 1) - 0.5) * dx;
    c.y += (((ind >> 1) & 1) - 0.5) * dx;
    if (s.ndim == 3) c.z += (((ind >> 2) & 1) - 0.5) * dx;
    return c;
}

inline std::string hydroFile(const Synthetic& s) {
    const int nlevelmax = 2, nb = s.boundaries ? 2 * s.ndim : 0, nvar = nvarOf(s);
    const std::vector<SynthOct> octs = synthOcts(s);
    std::string o;
    ints(o, {s.ncpu});
    ints(o, {nvar});
    ints(o, {s.ndim});
    ints(o, {nlevelmax});
    ints(o, {nb});
    reals(o, {1.4}, s.realBytes);
    for (int l = 1; l <= nlevelmax; ++l)
        for (int ib = 1; ib <= s.ncpu + nb; ++ib) {
            const SynthOct* mine = nullptr;
            for (const SynthOct& oct : octs)
                if (oct.level == l && oct.owner == ib) mine = &oct;
            ints(o, {l});
            ints(o, {mine ? 1 : 0});
            if (!mine) continue;
            for (int ind = 0; ind < (1 << s.ndim); ++ind)
                for (int v = 0; v < nvar; ++v)
                    reals(o, {ind == mine->refinedCell ? -1.0 : synthValue(v, cellCentre(s, *mine, ind))}, s.realBytes);
        }
    return o;
}

inline std::string infoText(const Synthetic& s) {
    std::string t = "ncpu        =          " + std::to_string(s.ncpu) + "\n";
    t += "ndim        =          " + std::to_string(s.ndim) + "\n";
    t += "levelmin    =          1\nlevelmax    =          2\nngridmax    =        100\nnstep_coarse=          0\n\n";
    t += "boxlen      =  " + std::to_string(s.boxlen) + "\n";
    t += "time        =  0.500000000000000E+00\naexp        =  0.100000000000000E+01\n";
    t += "unit_l      =  0.100000000000000E+01\nunit_d      =  0.100000000000000E+01\n";
    t += "unit_t      =  0.100000000000000E+01\n\n";
    t += std::string("ordering type=") + (s.bisection ? "bisection" : "hilbert") + "\n";
    return t;
}

inline std::string descriptorText(const Synthetic& s) {
    const std::vector<std::string> names = s.ndim == 3 ? std::vector<std::string>{"rho", "u", "v", "w", "p"}
                                                       : std::vector<std::string>{"rho", "u", "v", "p"};
    std::string t;
    if (s.descriptor == Synthetic::Old) {
        t = "nvar =          " + std::to_string(names.size()) + "\n";
        for (size_t i = 0; i < names.size(); ++i) t += "variable #  " + std::to_string(i + 1) + ": " + names[i] + "\n";
    } else {
        t = "# version:  1\n# ivar, variable_name, variable_type\n";
        for (size_t i = 0; i < names.size(); ++i) t += " " + std::to_string(i + 1) + ", " + names[i] + ", d\n";
    }
    return t;
}

// The files of output_00001 (name -> bytes), the descriptor only when s.descriptor != None.
inline std::map<std::string, std::string> outputFiles(const Synthetic& s) {
    std::map<std::string, std::string> files;
    files["info_00001.txt"] = infoText(s);
    if (s.descriptor != Synthetic::None) files["hydro_file_descriptor.txt"] = descriptorText(s);
    for (int c = 1; c <= s.ncpu; ++c) {
        const std::string suffix = "_00001.out0000" + std::to_string(c);
        files["amr" + suffix] = amrFile(s, c);
        files["hydro" + suffix] = hydroFile(s);
    }
    return files;
}

}  // namespace amrvk::test::ramses
