// amrvk: unbiased volumetric path tracing of AMR data on any Vulkan device.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/mpi_launch.h"
#include "gpu/context.h"

namespace {
const char* kUsage =
    "amrvk - volume path tracing of adaptive-mesh-refinement data\n"
    "\n"
    "usage: amrvk <command> [options]   (amrvk <command> --help for its options)\n"
    "\n"
    "commands:\n"
    "  amrvk info <input> [--field NAME] [--json]   describe a data set and build its bricks/ABRs\n"
    "  amrvk gen <kind> --cells N --seed S -o BASE  write synthetic AMR (.cells/.scalars)\n"
    "  amrvk convert <input> -o BASE               convert any input to ExaBrick .cells/.scalars\n"
    "  amrvk render <input> [-o out.png] [options]  path-trace the data on a Vulkan device\n"
    "  amrvk view <input> [options]                the interactive viewer (or --headless)\n"
    "  amrvk bench <input>... -o DIR [options]     benchmark protocol: speed against error, "
    "reports\n"
    "  amrvk devices [--json]                      list Vulkan devices and why any is unusable\n"
    "  amrvk shaders --export DIR                  write the built-in shader sources (for --shader-dir)\n"
    "\n"
    "inputs: ExaBrick .cells (+ .scalars), AMReX plotfile directory, Enzo parameter file,\n"
    "        Chombo .hdf5, Carpet .h5, RAMSES output_NNNNN directory (or its info_NNNNN.txt), raw\n"
    "        uniform volume (.raw); the format is detected (--format to override)\n";

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    amrvk::removeTemporariesOnSignal();  // Ctrl-C, a closed terminal (HUP), kill: no temporaries left
    amrvk::gpu::reportGpuCrashes();      // a --shader-dir shader writing outside its buffers: one line
    try {
        using namespace amrvk::cli;
        const std::pair<const char*, int (*)(const std::vector<std::string>&)> commands[] = {
            {"info", runInfo},       {"gen", runGen},     {"convert", runConvert}, {"render", runRender},
            {"view", runView},       {"devices", runDevices}, {"bench", runBench}, {"shaders", runShaders}};
        // Under mpirun only render, bench and view split their work; any other command would run N times over.
        const int ranks = amrvk::launchedJobSize();
        if (ranks > 1 && command != "render" && command != "bench" && command != "view") {
            if (amrvk::launchedRank() == 0)  // one line for the job
                std::fprintf(stderr,
                             "amrvk %s: error: started by an MPI launcher with %d processes; only 'amrvk render', "
                             "'amrvk bench' and 'amrvk view' run on several ranks (docs/mpi.md)\n",
                             command.c_str(), ranks);
            return 1;
        }
        for (const auto& [name, run] : commands)
            if (command == name) return run(args);
        std::fprintf(stderr, "amrvk: unknown command '%s' (see amrvk --help)\n", command.c_str());
        return 2;
    } catch (...) {
        std::fprintf(stderr, "amrvk %s: error: %s\n", command.c_str(),
                     amrvk::cli::errorText(std::current_exception(), command).c_str());
        return 1;
    }
}
