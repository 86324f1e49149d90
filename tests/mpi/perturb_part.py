#!/usr/bin/env python3
"""Writes a copy of an ExaBrick data set with one rank's part perturbed (the power check of the
data-parallel z-test): IN.cells (+ IN.scalars) -> OUT.cells + OUT.scalars, every value of the cells
whose lower corner lies in the box rank RANK owned in RUN.json (`amrvk render --json` under
--distribute data) multiplied by FACTOR. Prints the cells changed and the level-0 cells that touch
an interior face of the partition (the faces cut through the finest level when that is > 0)."""
import json
import sys

import numpy as np

cells_in, run_json, rank, factor, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
cells = np.fromfile(cells_in, dtype="<i4").reshape(-1, 4)
values = np.fromfile(cells_in[: -len(".cells")] + ".scalars", dtype="<f4")
assert len(values) == len(cells)
boxes = [np.array(r["ownedBox"]) for r in json.load(open(run_json))["mpi"]["perRank"]]
lo, hi = boxes[rank]
mine = np.all((cells[:, :3] >= lo) & (cells[:, :3] < hi), axis=1)
scaled = values.copy()
scaled[mine] *= factor
cells.astype("<i4").tofile(out + ".cells")
scaled.astype("<f4").tofile(out + ".scalars")
# Interior faces: a box face not on the data's bounds.
bounds_lo, bounds_hi = cells[:, :3].min(axis=0), (cells[:, :3] + (1 << cells[:, 3])[:, None]).max(axis=0)
fine = cells[cells[:, 3] == 0][:, :3]
touching = 0
for b_lo, b_hi in boxes:
    for axis in range(3):
        for plane in (b_lo[axis], b_hi[axis]):
            if bounds_lo[axis] < plane < bounds_hi[axis]:
                inside = np.all((fine >= b_lo) & (fine < b_hi), axis=1)
                touching += int(np.sum(inside & ((fine[:, axis] == plane) | (fine[:, axis] + 1 == plane))))
print(json.dumps({"changed": int(mine.sum()), "fineCellsAtInteriorFaces": touching}))
