#include "accel/bricks_file.h"

#include <string>
#include <vector>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/stats.h"

namespace amrvk::accel {

BrickSet readBricksFile(const std::filesystem::path& path, const amr::Model& model) {
    Timer timer;
    BrickSet out;
    BinaryReader in(path);
    AMRVK_CHECK(in.size() > 0, path.string(), ": empty file (no bricks)");
    const uint64_t n = model.cells.size();
    std::vector<uint8_t> used(n, 0);
    uint64_t usedCount = 0;
    while (!in.atEnd()) {
        const uint64_t recordOffset = in.offset();
        int32_t header[7];
        in.read(header, sizeof header);
        Brick br{{header[3], header[4], header[5]}, {header[0], header[1], header[2]}, header[6], 0};
        AMRVK_CHECK(br.size.x > 0 && br.size.y > 0 && br.size.z > 0 && br.level >= 0 && br.level <= amr::kMaxLevel,
                    path.string(), ": brick at byte ", recordOffset, " has size ", br.size.x, "x", br.size.y, "x",
                    br.size.z, " level ", br.level, " (invalid)");
        const std::string where = strCat(path.string(), ": brick at byte ", recordOffset);
        const uint64_t cells = checkedProduct({uint64_t(br.size.x), uint64_t(br.size.y), uint64_t(br.size.z)}, where);
        AMRVK_CHECK(checkedSum(out.cellIds.size(), cells, where) < BrickSet::kEmptySlot, where, ": ",
                    out.cellIds.size() + cells, " brick cells in all, the limit is ", BrickSet::kEmptySlot - 1);
        AMRVK_CHECK(glm::all(glm::lessThanEqual(glm::i64vec3(br.lower) + glm::i64vec3(br.size) * br.cellWidth(),
                                                glm::i64vec3(INT32_MAX))),
                    where, ": brick reaches past the 32-bit voxel range");
        br.begin = static_cast<uint32_t>(out.cellIds.size());
        std::vector<int32_t> ids;
        in.readArray(ids, br.cellCount());
        const int64_t w = br.cellWidth();
        for (size_t k = 0; k < ids.size(); ++k) {
            int32_t id = ids[k];
            if (id == -1) {
                out.cellIds.push_back(BrickSet::kEmptySlot);
                continue;
            }
            AMRVK_CHECK(id >= 0 && uint64_t(id) < n, path.string(), ": brick at byte ", recordOffset, " names cell ",
                        id, " but the model has ", n, " cells");
            AMRVK_CHECK(!used[size_t(id)], path.string(), ": cell ", id, " is in more than one brick (second at byte ",
                        recordOffset, ")");
            used[size_t(id)] = 1;
            ++usedCount;
            glm::i64vec3 local(int64_t(k % size_t(br.size.x)), int64_t(k / size_t(br.size.x) % size_t(br.size.y)),
                               int64_t(k / (size_t(br.size.x) * size_t(br.size.y))));
            glm::i64vec3 expect = glm::i64vec3(br.lower) + local * w;
            const amr::Cell& c = model.cells[size_t(id)];
            AMRVK_CHECK(glm::i64vec3(c.lower) == expect && c.level == br.level, path.string(), ": brick at byte ",
                        recordOffset, " slot ", k, " names cell ", id, " which is not at that position and level");
            out.cellIds.push_back(static_cast<uint32_t>(id));
        }
        out.bricks.push_back(br);
    }
    AMRVK_CHECK(usedCount == n, path.string(), ": ", n - usedCount, " cells of the model are in no brick");
    out.buildSeconds = timer.seconds();
    return out;
}

void writeBricksFile(const std::filesystem::path& path, const BrickSet& bricks) {
    AtomicFileWriter out(path);
    std::vector<int32_t> ids;
    for (const Brick& b : bricks.bricks) {
        int32_t header[7] = {b.size.x, b.size.y, b.size.z, b.lower.x, b.lower.y, b.lower.z, b.level};
        out.write(header, sizeof header);
        ids.clear();
        for (uint64_t k = 0; k < b.cellCount(); ++k) {
            uint32_t id = bricks.cellId(b.begin + k);
            ids.push_back(id == BrickSet::kEmptySlot ? -1 : static_cast<int32_t>(id));
        }
        out.write(ids.data(), ids.size() * sizeof(int32_t));
    }
    out.commit();
}

}  // namespace amrvk::accel
