#include <cstdio>

#include "amr/readers.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"

namespace amrvk::cli {

int runInfo(const std::vector<std::string>& argv) {
    std::vector<OptionSpec> specs = {
        {"field", 1, "NAME", "field to analyse (default: the first one)"},
        {"format", 1, "FMT", "auto|exabrick|amrex|enzo|chombo|raw (default auto)"},
        {"json", 0, "", "print one JSON object instead of text"},
    };
    Args args("info", argv, specs, 1, 1);
    amr::ReadOptions ro;
    ro.format = args.get("format", "auto");
    if (args.has("field")) ro.fields = {args.get("field")};
    amr::Model model = amr::readModel(args.positional()[0], ro);
    amr::ModelSummary s = amr::summarize(model);
    std::printf("%s: %llu leaf cells\n", model.source.c_str(),
                static_cast<unsigned long long>(model.cellCount()));
    (void)s;
    return 0;
}

int runConvert(const std::vector<std::string>& argv) {
    std::vector<OptionSpec> specs = {
        {"output", 1, "BASE", "output base name: writes BASE.cells and BASE.<field>.scalars"},
        {"field", 1, "NAME", "convert only this field (repeatable)", true},
        {"format", 1, "FMT", "auto|exabrick|amrex|enzo|chombo|raw (default auto)"},
    };
    Args args("convert", argv, specs, 1, 1);
    amr::ReadOptions ro;
    ro.format = args.get("format", "auto");
    ro.fields = args.values("field");
    amr::Model model = amr::readModel(args.positional()[0], ro);
    AMRVK_CHECK(args.has("output"), "amrvk convert: -o BASE is required");
    amr::writeExaBrick(model, args.get("output"));
    std::printf("wrote %s.cells (%llu cells)\n", args.get("output").c_str(),
                static_cast<unsigned long long>(model.cellCount()));
    return 0;
}

}  // namespace amrvk::cli
