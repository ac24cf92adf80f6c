#!/usr/bin/env bash
# Creates (or checks) the Python virtual environment the Mitsuba comparison runs in:
#   tests/mitsuba/install.sh [VENV]      (default: build/pyenv, where CMake looks for it)
# Uses Debian's python3 and its venv module; pip's own cache keeps reinstalls quick. Does nothing
# when VENV already holds the pinned versions of requirements.txt.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="${1:-$here/../../build/pyenv}"
requirements="$here/requirements.txt"
stamp="$venv/.pmrender-requirements"
if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && cmp -s "$requirements" "$stamp"; then
  exit 0
fi
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
"$venv/bin/python" -c "import mitsuba, numpy; mitsuba.set_variant('scalar_rgb')"
cp "$requirements" "$stamp"
echo "Mitsuba $("$venv/bin/python" -c 'import mitsuba; print(mitsuba.__version__)') in $venv"
