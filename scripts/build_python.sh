#!/usr/bin/env bash
# Builds the Python package `scenesmith` (src/python: pyo3 + maturin, release profile) into
# target/wheels/ and installs it into .venv. Idempotent: skipped when the installed package was
# built from the current sources (a hash of src/, Cargo.toml and Cargo.lock, kept in
# .venv/.scenesmith-python). Usage: scripts/build_python.sh [--quiet] [--if-missing]
#   --if-missing  only build when `import scenesmith` fails (what scripts/setup.sh uses, so
#                 the CLI's first run does not wait for a rebuild after every source change)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
quiet=0
if_missing=0
for a in "$@"; do
  case "$a" in
    --quiet) quiet=1 ;;
    --if-missing) if_missing=1 ;;
    *) echo "usage: $0 [--quiet] [--if-missing]" >&2; exit 2 ;;
  esac
done
say() { [ "$quiet" = 1 ] || echo "build_python: $*" >&2; }

[ -x "$venv/bin/python" ] || { echo "build_python: no .venv: run scripts/setup.sh first" >&2; exit 1; }
if [ "$if_missing" = 1 ] && "$venv/bin/python" -c "import scenesmith" 2>/dev/null; then
  exit 0
fi
stamp="$venv/.scenesmith-python"
want="$(cd "$root" && { find src -type f \( -name '*.rs' -o -name '*.py' -o -name '*.pyi' -o -name '*.toml' -o -name '*.json' -o -name '*.txt' \) -not -path 'src/view/web/*' | sort | xargs sha256sum; sha256sum Cargo.toml Cargo.lock; } | sha256sum | cut -c1-16)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ] && "$venv/bin/python" -c "import scenesmith" 2>/dev/null; then
  say "up to date"
  exit 0
fi
say "building the wheel (release; a few minutes on 2 cores the first time)"
rm -rf "$root/target/wheels"
"$venv/bin/maturin" build --release --quiet -m "$root/src/python/Cargo.toml" \
  -i "$venv/bin/python" --out "$root/target/wheels" >&2
"$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps "$root"/target/wheels/scenesmith-*.whl
echo "$want" > "$stamp"
say "installed $(basename "$root"/target/wheels/scenesmith-*.whl) into .venv"
