#pragma once
// Small synthetic AMReX plotfiles for what the real one lacks (2-D, ghost cells, float32,
// big-endian, raw VisMF versions 2-4, refinement ratio 3): the reader tests write them to disk,
// the fuzz seed generator joins them into fuzz_amrex inputs.
#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace amrvk::test::amrex {

struct Synthetic {
    int dim = 3;
    int vismfVersion = 1;
    int realBytes = 8;
    bool bigEndian = false;
    int ngrow = 0;
    bool ngrowAsIntVect = false;
    int ratio = 2;
    int levels = 2;  // 1: level 0 only
};

inline constexpr float kGhostValue = -7777.0f;

// Value of component c at cell (i,j,k) of level l: exact in float32.
inline float synthValue(int level, int comp, int i, int j, int k) {
    return float(1000 * level + 100 * comp + i + 10 * j) + 0.25f * float(k);
}

inline std::string intVect(glm::ivec3 v, int dim) {
    std::string s = "(" + std::to_string(v.x) + "," + std::to_string(v.y);
    if (dim == 3) s += "," + std::to_string(v.z);
    return s + ")";
}

inline std::string boxText(glm::ivec3 lo, glm::ivec3 hi, int dim) {
    return "(" + intVect(lo, dim) + " " + intVect(hi, dim) + " " + intVect(glm::ivec3(0), dim) +
           ")";
}

inline std::string realDescriptor(const Synthetic& s) {
    std::string format = s.realBytes == 8 ? "(64 11 52 0 1 12 0 1023)" : "(32 8 23 0 1 9 0 127)";
    std::string order;
    for (int i = 0; i < s.realBytes; ++i) {
        if (i) order += " ";
        order += std::to_string(s.bigEndian ? i + 1 : s.realBytes - i);
    }
    const std::string n = std::to_string(s.realBytes);
    return "((" + n + ", " + format + "),(" + n + ", (" + order + ")))";
}

inline void appendReal(std::string& out, double v, const Synthetic& s) {
    unsigned char b[8];
    if (s.realBytes == 8)
        std::memcpy(b, &v, 8);
    else {
        float f = static_cast<float>(v);
        std::memcpy(b, &f, 4);
    }
    const size_t n = static_cast<size_t>(s.realBytes);
    if (s.bigEndian == (std::endian::native == std::endian::little)) std::reverse(b, b + n);
    out.append(reinterpret_cast<const char*>(b), n);
}

// Two levels (or level 0 only) on [0, 1]^dim: level 0 is 4^dim cells, level 1 one box of 4^dim
// cells over level-0 cells 1..2 (with ratio 2). Components "a" and "b(x)".
inline std::vector<std::pair<std::string, std::string>> plotfileFiles(const Synthetic& s) {
    std::vector<std::pair<std::string, std::string>> files;
    const int d = s.dim;
    const glm::ivec3 one = d == 3 ? glm::ivec3(1) : glm::ivec3(1, 1, 0);
    const glm::ivec3 lo[2] = {glm::ivec3(0), 2 * one};
    const glm::ivec3 hi[2] = {3 * one, 5 * one};
    const glm::ivec3 domainHi[2] = {3 * one, (4 * s.ratio - 1) * one};
    std::ostringstream h;
    h << "HyperCLaw-V1.1\n2\na\nb(x)\n" << d << "\n0.5\n" << s.levels - 1 << "\n";
    for (int a = 0; a < d; ++a) h << "0 ";
    h << "\n";
    for (int a = 0; a < d; ++a) h << "1 ";
    h << "\n";
    if (s.levels == 2) h << s.ratio << " ";
    h << "\n";
    for (int l = 0; l < s.levels; ++l) h << boxText(glm::ivec3(0), domainHi[l], d) << " ";
    h << "\n";
    for (int l = 0; l < s.levels; ++l) h << "0 ";
    h << "\n";
    for (int l = 0; l < s.levels; ++l) {
        for (int a = 0; a < d; ++a) h << 0.25 / (l ? s.ratio : 1) << " ";
        h << "\n";
    }
    h << "0\n0\n";
    for (int l = 0; l < s.levels; ++l) {
        h << l << " 1 0.5\n0\n";
        for (int a = 0; a < d; ++a) h << "0 1\n";
        h << "Level_" << l << "/Cell\n";
    }
    files.emplace_back("Header", h.str());

    for (int l = 0; l < s.levels; ++l) {
        const std::string levelDir = "Level_" + std::to_string(l) + "/";
        const glm::ivec3 g = s.ngrow * one;
        const glm::ivec3 flo = lo[l] - g, fhi = hi[l] + g;
        std::string data;
        if (s.vismfVersion == 1) data = "FAB " + realDescriptor(s) + boxText(flo, fhi, d) + " 2\n";
        for (int c = 0; c < 2; ++c)
            for (int k = flo.z; k <= fhi.z; ++k)
                for (int j = flo.y; j <= fhi.y; ++j)
                    for (int i = flo.x; i <= fhi.x; ++i) {
                        const bool ghost = glm::any(glm::lessThan(glm::ivec3(i, j, k), lo[l])) ||
                                           glm::any(glm::greaterThan(glm::ivec3(i, j, k), hi[l]));
                        appendReal(data, ghost ? kGhostValue : synthValue(l, c, i, j, k), s);
                    }

        std::ostringstream ch;
        ch << s.vismfVersion << "\n0\n2\n";
        if (s.ngrowAsIntVect)
            ch << intVect(s.ngrow * glm::ivec3(1), d) << "\n";
        else
            ch << s.ngrow << "\n";
        ch << "(1 0\n" << boxText(lo[l], hi[l], d) << "\n)\n1\nFabOnDisk: Cell_D_00000 0\n\n";
        if (s.vismfVersion == 1 || s.vismfVersion == 3)
            ch << "1,2\n0.0e+00,1.0e+02,\n\n1,2\n1.0e+03,1.1e+03,\n";
        if (s.vismfVersion == 4) ch << "0.0e+00,1.0e+02,\n1.0e+03,1.1e+03,\n";
        if (s.vismfVersion >= 2) ch << realDescriptor(s) << "\n";
        files.emplace_back(levelDir + "Cell_H", ch.str());
        files.emplace_back(levelDir + "Cell_D_00000", std::move(data));
    }
    return files;
}


}  // namespace amrvk::test::amrex
