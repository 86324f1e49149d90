#include "cli/read_options.h"

#include "core/error.h"

namespace amrvk::cli {

std::vector<OptionSpec> readOptionSpecs(bool multiField) {
    return {
        {"format", 1, "FMT", "auto|exabrick|amrex|enzo|chombo|raw (default: detected)"},
        {"field", 1, "NAME",
         multiField ? "field to load (repeatable; default: all)" : "field to use (default: the first)",
         multiField},
        {"nan", 1, "POLICY", "reject|drop: NaN/Inf values are an error, or their cells are removed (default reject)"},
        {"dims", 3, "NX NY NZ", "raw volumes: voxels per axis (else from a name like v_64x64x64_uint8.raw)"},
        {"type", 1, "TYPE", "raw volumes: uint8|uint16|float32|float64"},
        {"threshold", 1, "T", "raw volumes: merge a block into one cell when max - min <= T (default 0)"},
    };
}

amr::ReadOptions readOptionsFrom(const Args& args) {
    amr::ReadOptions ro;
    ro.format = args.get("format", "auto");
    ro.fields = args.values("field");
    ro.nanPolicy = amr::parseNanPolicy(args.get("nan", "reject"));
    if (args.has("dims")) {
        auto d = args.values("dims");
        for (int a = 0; a < 3; ++a) {
            int64_t v = parseInt("--dims", d[size_t(a)]);
            AMRVK_CHECK(v >= 1 && v <= (1 << 20), "--dims: ", v, " is outside [1, 2^20]");
            ro.rawDims[a] = int(v);
        }
    }
    ro.rawType = args.get("type", "");
    ro.rawThreshold = args.getDouble("threshold", 0.0);
    AMRVK_CHECK(ro.rawThreshold >= 0, "--threshold must be >= 0");
    return ro;
}

}  // namespace amrvk::cli
