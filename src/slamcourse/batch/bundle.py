"""The Gradescope autograder bundle: ``setup.sh`` + ``run_autograder`` (+ wheel, course, secret).

Gradescope unpacks the zip into ``/autograder/source``, runs ``setup.sh`` once when it builds
the image, and ``run_autograder`` per submission; the learner's upload is in
``/autograder/submission`` and the grader writes ``/autograder/results/results.json``.
"""

from __future__ import annotations

import zipfile
from pathlib import Path

from slamcourse import __version__
from slamcourse.errors import UsageError

VENV = "/opt/slamcourse"

SETUP = """#!/usr/bin/env bash
# Gradescope runs this once when it builds the autograder image.
set -euo pipefail
apt-get update
apt-get install -y --no-install-recommends python3 python3-venv python3-pip bubblewrap
PYTHON=python3
# slamcourse needs Python 3.11 or newer (Gradescope's Ubuntu 22.04 image has 3.10)
if ! python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))'; then
  apt-get install -y --no-install-recommends python3.11 python3.11-venv
  PYTHON=python3.11
fi
"$PYTHON" -m venv {venv}
{venv}/bin/pip install --upgrade pip
{install}
"""

RUN = """#!/usr/bin/env bash
# Gradescope runs this for every submission.
set -uo pipefail
ROOT=${{AUTOGRADER_ROOT:-/autograder}}  # overridable only to test this script
SLAMCOURSE=${{SLAMCOURSE_BIN:-{venv}/bin/slamcourse}}
SOURCE=$ROOT/source
SUBMISSION=$ROOT/submission
RESULTS=$ROOT/results
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
mkdir -p "$RESULTS"
# a learner may upload the submission folder's files or the submission zip itself
if [ ! -f "$SUBMISSION/submission.json" ]; then
  ZIP=$(find "$SUBMISSION" -maxdepth 1 -name '*.zip' | sort | head -n 1)
  if [ -n "$ZIP" ]; then SUBMISSION="$ZIP"; fi
fi
COURSE=()
if [ -d "$SOURCE/course" ]; then COURSE=(--course "$SOURCE/course"); fi
if [ -f "$SOURCE/secret" ]; then export SLAMCOURSE_GRADING_SECRET="$(cat "$SOURCE/secret")"; fi
# Gradescope's container is the outer sandbox; namespaces are used whenever it allows them
ISOLATION=()
if ! "$SLAMCOURSE" doctor --json | grep -q '"isolation": "namespaces"'; then
  ISOLATION=(--allow-no-isolation)
fi
if "$SLAMCOURSE" "${{COURSE[@]}}" grade "$SUBMISSION" --format gradescope \\
    --out "$OUT" "${{ISOLATION[@]}}"; then
  cp "$OUT"/*/results.json "$RESULTS/results.json"
else
  printf '{{"score": 0, "output": "The autograder could not run; tell your instructor."}}\\n' \\
    > "$RESULTS/results.json"
fi
"""


def gradescope_bundle(
    out: Path, *, wheel: str | None = None, course: str | None = None, secret: str | None = None
) -> Path:
    """Write the autograder zip to ``out``: slamcourse from PyPI (this version) or ``wheel``;
    ``course`` (a course folder) is shipped inside when it is not the bundled one; ``secret``
    seeds the hidden checks."""
    if out.suffix.lower() != ".zip":
        raise UsageError(f"--out {out}: the Gradescope bundle is a .zip file")
    if wheel is not None:
        wheel_path = Path(wheel)
        if not wheel_path.is_file() or wheel_path.suffix != ".whl":
            raise UsageError(f"--wheel {wheel}: not a wheel file (build one: python -m build)")
        install = f"{VENV}/bin/pip install /autograder/source/{wheel_path.name}"
    else:
        install = f"{VENV}/bin/pip install 'slamcourse=={__version__}'"
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        _script(zf, "setup.sh", SETUP.format(venv=VENV, install=install))
        _script(zf, "run_autograder", RUN.format(venv=VENV))
        if wheel is not None:
            zf.write(wheel, Path(wheel).name)
        if secret:
            zf.writestr("secret", secret)
        if course is not None:
            from slamcourse.course.locate import course_root

            root = course_root(course)
            for top in ("chapters", "exercises"):
                for path in sorted((root / top).rglob("*")):
                    if path.is_file() and "__pycache__" not in path.parts:
                        zf.write(path, "course/" + path.relative_to(root).as_posix())
    return out


def _script(zf: zipfile.ZipFile, name: str, text: str) -> None:
    info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
    info.external_attr = 0o100755 << 16  # executable
    info.compress_type = zipfile.ZIP_DEFLATED
    zf.writestr(info, text)
