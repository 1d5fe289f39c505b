"""Every shell block of the README, of the example data's READMEs, of docs/data.md (the real-data
walkthrough), docs/fitting.md and docs/studies.md (the lighting worked study) runs as written.

The blocks run with bash (-e -o pipefail) in a scratch folder laid out like the source tree: a copy of
data/ (commands may write into data/examples/fits), examples/ and docs/ linked, and build/roadbrdf,
build/python pointing at the program and package under test. A block preceded by
``<!-- docs-test: skip (reason) -->`` is not run (installing system-wide, building everything again).
"""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCUMENTS = ["README.md", "data/examples/README.md", "data/examples/formulations/README.md", "docs/data.md",
             "docs/fitting.md",
             "docs/studies.md"]


def shell_blocks(document):
    text = (ROOT / document).read_text(encoding="utf-8")
    blocks = []
    for m in re.finditer(r"^[ \t]*```sh\n(.*?)^[ \t]*```", text, flags=re.S | re.M):
        before = text[: m.start()].rstrip().splitlines()
        skipped = bool(before) and "docs-test: skip" in before[-1]
        line = text[: m.start()].count("\n") + 1
        body = "\n".join(l.strip() if l.startswith("  ") and not l.startswith("    ") else l
                         for l in m.group(1).splitlines())
        blocks.append((line, skipped, body))
    return blocks


CASES = [(doc, line, body) for doc in DOCUMENTS for line, skipped, body in shell_blocks(doc) if not skipped]


def test_documents_have_runnable_blocks():
    # The README's quick start is skipped only because it is what CI itself runs (make test).
    assert len(CASES) >= 4, CASES


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    cli = pathlib.Path(os.environ.get("ROADBRDF_CLI", ROOT / "build" / "roadbrdf")).resolve()
    scratch = tmp_path_factory.mktemp("doc-commands")
    shutil.copytree(ROOT / "data", scratch / "data", symlinks=True)
    for name in ("examples", "docs", "scripts", "tests"):
        (scratch / name).symlink_to(ROOT / name)
    (scratch / "build").mkdir()
    (scratch / "build" / "roadbrdf").symlink_to(cli)
    (scratch / "build" / "python").symlink_to(cli.parent / "python")
    (scratch / "build" / "tests").symlink_to(cli.parent / "tests")  # the generated instrument files
    return scratch


@pytest.mark.parametrize("document,line,body", CASES, ids=[f"{d}:{l}" for d, l, _ in CASES])
def test_block_runs(tree, document, line, body):
    if body.lstrip().startswith("make "):
        pytest.skip("make targets: `make test` is what CI runs, `make demo` is ctest examples.demo")
    result = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", body], cwd=tree, capture_output=True, text=True,
                            timeout=600)
    assert result.returncode == 0, f"{document}:{line} failed ({result.returncode}):\n{body}\n{result.stderr[-3000:]}"
