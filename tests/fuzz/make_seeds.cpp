// Writes the fuzz targets' seed corpora: small valid inputs generated here (through the same
// APIs and layouts the reader tests use) plus inputs cut from the real data sets in
// ../shared/data/amr and the bundled assets where they exist (tools/run.sh fuzz; docs/fuzzing.md).
// Usage: amrvk_fuzz_seeds OUT_DIR DATA_DIR SOURCE_DIR   (writes OUT_DIR/<target>/seed-*)
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "amr/model.h"
#include "amrex_synthetic.h"
#include "fuzz_common.h"
#include "ramses_synthetic.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "session/session.h"

namespace fs = std::filesystem;
using namespace amrvk;

namespace {

fs::path gOut;
int gCount = 0;

std::string readAll(const fs::path& p, size_t limit = std::string::npos) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return {};
    std::ostringstream os;
    os << in.rdbuf();
    std::string s = os.str();
    if (s.size() > limit) s.resize(limit);
    return s;
}

void seed(const std::string& target, const std::string& name, const std::string& bytes) {
    fuzz::writeFile(gOut / target / ("seed-" + name), bytes);
    ++gCount;
}

template <typename T, typename A>
std::string bytesOf(const std::vector<T, A>& v) {
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// ---- ExaBrick ------------------------------------------------------------------------------
void exabrickSeeds(const fs::path& source) {
    const std::vector<amr::Cell> cells = {{{0, 0, 0}, 1}, {{2, 0, 0}, 0}, {{3, 0, 0}, 0},
                                          {{2, 1, 0}, 0}, {{3, 1, 0}, 0}};
    const std::vector<float> a = {1, 2, 3, 4, 5}, b = {-1, 0.5f, NAN, 7, 8};
    seed("exabrick", "five", fuzz::joinParts({bytesOf(cells), bytesOf(a)}));
    seed("exabrick", "two-fields", fuzz::joinParts({bytesOf(cells), bytesOf(a), bytesOf(b)}));
    // The bundled cloud sample, cut to its first 256 cells (a partial cover: validation errors).
    const std::string cc = readAll(source / "assets/samples/cloud.cells", 256 * 16);
    const std::string cs = readAll(source / "assets/samples/cloud.scalars", 256 * 4);
    if (!cc.empty()) seed("exabrick", "cloud-256", fuzz::joinParts({cc, cs}));

    // .bricks: the five-cell model's own bricks (written as `amrvk convert --bricks` would).
    amr::Model m;
    m.cells.append(cells);
    m.fields.push_back({"scalars", a});
    const fuzz::Scratch scratch;
    const fs::path tmp = scratch.path() / "m.bricks";
    accel::writeBricksFile(tmp, accel::buildBricks(m));  // m is now in brick order: write it so
    const std::vector<amr::Cell> ordered(m.cells.begin(), m.cells.end());
    seed("bricks", "five", fuzz::joinParts({bytesOf(ordered), bytesOf(m.fields[0].values), readAll(tmp)}));
}

// ---- AMReX (the synthetic plotfiles of the reader tests, tests/amrex_synthetic.h) -----------
std::string amrexSynthetic(int dim, int vismfVersion, int realBytes, bool bigEndian, int ngrow) {
    amrvk::test::amrex::Synthetic s;
    s.dim = dim;
    s.vismfVersion = vismfVersion;
    s.realBytes = realBytes;
    s.bigEndian = bigEndian;
    s.ngrow = ngrow;
    std::vector<std::string> parts;  // Header, then Cell_H and Cell_D_00000 per level: fuzz_amrex's order
    for (auto& [name, bytes] : amrvk::test::amrex::plotfileFiles(s)) parts.push_back(std::move(bytes));
    return fuzz::joinParts(parts);
}
void amrexSeeds(const fs::path& data) {
    seed("amrex", "synthetic-v1-3d", amrexSynthetic(3, 1, 8, false, 0));
    seed("amrex", "synthetic-v1-2d-ghost-float-be", amrexSynthetic(2, 1, 4, true, 1));
    seed("amrex", "synthetic-v2-3d", amrexSynthetic(3, 2, 8, false, 0));
    seed("amrex", "synthetic-v3-2d", amrexSynthetic(2, 3, 4, false, 0));
    seed("amrex", "synthetic-v4-3d-ghost", amrexSynthetic(3, 4, 8, false, 2));
    // The real PeleLM plotfile's Header, level 0 (Cell_H and its 156 KB of FAB data) and the
    // level-1 Cell_H (its data files are not in the input: the read ends there).
    const fs::path plt = data / "amrex_pelelm_3d/example_plt_3d";
    const std::string header = readAll(plt / "Header");
    if (!header.empty())
        seed("amrex", "pelelm-level0",
             fuzz::joinParts({header, readAll(plt / "Level_0/Cell_H"), readAll(plt / "Level_0/Cell_D_00000"),
                              readAll(plt / "Level_1/Cell_H")}));
}

// ---- Enzo -------------------------------------------------------------------------------------
// The grid-file description fuzz_enzo's FuzzedDataProvider reads back (integers in a range and
// bools come from the end of the data, one byte each for these small ranges): per grid "take id
// i+1" and two datasets Density and Temperature, rank 3, shape 4^3 or given, float32.
std::string enzoGridFile(const std::vector<glm::ivec3>& shapes) {
    // Bytes are consumed from the back, so build the sequence and reverse it.
    std::vector<uint8_t> seq;
    seq.push_back(uint8_t(shapes.size()));                  // grids (0..4)
    for (const glm::ivec3& s : shapes) {
        seq.push_back(1);                                   // id = i + 1
        seq.push_back(2);                                   // datasets (0..3)
        for (int name : {0, 1}) {
            seq.push_back(uint8_t(name));                   // Density, Temperature
            seq.push_back(1);                               // rank: not the 1-in-8 case -> 3
            for (int a : {2, 1, 0}) {                       // dims, slowest first
                seq.push_back(0);                           // not "4"
                seq.push_back(uint8_t(s[a]));               // 0..40
            }
            seq.push_back(0);                               // no odd value
            seq.push_back(0);                               // float32
        }
    }
    return std::string(seq.rbegin(), seq.rend());
}
const char* kEnzoParams =
    "InitialTime = 1.5\nTopGridRank = 3\nTopGridDimensions = 4 4 4\nDomainLeftEdge = 0 0 0\n"
    "DomainRightEdge = 1 1 1\nRefineBy = 2\nMaximumRefinementLevel = 1\n"
    "DataLabel[0] = Density\nDataLabel[1] = Temperature\n";
std::string enzoGrid(int id, glm::ivec3 dim, glm::ivec3 start, glm::ivec3 end, glm::dvec3 left,
                     glm::dvec3 right) {
    std::ostringstream h;
    auto v3 = [&](auto v) { return std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z); };
    h << "\nGrid = " << id << "\nTask = 0\nGridRank = 3\nGridDimension = " << v3(dim)
      << "\nGridStartIndex = " << v3(start) << "\nGridEndIndex = " << v3(end)
      << "\nGridLeftEdge = " << v3(left) << "\nGridRightEdge = " << v3(right)
      << "\nNumberOfBaryonFields = 2\nBaryonFileName = ./DD0000.cpu0000\n"
      << "Pointer: Grid[" << id << "]->NextGridThisLevel = 0\n";
    return h.str();
}
void enzoSeeds(const fs::path& data) {
    // Root grid 4^3 (no ghost zones in the file) and one level-1 grid 4^3 over root cells 1..2,
    // stored with 1 ghost zone (6^3).
    const std::string hierarchy =
        enzoGrid(1, glm::ivec3(4), glm::ivec3(0), glm::ivec3(3), glm::dvec3(0), glm::dvec3(1)) +
        enzoGrid(2, glm::ivec3(6), glm::ivec3(1), glm::ivec3(4), glm::dvec3(0.25), glm::dvec3(0.75));
    const std::string grids = enzoGridFile({glm::ivec3(4), glm::ivec3(6)});
    seed("enzo", "two-grids", fuzz::joinParts({kEnzoParams, hierarchy, grids}));
    seed("enzo", "root-only",
         fuzz::joinParts({kEnzoParams,
                          enzoGrid(1, glm::ivec3(4), glm::ivec3(0), glm::ivec3(3), glm::dvec3(0), glm::dvec3(1)),
                          enzoGridFile({glm::ivec3(4)})}));
    // The real tiny-cosmology parameter file and hierarchy with the small grid file.
    const fs::path dd = data / "enzo_tiny_cosmology/DD0018";
    const std::string params = readAll(dd / "DD0018");
    std::string realHierarchy = readAll(dd / "DD0018.hierarchy");
    for (size_t at; (at = realHierarchy.find("DD0018.cpu")) != std::string::npos;)
        realHierarchy.replace(at, 10, "DD0000.cpu");  // the file name fuzz_enzo writes
    if (!params.empty()) seed("enzo", "dd0018-text", fuzz::joinParts({params, realHierarchy, grids}));
}

// ---- RAMSES (the synthetic outputs of the reader tests, tests/ramses_synthetic.h) -------------
std::string ramsesSeed(const amrvk::test::ramses::Synthetic& s) {
    auto files = amrvk::test::ramses::outputFiles(s);
    std::vector<std::string> parts = {files["info_00001.txt"], files["hydro_file_descriptor.txt"],
                                      files["amr_00001.out00001"], files["hydro_00001.out00001"]};
    if (s.ncpu == 2) {
        parts.push_back(files["amr_00001.out00002"]);
        parts.push_back(files["hydro_00001.out00002"]);
    }
    return fuzz::joinParts(parts);
}

void ramsesSeeds() {
    using S = amrvk::test::ramses::Synthetic;
    seed("ramses", "synthetic-3d", ramsesSeed(S{}));
    seed("ramses", "synthetic-2d-float-old-names", ramsesSeed(S{.ndim = 2, .realBytes = 4, .descriptor = S::Old}));
    seed("ramses", "synthetic-3d-two-domains-bisection",
         ramsesSeed(S{.ncpu = 2, .bisection = true, .descriptor = S::None}));
    seed("ramses", "synthetic-2d-boundaries", ramsesSeed(S{.ndim = 2, .boundaries = true, .boxlen = 3}));
}

// ---- Chombo ---------------------------------------------------------------------------------
// fuzz_chombo (structured): a few byte patterns for its FuzzedDataProvider (libFuzzer finds the
// rest). fuzz_chombo_bytes: the smaller real file (403 KB), copied at run time.
void chomboSeeds(const fs::path& data) {
    for (int b : {1, 2, 3, 5})
        seed("chombo", "bytes-" + std::to_string(b), std::string(256, char(b)));
    const std::string plt = readAll(data / "chombo_mushy_layer_2d/plt000100.2d.hdf5");
    if (!plt.empty()) seed("chombo_bytes", "plt000100", plt);
}

// ---- raw ----------------------------------------------------------------------------------------
void rawSeeds() {
    // Header bytes: type|flags, dims-1 (x, y, z), threshold*16; then voxels (fuzz_raw.cpp).
    std::string ramp = {char(0), char(7), char(7), char(7), char(0)};
    for (int i = 0; i < 512; ++i) ramp += char(i / 64);
    seed("raw", "uint8-8cube", ramp);
    std::string f32 = {char(2 | 8), char(4), char(2), char(2), char(8)};
    for (int i = 0; i < 45; ++i) {
        float v = float(i % 5) * 0.5f;
        f32.append(reinterpret_cast<const char*>(&v), 4);
    }
    seed("raw", "float32-5x3x3-named", f32);
    std::string u16 = {char(1), char(15), char(0), char(3), char(0)};
    for (int i = 0; i < 64; ++i) u16 += char(i), u16 += char(0);
    seed("raw", "uint16-16x1x4", u16);
    std::string f64 = {char(3 | 4), char(1), char(1), char(1), char(1)};
    for (int i = 0; i < 8; ++i) {
        double v = i == 3 ? NAN : i;
        f64.append(reinterpret_cast<const char*>(&v), 8);
    }
    seed("raw", "float64-2cube-nan", f64);
}

// ---- transfer functions ----------------------------------------------------------------------
void tfSeeds(const fs::path& source) {
    std::string xf;
    auto put = [&](const auto& v) { xf.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
    put(scene::kXfMagic);
    for (float f : {100.0f, 0.0f, 10.0f, 0.0f, 100.0f}) put(f);
    put(int32_t(4));
    for (int i = 0; i < 4; ++i) {
        const float x = float(i);
        for (float f : {0.25f * x, 0.5f, 1.0f - 0.25f * x, 0.3f * x}) put(f);
    }
    seed("tf_xf", "magic-4", xf);
    std::string owl;
    for (int i = 0; i < 128; ++i) {
        float a = float(i) / 127.0f;
        owl.append(reinterpret_cast<const char*>(&a), 4);
    }
    seed("tf_xf", "owl-128", owl);
    for (const char* name : {"ramp", "spiky"})
        seed("tf_json", name, scene::paraViewPresetJson(scene::builtInChannels(name)));
    const std::string web = readAll(source / "assets/tf/cosmic-web.json");
    if (!web.empty()) seed("tf_json", "cosmic-web", web);
    seed("tf_json", "object-with-points",
         R"({"Name":"x","RGBPoints":[0,0,0,0,0.5,1,0,0,1,1,1,1],"Points":[0,0,0.5,0,1,1,0.5,0]})");
}

// ---- Sessions and viewer scripts ----------------------------------------------------------------
void sessionSeeds(const fs::path& source) {
    session::Session s;
    s.input = (source / "assets/samples/cloud.cells").string();
    s.field = "scalars";
    s.settings.lights.push_back({false, {1, -1, 2}, {5, 4.5, 3.8}});
    s.settings.lights.push_back({true, {0, 0, 9}, {2, 2, 2}});
    s.settings.background = glm::dvec3(0.1);
    s.structure.traversal = scene::TraversalKind::KdTree;
    s.tf = scene::builtInChannels("ramp");
    seed("session", "full", session::sessionJson(s));
    seed("session", "minimal",
         R"({"amrvk":"session","version":1,"input":"a.cells","camera":{"eye":[1,2,3],"target":[0,0,0],"up":[0,0,1]},)"
         R"("image":{"width":8,"height":8},"transferFunction":{"RGBPoints":[0,1,1,1,1,0,0,0],"Points":[0,0,0.5,0,1,1,0.5,0]}})");
    seed("script", "every-action",
         "# every action\n0 orbit 10 5\n0 pan 3 -2\n0 zoom 1\n1 tf-preset foggy\n1 tf-range 0.1 1.5\n"
         "2 density 2\n2 mode ss\n3 traversal grid-bvh\n3 sampler abr\n3 backend sw\n3 grid 8x4x2\n"
         "4 edit-shader path_trace.comp \"void main() {\" \"void main() { // \\\"x\\\"\"\n"
         "5 edit-shader ../lib/tf.glsl a b\n6 reload\n7 screenshot \"a b.pfm\"\n7 save-session s.json\n"
         "7 capture-window w.png\n8 quit\n");
    seed("script", "dense-then-abr", "0 sampler dense\n1 traversal abr\n");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::cerr << "usage: amrvk_fuzz_seeds OUT_DIR DATA_DIR SOURCE_DIR\n";
        return 2;
    }
    gOut = argv[1];
    const fs::path data = argv[2], source = argv[3];
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    exabrickSeeds(source);
    amrexSeeds(data);
    enzoSeeds(data);
    chomboSeeds(data);
    ramsesSeeds();
    rawSeeds();
    tfSeeds(source);
    sessionSeeds(source);
    std::cout << "amrvk_fuzz_seeds: wrote " << gCount << " seeds under " << gOut.string() << "\n";
    return 0;
}
