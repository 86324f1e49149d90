// Chombo HDF5 plotfiles (src/amr/chombo_reader.cpp), structured: the fuzz bytes choose the
// content (dimension, components, levels, dx, ref_ratio, prob_domain, outputGhost, boxes,
// offsets, data) of a well-formed HDF5 file written through the HDF5 API (hdf5_writer.h), which
// readModel then reads. The HDF5 parser itself is fuzzed by fuzz_chombo_bytes.
#include <algorithm>
#include <cstdint>
#include <string>

#include "amr/readers.h"
#include "fuzz_common.h"
#include "hdf5_writer.h"

using namespace amrvk;

namespace {

void writeChombo(const std::filesystem::path& path, FuzzedDataProvider& p) {
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const int dim = fuzz::smallOrAny(p, 2, 3);
    const int ncomp = fuzz::smallOrAny(p, 1, 3);
    const int levels = fuzz::smallOrAny(p, 1, 3);
    if (p.ConsumeBool()) {
        hid_t g = H5Gcreate2(f, "Chombo_global", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        fuzz::intAttribute(g, "SpaceDim", dim);
        H5Gclose(g);
    }
    fuzz::intAttribute(f, "num_components", ncomp);
    for (int c = 0; c < std::min(ncomp, 4); ++c)
        fuzz::stringAttribute(f, ("component_" + std::to_string(c)).c_str(),
                              p.ConsumeBool() ? "c" + std::to_string(c) : p.ConsumeRandomLengthString(8));
    fuzz::intAttribute(f, "num_levels", levels);
    if (p.ConsumeBool()) fuzz::doubleAttribute(f, "time", p.ConsumeFloatingPoint<double>());

    const int d = std::clamp(dim, 1, 3);
    const char* axes[] = {"i", "j", "k"};
    std::vector<std::string> boxMembers, ghostMembers;
    for (const char* side : {"lo_", "hi_"})
        for (int a = 0; a < d; ++a) boxMembers.push_back(std::string(side) + axes[a]);
    for (int a = 0; a < d; ++a) ghostMembers.push_back(std::string("intvect") + axes[a]);

    for (int l = 0; l < std::min(levels, 4); ++l) {
        hid_t g = H5Gcreate2(f, ("level_" + std::to_string(l)).c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        fuzz::doubleAttribute(g, "dx", p.ConsumeBool() ? 1.0 / (4 << (2 * l)) : p.ConsumeFloatingPoint<double>());
        fuzz::intAttribute(g, "ref_ratio", p.ConsumeBool() ? 2 : fuzz::smallOrAny(p, 0, 8));
        if (p.ConsumeBool()) {
            std::vector<int> dom;
            for (int i = 0; i < 2 * d; ++i) dom.push_back(fuzz::smallOrAny(p, -4, 64));
            fuzz::intCompound(g, "prob_domain", boxMembers, dom, -1);
        }
        int ghost = 0;
        if (p.ConsumeBool()) {
            hid_t da = H5Gcreate2(g, "data_attributes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
            if (p.ConsumeBool()) fuzz::intAttribute(da, "comps", p.ConsumeBool() ? ncomp : fuzz::smallOrAny(p, 0, 4));
            if (p.ConsumeBool()) {
                ghost = fuzz::smallOrAny(p, 0, 2);
                std::vector<int> gv(size_t(d), ghost);
                if (p.ConsumeBool()) gv[0] = fuzz::smallOrAny(p, -1, 3);
                fuzz::intCompound(da, "outputGhost", ghostMembers, gv, -1);
            }
            H5Gclose(da);
        }
        // Boxes, their offsets (prefix sums of cells x components unless the bytes say otherwise)
        // and the data, at most 64 Ki values.
        const int nboxes = p.ConsumeIntegralInRange<int>(0, 4);
        std::vector<int> boxes;
        std::vector<int64_t> offsets{0};
        for (int b = 0; b < nboxes; ++b) {
            int64_t cells = 1;
            std::vector<int> lo, hi;
            for (int a = 0; a < d; ++a) {
                lo.push_back(fuzz::smallOrAny(p, 0, 16));
                hi.push_back(p.ConsumeBool() ? int(std::min<int64_t>(int64_t(lo.back()) + p.ConsumeIntegralInRange<int>(0, 7), INT32_MAX))
                                             : fuzz::smallOrAny(p, 0, 16));
                cells = std::min<int64_t>(cells * std::clamp<int64_t>(int64_t(hi.back()) - lo.back() + 1 + 2 * int64_t(ghost), 0, 1 << 20), 1 << 20);
            }
            boxes.insert(boxes.end(), lo.begin(), lo.end());
            boxes.insert(boxes.end(), hi.begin(), hi.end());
            int64_t next = 0;
            if (__builtin_add_overflow(offsets.empty() ? 0 : offsets.back(),
                                       std::min<int64_t>(cells * std::max(ncomp, 0), 1 << 16), &next))
                next = INT64_MAX;
            offsets.push_back(p.ConsumeIntegralInRange<int>(0, 7) == 0 ? p.ConsumeIntegral<int64_t>() : next);
        }
        if (p.ConsumeIntegralInRange<int>(0, 7) == 0) offsets.pop_back();
        fuzz::intCompound(g, "boxes", boxMembers, boxes, nboxes);
        fuzz::int64Dataset(g, "data:offsets=0", offsets);
        const int64_t last = offsets.empty() ? 0 : std::clamp<int64_t>(offsets.back(), 0, 1 << 16);
        const hsize_t n = hsize_t(p.ConsumeBool() ? last : p.ConsumeIntegralInRange<int64_t>(0, last + 16));
        std::vector<double> values(n);
        for (size_t i = 0; i < values.size(); ++i) values[i] = double(i % 13) * 0.5;
        if (p.ConsumeBool() && !values.empty()) values[p.ConsumeIntegralInRange<size_t>(0, n - 1)] = p.ConsumeFloatingPoint<double>();
        fuzz::doubleDataset(g, "data:datatype=0", {n}, values, p.ConsumeBool() ? H5T_IEEE_F64LE : H5T_IEEE_F32LE);
        H5Gclose(g);
    }
    H5Fclose(f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool quiet = (H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr), true);
    (void)quiet;
    FuzzedDataProvider p(data, size);
    const fuzz::Scratch scratch;
    const auto path = scratch.path() / "plt.hdf5";
    writeChombo(path, p);
    fuzz::expectOnlyAmrvkErrors("chombo", [&] {
        amr::ReadOptions options;
        amr::readModel(path, options);
    });
    return 0;
}
