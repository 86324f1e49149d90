#pragma once
// Input options shared by every subcommand that reads AMR data.
#include <vector>

#include "amr/readers.h"
#include "cli/args.h"

namespace amrvk::cli {

// --format, --field (repeatable where `multiField`), --nan, --dims, --type, --threshold.
std::vector<OptionSpec> readOptionSpecs(bool multiField);
amr::ReadOptions readOptionsFrom(const Args& args);

}  // namespace amrvk::cli
