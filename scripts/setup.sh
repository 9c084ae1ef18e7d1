#!/usr/bin/env bash
# Creates .venv/ with the pinned Python side of scenesmith (pydrake, numpy, mujoco, usd-core,
# pytest, ray, maturin) and verifies the imports, then installs the Python package `scenesmith`
# (scripts/build_python.sh --if-missing). Idempotent: a second run only re-verifies (about a second).
#
# Interpreter: CPython 3.12 (pyenv's 3.12.*, or python3.12 on PATH) with drake 1.58.0; where
# no 3.12 exists, CPython 3.11 with drake 1.51.1, the newest wheel for 3.11.
# SCENESMITH_SETUP_PYTHON=/path/to/python forces the interpreter the venv is made from.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
quiet=0
[ "${1:-}" = "--quiet" ] && quiet=1
say() { [ "$quiet" = 1 ] || echo "setup: $*" >&2; }

find_python() {
  if [ -n "${SCENESMITH_SETUP_PYTHON:-}" ]; then
    echo "$SCENESMITH_SETUP_PYTHON"; return
  fi
  local candidates=()
  if command -v pyenv >/dev/null 2>&1; then
    local proot; proot="$(pyenv root)"
    for v in $(ls -1 "$proot/versions" 2>/dev/null | grep -E '^3\.12\.[0-9]+$' | sort -t. -k3 -n -r); do
      candidates+=("$proot/versions/$v/bin/python")
    done
  fi
  candidates+=("$(command -v python3.12 || true)")
  if command -v pyenv >/dev/null 2>&1; then
    local proot; proot="$(pyenv root)"
    for v in $(ls -1 "$proot/versions" 2>/dev/null | grep -E '^3\.11\.[0-9]+$' | sort -t. -k3 -n -r); do
      candidates+=("$proot/versions/$v/bin/python")
    done
  fi
  candidates+=("$(command -v python3.11 || true)" "$(command -v python3 || true)")
  for c in "${candidates[@]}"; do
    [ -n "$c" ] && [ -x "$c" ] || continue
    local ver; ver="$("$c" -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null || true)"
    if [ "$ver" = "3.12" ] || [ "$ver" = "3.11" ]; then echo "$c"; return; fi
  done
  echo ""
}

base_python="$(find_python)"
if [ -z "$base_python" ]; then
  echo "setup: no CPython 3.12 or 3.11 found (looked in pyenv and PATH); install one or set SCENESMITH_SETUP_PYTHON" >&2
  exit 1
fi
pyver="$("$base_python" -c 'import sys; print("%d%d" % sys.version_info[:2])')"
req="$root/scripts/requirements-py$pyver.txt"
stamp_want="$(cat "$req" | sha256sum | cut -c1-16)-$("$base_python" -c 'import sys; print(sys.version.split()[0])')"
stamp="$venv/.scenesmith-setup"

verify() {
  "$venv/bin/python" - <<'PY'
import importlib.metadata as m
import pydrake.all, numpy, mujoco, pxr.Usd, pytest  # noqa: F401
print("drake", m.version("drake"), "numpy", numpy.__version__, "mujoco", mujoco.__version__,
      "usd-core", m.version("usd-core"))
PY
}

if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$stamp_want" ] && [ -x "$venv/bin/python" ]; then
  # The wrappers call this before every command: trust the stamp there (the bridge reports a
  # missing module itself); an explicit run re-verifies the imports.
  if [ "$quiet" = 1 ]; then
    "$root/scripts/build_python.sh" --quiet --if-missing
    exit 0
  fi
  if out="$(verify 2>&1)"; then
    "$root/scripts/build_python.sh" --if-missing $([ "$quiet" = 1 ] && echo --quiet)
    say "ready ($out)"
    exit 0
  fi
  say "existing .venv fails its import check; rebuilding"
fi

say "creating .venv from $base_python with $(basename "$req")"
rm -rf "$venv"
"$base_python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet -r "$req"
out="$(verify)"
echo "$stamp_want" > "$stamp"
say "ready ($out)"
"$root/scripts/build_python.sh" --if-missing $([ "$quiet" = 1 ] && echo --quiet)
