#pragma once
// Subcommands of the amrvk CLI; each takes the arguments after its name and returns the exit code.
#include <string>
#include <vector>

namespace amrvk::cli {

int runInfo(const std::vector<std::string>& args);
int runGen(const std::vector<std::string>& args);
int runConvert(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
int runDevices(const std::vector<std::string>& args);
int runBench(const std::vector<std::string>& args);
int runView(const std::vector<std::string>& args);
int runShaders(const std::vector<std::string>& args);

}  // namespace amrvk::cli
