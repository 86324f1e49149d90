#pragma once
// The .bricks file format of the ExaBrick builders: bricks made elsewhere, read and checked
// against the model they name cells of, and a BrickSet written for the ExaBrick tools.
#include <filesystem>

#include "accel/bricks.h"
#include "amr/model.h"

namespace amrvk::accel {

// Reads a .bricks file of the ExaBrick builders (records: int3 size, int3 lower, int level,
// int cellId[size]) and checks it against the model: every cell id valid and used once, ids -1
// are empty slots, every brick slot at the position of the cell it names.
BrickSet readBricksFile(const std::filesystem::path& path, const amr::Model& model);

// Writes bricks in the same .bricks format (empty slots as -1), atomically.
void writeBricksFile(const std::filesystem::path& path, const BrickSet& bricks);

}  // namespace amrvk::accel
