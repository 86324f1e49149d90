#!/usr/bin/env python3
"""Usage: doc_names.py REPO DOC...

Checks that the code names a document cites in backquotes still exist in the repository REPO
(issue 54: docs/architecture.md true to the code):
- a qualified name (`scene::Volume`, `Renderer::accumulateStaged`, `picture::Options::warmTracer`):
  every part is an identifier somewhere in src/, shaders/, python/, tests/ or tools/;
- a file pair (`auto_select.*`): a tracked file of that stem;
- a source or document file (`tools/run.sh`, `first_frame.h`, `shared/data/amr/FORMATS.md`): a
  tracked file of that name, or that path in the folder beside the repository (the shared data).
Other backquoted text (options, values, commands, plain words) is not checked. Prints each name
that is missing with its document and line, and exits 1 when one is.
"""
import re
import subprocess
import sys
from pathlib import Path

QUALIFIED = re.compile(r"[A-Za-z_]\w*(::~?[A-Za-z_]\w*)+")
PAIR = re.compile(r"[a-z_0-9]+\.\*")
FILE = re.compile(r"[A-Za-z0-9_./-]+\.(cpp|h|glsl|comp|py|sh|md)")


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    repo = Path(argv[1]).resolve()
    git = ["git", "-C", str(repo)]
    tracked = subprocess.run(git + ["ls-files"], capture_output=True, text=True, check=True).stdout.split()
    text = subprocess.run(git + ["grep", "-h", "-o", "-I", "-E", r"[A-Za-z_][A-Za-z0-9_]*", "--", "src", "shaders",
                                 "python", "tests", "tools", ":!tests/tools", ":!tools/doc_names.py"],  # not the check's own fixtures
                          capture_output=True, text=True, check=True).stdout
    words = set(text.split())
    names = {Path(f).name for f in tracked}
    stems = {Path(f).name.split(".")[0] for f in tracked}
    missing, checked = [], 0
    for doc in argv[2:]:
        for number, line in enumerate(Path(doc).read_text().splitlines(), 1):
            for cited in re.findall(r"`([^`\s]+)`", line):
                core = cited.rstrip("(),.;:")
                if core.endswith("()"):
                    core = core[:-2]
                if QUALIFIED.fullmatch(core):
                    ok = all(part.lstrip("~") in words for part in core.split("::"))
                elif PAIR.fullmatch(core):
                    ok = core[:-2] in stems
                elif FILE.fullmatch(core):
                    # A tracked file of that name, or the shared folder's (shared/data/amr/FORMATS.md).
                    ok = Path(core).name in names or (repo.parent / core.removeprefix("../")).exists()
                else:
                    continue
                checked += 1
                if not ok:
                    missing.append(f"{doc}:{number}: `{cited}` names nothing in the code")
    for m in missing:
        print(m)
    print(f"{checked} names checked, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
