#!/usr/bin/env bash
# Install slamcourse (system packages via apt when missing, Python packages via pip into .venv)
# and start the bundled course: `slamcourse next`. Progress lives in an embedded SQLite file
# (`slamcourse doctor` prints where). Extra arguments go to `slamcourse next`.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
EXTRAS="" source scripts/setup.sh
exec .venv/bin/slamcourse next "$@"
