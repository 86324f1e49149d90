"""docs/python.md runs top to bottom as a notebook (issue 33, point 2): its ```python blocks, in
order, become the cells of one notebook that nbconvert executes on the python3 kernel, and every
section with code shows a picture inline (an image/png output), as a yt user pasting the doc into
Jupyter would see it. Small pictures: the doc reads its side from AMRVK_DOC_SIDE.

The doc's paths are relative to the checkout with the data beside it (../shared/data/amr); the
notebook runs in a scratch directory laid out the same way (links to assets/ and to the data), so
what the doc writes stays out of the checkout."""
import os
import pathlib
import re

import pytest

from conftest import DATA, ENZO, SOURCE, need

DOC = SOURCE / "docs" / "python.md"
SIDE = 64


def sections(markdown):
    """[(heading, [code, ...]), ...]: the doc's python blocks under their nearest ## or ### heading."""
    out, heading, block = [], "(top)", None
    for line in markdown.splitlines():
        if block is not None:
            if line.startswith("```"):
                if not out or out[-1][0] != heading:
                    out.append((heading, []))
                out[-1][1].append("\n".join(block))
                block = None
            else:
                block.append(line)
        elif line.startswith("```python"):
            block = []
        elif re.match(r"#{2,3} ", line):
            heading = line.lstrip("#").strip()
    assert block is None, f"{DOC}: an unclosed ```python block"
    return out


def test_the_sections_are_found():
    found = sections(DOC.read_text())
    headings = [h for h, _ in found]
    assert headings[0] == "Three lines from yt" and "1. A yt data set, a first picture" in headings, headings
    assert all(code.strip() for _, blocks in found for code in blocks)


def test_python_md_runs_as_a_notebook(amrvk, yt, tmp_path, monkeypatch):
    nbformat = pytest.importorskip("nbformat", reason="Debian: python3-nbformat")
    execute = pytest.importorskip("nbconvert.preprocessors", reason="Debian: python3-nbconvert")
    kernelspec = pytest.importorskip("jupyter_client.kernelspec", reason="Debian: python3-jupyter-client")
    if "python3" not in kernelspec.KernelSpecManager().find_kernel_specs():
        pytest.skip("no python3 Jupyter kernel (Debian: python3-ipykernel)")
    need(ENZO)
    # The checkout's layout: work/assets -> the checkout's assets, shared/data/amr -> the data.
    work = tmp_path / "work"
    work.mkdir()
    (work / "assets").symlink_to(SOURCE / "assets")
    (tmp_path / "shared" / "data").mkdir(parents=True)
    (tmp_path / "shared" / "data" / "amr").symlink_to(DATA.resolve())
    # The kernel imports the module under test (an absolute path: the kernel runs in `work`).
    package = pathlib.Path(amrvk.__file__).resolve().parents[1]
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(package), os.environ.get("PYTHONPATH", "")]))
    monkeypatch.setenv("AMRVK_DOC_SIDE", str(SIDE))

    found = sections(DOC.read_text())
    nb = nbformat.v4.new_notebook()
    owner = []  # the section of each cell
    for heading, blocks in found:
        for code in blocks:
            nb.cells.append(nbformat.v4.new_code_cell(code))
            owner.append(heading)
    class Executor(execute.ExecutePreprocessor):
        def on_comm_open_jupyter_widget(self, msg):
            # Debian's ipywidgets 6.0 opens its comms without 'state' (the older widget protocol),
            # which nbclient 0.7's widget-state store indexes unconditionally; the widget's picture
            # is checked by its static copy (the doc's section 9), not its comm.
            return super().on_comm_open_jupyter_widget(msg) if "state" in msg["content"]["data"] else None

    Executor(timeout=600, kernel_name="python3").preprocess(nb, {"metadata": {"path": str(work)}})

    pictures = {h: 0 for h, _ in found}
    for heading, cell in zip(owner, nb.cells):
        for output in cell.outputs:
            assert output.output_type != "error", f"{heading}: {output.ename}: {output.evalue}"
            if output.output_type in ("execute_result", "display_data") and "image/png" in output.data:
                pictures[heading] += 1
    assert all(pictures.values()), f"sections without an inline picture: {[h for h, n in pictures.items() if n == 0]}"
    # What the doc says it writes, it wrote (into the scratch directory, not the checkout).
    for name in ("1-first-picture.png", "3-128spp.png", "4-velocity-magnitude.png", "tour.session.json",
                 "8-magma-legend.png"):
        assert (work / name).stat().st_size > 0, name
