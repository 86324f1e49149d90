"""The yt bridge against yt itself and against amrvk's own readers: leaf cells per level and the
volume-weighted mean on the real data sets and yt's synthetic one, derived fields, log10, cut-outs,
refinement that is not a power of two, and the picture: from_yt(Enzo) renders what the native
reader's volume renders (per-tile and whole-image z-tests; the whole-image one is shown to catch a
5% density change)."""
import numpy as np
import pytest

from conftest import DATA, ENZO, global_z, need, tile_z_test


def yt_counts(ds):
    """Leaf cells per yt level as yt selects them."""
    return np.bincount(np.asarray(ds.all_data().ires))


def amrvk_counts(volume):
    """amrvk's cells per level (0 = finest) in yt's order (0 = coarsest)."""
    per_level = [c for c in volume.summary()["cells_per_level"]]
    while per_level and per_level[-1] == 0:
        per_level.pop()
    return [c for c in reversed(per_level) if c > 0]


def yt_mean(ds, field):
    return float(ds.all_data().quantities.weighted_average_quantity(field, ("index", "cell_volume")))


@pytest.mark.parametrize(
    "relative, field, native",
    [
        ("enzo_tiny_cosmology/DD0018/DD0018", ("enzo", "Density"), "Density"),
        ("amrex_pelelm_3d/example_plt_3d", ("boxlib", "temp"), "temp"),
        ("ramses_galaxy_3d/output_00010/info_00010.txt", ("ramses", "Density"), "density"),
    ],
)
def test_leaf_cells_and_mean_agree_with_yt(amrvk, yt, relative, field, native):
    path = need(DATA / relative)
    ds = yt.load(str(path))
    v = amrvk.Volume.from_yt(ds, field, log=False)
    assert amrvk_counts(v) == [int(c) for c in yt_counts(ds) if c > 0]
    assert v.summary()["volume_weighted_mean"] == pytest.approx(yt_mean(ds, field), rel=1e-7)
    assert v.units == str(ds.all_data()[field].units)
    if native:
        n = amrvk.Volume(str(path), field=native, scale="linear").summary()
        s = v.summary()
        for key in ("cells", "cells_per_level", "volume_weighted_mean", "value_range", "world_lo", "world_hi"):
            assert s[key] == n[key], key


def test_chombo_leaves_agree_with_the_native_reader_where_yt_double_counts(amrvk, yt):
    # Ratios 2, 2: yt, the native reader and the bridge agree.
    path = need(DATA / "chombo_mushy_layer_2d/plt000100.2d.hdf5")
    ds = yt.load(str(path))
    v = amrvk.Volume.from_yt(ds, ("chombo", "Porosity"), log=False)
    assert amrvk_counts(v) == [int(c) for c in yt_counts(ds) if c > 0] == [64, 224, 2176]
    n = amrvk.Volume(str(path), field="Porosity", scale="linear").summary()
    assert v.summary()["cells_per_level"] == n["cells_per_level"]
    # 2-D cells are as deep as they are wide (slabs, as the readers make them): weight w^3.
    dx = ds.all_data()["index", "dx"].d
    values = ds.all_data()[("chombo", "Porosity")].d
    assert v.summary()["volume_weighted_mean"] == pytest.approx((values * dx**3).sum() / (dx**3).sum(), rel=1e-7)
    # Ratios 4 then 2: yt 4.1.4's selection keeps 744 covered level-1 cells (10,984 leaves whose
    # areas exceed the domain's); the bridge computes coverage from the grid edges and finds the
    # native reader's 10,240, which tile the unit square exactly.
    path = need(DATA / "chombo_mushy_layer_2d/plt025000.2d.hdf5")
    ds = yt.load(str(path))
    assert int(yt_counts(ds).sum()) == 10984
    v = amrvk.Volume.from_yt(ds, ("chombo", "Porosity"), log=False)
    s, n = v.summary(), amrvk.Volume(str(path), field="Porosity", scale="linear").summary()
    assert s["cells"] == n["cells"] == 10240 and s["cells_per_level"] == n["cells_per_level"]
    widths = 2 ** np.nonzero(s["cells_per_level"])[0]
    area = sum(int(c) * int(w) ** 2 for c, w in zip(np.array(s["cells_per_level"])[np.nonzero(s["cells_per_level"])], widths))
    assert area == 256 * 256
    assert s["volume_weighted_mean"] == n["volume_weighted_mean"]
    assert s["world_hi"] == pytest.approx(n["world_hi"])


def test_yts_synthetic_data_set(amrvk, yt):
    import yt.testing

    ds = yt.testing.fake_amr_ds(fields=[("gas", "density")], units=["g/cm**3"])
    v = amrvk.Volume.from_yt(ds, ("gas", "density"), log=False)
    assert amrvk_counts(v) == [int(c) for c in yt_counts(ds) if c > 0]
    assert v.summary()["volume_weighted_mean"] == pytest.approx(yt_mean(ds, ("gas", "density")), rel=1e-7)
    assert v.units == "g/cm**3"


def test_native_units_name_what_yt_converts_to(amrvk, yt):
    """Volume.units of the native reader (code values, "code units (1 = X g/cm^3)") against
    from_yt's of yt's cgs field: X times the native values is yt's g/cm^3, cell for cell on the
    whole (the volume-weighted means); X uses Enzo's critical density, yt's differs by 2e-4."""
    ds = yt.load(str(need(ENZO)))
    native = amrvk.Volume(str(ENZO), field="Density", scale="linear")
    cgs = amrvk.Volume.from_yt(ds, ("gas", "density"), log=False)
    assert cgs.units == "g/cm**3"
    prefix, suffix = "code units (1 = ", " g/cm^3)"
    assert native.units.startswith(prefix) and native.units.endswith(suffix), native.units
    scale = float(native.units[len(prefix) : -len(suffix)])
    assert scale * native.summary()["volume_weighted_mean"] == pytest.approx(
        cgs.summary()["volume_weighted_mean"], rel=3e-4, abs=0
    )
    assert "[code units (1 = " in repr(native)


def test_derived_fields_log_and_cut_outs(amrvk, yt):
    ds = yt.load(str(need(ENZO)))
    ad = ds.all_data()
    speed = amrvk.Volume.from_yt(ds, ("gas", "velocity_magnitude"), log=False)
    ref = ad[("gas", "velocity_magnitude")].d
    assert speed.value_range == pytest.approx((ref.min(), ref.max()), rel=1e-6)
    assert speed.units == "cm/s"
    dens = amrvk.Volume.from_yt(ds, ("gas", "density"), log=True)
    ref = np.log10(ad[("gas", "density")].d)
    assert dens.value_range == pytest.approx((ref.min(), ref.max()), rel=1e-6)
    assert dens.units == "log10(g/cm**3)"
    with pytest.raises(ValueError, match=r"value\(s\) <= 0 have no log10"):
        amrvk.Volume.from_yt(ds, ("gas", "velocity_x"), log=True)
    floored = amrvk.Volume.from_yt(ds, ("gas", "velocity_x"), log=True, log_floor=1.0)
    assert floored.value_range[0] == 0.0
    region = ds.region([0.5] * 3, [0.25] * 3, [0.75] * 3)
    cut = amrvk.Volume.from_yt(region, ("enzo", "Density"), log=False)
    assert cut.cells == len(region[("index", "ones")])
    assert np.all(np.array(cut.summary()["world_lo"]) >= 0.25 - 1e-9)
    assert np.all(np.array(cut.summary()["world_hi"]) <= 0.75 + 1e-9)
    with pytest.raises(TypeError, match="expected a yt data set or data object"):
        amrvk.Volume.from_yt("DD0018", ("enzo", "Density"), log=False)


def test_refinement_by_three_is_refused(amrvk, yt):
    grids = [
        dict(left_edge=[0.0, 0.0, 0.0], right_edge=[1.0, 1.0, 1.0], level=0, dimensions=[3, 3, 3],
             density=np.ones((3, 3, 3))),
        dict(left_edge=[1 / 3, 1 / 3, 1 / 3], right_edge=[2 / 3, 2 / 3, 2 / 3], level=1, dimensions=[3, 3, 3],
             density=2 * np.ones((3, 3, 3))),
    ]
    ds = yt.load_amr_grids(grids, [3, 3, 3], refine_by=3)
    with pytest.raises(ValueError, match="3 times the finest one: amrvk needs refinement by powers of two"):
        amrvk.Volume.from_yt(ds, ("stream", "density"), log=False)


def test_the_picture_of_from_yt_is_the_native_readers(amrvk, yt):
    ds = yt.load(str(need(ENZO)))
    native = amrvk.Volume(str(ENZO), field="Density", scale="linear")
    bridged = amrvk.Volume.from_yt(ds, ("enzo", "Density"), log=False)
    settings = dict(width=32, height=32, mode="ss", density_scale=0.05, tf_range=(0.0, 3.0),
                    tf=amrvk.TransferFunction.preset("ramp", 0.0, 3.0), background=(1, 1, 1),
                    lights=[amrvk.Light.directional([1, -1, 2], [4, 4, 4])], quiet=True)
    camera = amrvk.Camera.frame(native)
    a = amrvk.Renderer(native, camera=camera, seed=1, **settings)
    b = amrvk.Renderer(bridged, camera=camera, seed=2, **settings)  # independent samples
    ia, ib = a.render(spp=256).copy(), b.render(spp=256).copy()
    va, vb = a.variance(), b.variance()
    assert tile_z_test(ia, va, ib, vb) == 0
    assert all(abs(z) < 4.5 for z in global_z(ia, va, ib, vb)), global_z(ia, va, ib, vb)
    # Power: the whole-image test catches the native data 5% denser (8x8 tiles need a 50% change).
    c = amrvk.Renderer(native, camera=camera, seed=3, **{**settings, "density_scale": 0.05 * 1.05})
    ic = c.render(spp=256).copy()
    assert all(abs(z) > 4.5 for z in global_z(ic, c.variance(), ib, vb)), global_z(ic, c.variance(), ib, vb)
