"""The yt bridge: any data set yt reads (Enzo, AMReX/Castro/MAESTRO, Chombo, FLASH, Athena++, GAMER,
RAMSES, ART, ...) and any field it knows, derived ones included, as an amrvk Volume.

Leaf cells become amrvk cells with their level and integer position:
  - block-structured data sets (yt's grid index): per grid, the cells no finer grid covers, at
    the grid's left edge / cell size + (i, j, k) (computed from the edges: see _grid_cells);
  - octree data sets (RAMSES, ART) and any data object (``ds.region(...)``, ``ds.sphere(...)``,
    ``ds.all_data()``): the leaf cells yt selects, through ``icoords`` and ``ires``.
amrvk counts levels from the finest (0) and positions in finest-level units, so a cell w times as
wide as the finest (w from yt's cell sizes, dds or dx: a power of two, whatever each level's
refinement ratio) lies at ``index * w`` with level log2(w). Positions are in code_length: world =
domain_left_edge + voxel * (the finest cell size), the transform amrvk's own readers give. 2-D data
sets become one-cell-thick slabs as the readers make them: a cell w wide is w deep too, so a
volume weight is w^3 (yt's 2-D cell_volume is w^2 times the domain depth).
Values are the field's bare numbers (``.d``); their unit is kept as ``Volume.units``.

Copies: yt produces each grid's (or the selection's) arrays; the leaf cells are gathered into one
array per quantity (numpy, one copy) and copied once more into amrvk's cell list, which the volume
then owns (the brick build reorders it in place, no further copy).
"""

import numpy as np
from .one_line_errors import _shown  # a value in a message: one short line


def _widths(cell_size, finest, what):
    """Cell widths in finest-level cells from cell sizes (yt's dds / dx): whole powers of two."""
    ratio = np.asarray(cell_size, dtype=np.float64) / finest
    width = np.rint(ratio).astype(np.int64)
    if np.any(np.abs(ratio - width) > 1e-6 * ratio) or np.any(width < 1) or np.any(width & (width - 1)):
        bad = ratio[np.argmax((np.abs(ratio - width) > 1e-6 * ratio) | (width < 1) | ((width & (width - 1)) != 0))]
        raise ValueError(
            f"{what}: a cell {bad:g} times the finest one: amrvk needs refinement by powers of two "
            f"(2, 4, ...) between levels"
        )
    return width


def _values(array, log, log_floor, field_name):
    """Bare float values of a yt array, log10 of them when asked (yt's default for densities)."""
    units = str(getattr(array, "units", ""))
    values = np.asarray(getattr(array, "d", array), dtype=np.float64)
    if log:
        if log_floor is not None:
            if not log_floor > 0:
                raise ValueError(f"log_floor: {log_floor} must be > 0")
            values = np.maximum(values, log_floor)
        bad = int(np.count_nonzero(~(values > 0)))
        if bad:
            raise ValueError(
                f"{field_name}: {bad} value(s) <= 0 have no log10 (give log_floor=... to clamp them, "
                f"or log=False)"
            )
        values = np.log10(values)
        units = f"log10({units})" if units and units != "dimensionless" else "log10"
    return values, units


def _grid_cells(ds, field, log, log_floor):
    """Leaf cells of a grid-indexed data set, grid by grid: the cells no finer grid covers.

    Positions and coverage come from the grids' edges and cell sizes, not from yt's
    get_global_startindex and child_mask: yt 4.1.4 computes both with one refinement factor for
    every level, which is wrong where ratios differ between levels (Chombo plt025000, ratios 4
    then 2: 744 covered cells kept twice, grids placed outside the domain).
    """
    grids = [g for g in ds.index.grids]
    left0 = np.asarray(ds.domain_left_edge.to("code_length").d, dtype=np.float64)
    dds = np.array([g.dds.to("code_length").d for g in grids], dtype=np.float64)
    lo = np.array([g.LeftEdge.to("code_length").d for g in grids], dtype=np.float64)
    hi = np.array([g.RightEdge.to("code_length").d for g in grids], dtype=np.float64)
    finest = dds[:, 0].min()
    widths = _widths(dds[:, 0], finest, str(ds))
    lowers, levels, values, units = [], [], [], ""
    for n, g in enumerate(grids):
        dims = np.asarray(g.ActiveDimensions, dtype=np.int64)
        mask = np.ones(tuple(dims), dtype=bool)
        # Finer grids overlapping this one cover those of its cells they contain.
        finer = (dds[:, 0] < dds[n, 0]) & np.all(lo < hi[n], axis=1) & np.all(hi > lo[n], axis=1)
        for m in np.nonzero(finer)[0]:
            a = np.clip(np.rint((lo[m] - lo[n]) / dds[n]).astype(np.int64), 0, dims)
            b = np.clip(np.rint((hi[m] - lo[n]) / dds[n]).astype(np.int64), 0, dims)
            mask[a[0]:b[0], a[1]:b[1], a[2]:b[2]] = False
        if not mask.any():
            continue
        i, j, k = np.nonzero(mask)
        start = np.rint((lo[n] - left0) / dds[n]).astype(np.int64)
        width = int(widths[n])
        lowers.append((np.stack([i, j, k], axis=1).astype(np.int64) + start) * width)
        levels.append(np.full(i.size, width, dtype=np.int64))
        v, units = _values(g[field][mask], log, log_floor, str(field))
        values.append(v)
    if not lowers:
        raise ValueError(f"{ds}: no leaf cells")
    return np.concatenate(lowers), np.concatenate(levels), np.concatenate(values), units, dds[np.argmin(dds[:, 0])]


def _selected_cells(obj, field, log, log_floor):
    """Leaf cells of a data object: yt selects unrefined cells, with their index at their own level."""
    icoords = np.asarray(obj.icoords, dtype=np.int64)
    if icoords.shape[0] == 0:
        raise ValueError(f"{obj}: the selection holds no cells (an empty volume)")
    dx = np.stack([obj["index", a].to("code_length").d for a in ("dx", "dy", "dz")], axis=1)
    finest = dx[:, 0].min()
    width = _widths(dx[:, 0], finest, str(obj.ds))
    values, units = _values(obj[field], log, log_floor, str(field))
    return icoords * width[:, None], width, values, units, dx[np.argmin(dx[:, 0])]


def _mesh_field(ds, field):
    """The field as yt names it, checked to be one yt knows with values on cells (not particles)."""
    if not isinstance(field, (str, tuple)) or (isinstance(field, tuple) and (
            len(field) != 2 or not all(isinstance(p, str) for p in field))):
        raise TypeError(f"field: expected a yt field name such as ('gas', 'density') or 'density', got {_shown(field)}")
    try:
        info = ds._get_field_info(field)
    except Exception as e:  # yt's YTFieldNotFound and its kin: one line naming the keyword
        raise ValueError(f"field: {_shown(field)} is not a field of {ds} (see ds.derived_field_list)") from None
    if getattr(info, "sampling_type", "cell") == "particle":  # "cell" and "local" (derived per cell) are fine
        raise ValueError(
            f"field: {info.name!r} is a particle field; amrvk renders fields with a value per cell, "
            f"such as ('gas', 'density') (deposit particles onto the mesh first, e.g. ('deposit', 'all_density'))"
        )
    return info.name


def _yt_takes_log(ds, obj, field):
    """yt's own choice for a field (its ``take_log``), where every value is positive (yt would floor
    the others; amrvk then stays linear, as ``--scale auto`` does)."""
    try:
        finfo = ds._get_field_info(field)
        take_log = bool(getattr(finfo, "take_log", False))
    except Exception:  # a field yt cannot describe: linear
        return False
    return take_log and float(obj.min(field)) > 0


def from_yt(data, field, *, log=None, log_floor=None, nan="reject"):
    """An amrvk Volume of `field` from a yt data set or data object.

    data: ``yt.load(...)`` (grid index: leaf cells grid by grid; octree: yt's leaf selection), or a
      data object (``ds.region(...)``, ``ds.all_data()``, ...): its selected leaf cells, a cut-out
      whose cells keep their size and place (the medium is empty outside it).
    field: any field yt knows, e.g. ``("gas", "density")``, ``("gas", "velocity_magnitude")``,
      ``("enzo", "Density")``.
    log: take log10 of the values; values <= 0 are an error unless ``log_floor`` clamps them first.
      None (the default): as yt takes the field (its ``take_log``: densities, temperatures, ...)
      where every value is positive, else linear.
    nan: ``"reject"`` (an error naming the cell) or ``"drop"`` (those cells are removed).

    Refinement must be by powers of two (2, 4, ...; ratios may differ between levels); 2-D data
    sets become slabs whose cells are as deep as they are wide, as amrvk's readers make them.
    """
    from . import _amrvk

    try:
        import yt  # noqa: F401  (the error below says what is missing)
    except ImportError as e:
        raise ImportError("amrvk.Volume.from_yt needs yt (Debian: python3-yt)") from e
    if hasattr(data, "piter"):
        raise TypeError("data: a yt DatasetSeries is a series: amrvk.render_series(ts, out, field=...) renders one "
                        "frame per data set; from_yt takes one of them (ts[0])")
    is_dataset = hasattr(data, "index") and hasattr(data, "domain_dimensions")
    ds = data if is_dataset else getattr(data, "ds", None)
    if ds is None:
        raise TypeError(f"from_yt: expected a yt data set or data object, got {type(data).__name__}")
    _mesh_field(ds, field)
    if log is not None and not isinstance(log, bool):
        raise TypeError(f"log: expected True, False or None, got {_shown(log)}")
    if log is None:
        log = _yt_takes_log(ds, data if not is_dataset else ds.all_data(), field)
    if is_dataset and hasattr(ds.index, "grids"):
        lower, width, values, units, spacing = _grid_cells(ds, field, log, log_floor)
    else:
        lower, width, values, units, spacing = _selected_cells(data if not is_dataset else ds.all_data(), field, log, log_floor)
    level = np.log2(width).round().astype(np.int64)
    left = np.asarray(ds.domain_left_edge.to("code_length").d, dtype=np.float64)
    spacing = np.where(spacing > 0, spacing, 1.0)
    # 2-D (and 1-D) data: the missing axes get the finest cell size, as amrvk's readers make slabs.
    spacing[int(ds.dimensionality):] = spacing[0]
    name = field if isinstance(field, str) else "_".join(str(p) for p in field)
    volume = _amrvk.Volume.from_arrays(
        lower,
        level,
        values,
        field=name.replace("/", "_"),
        origin=left.tolist(),
        spacing=spacing.tolist(),
        nan=nan,
        units=units,
        source=str(ds),
    )
    volume._made_by = "yt"  # save_session names yt, not arrays, in its refusal
    return volume
