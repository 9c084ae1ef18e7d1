#!/usr/bin/env bash
# The whole test suite: formatting and lints, Rust unit and integration tests (which drive the
# real Drake bridge), and the bridge's pytest suite. Sets up .venv on first use.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
step() { echo "== $* ($(date +%H:%M:%S))" >&2; }

step "python environment"
scripts/setup.sh
step "viewer: chromium and the page bundle"
if ! command -v chromium >/dev/null 2>&1 && [ -z "${SCENESMITH_CHROMIUM:-}" ]; then
  # Debian's chromium for the viewer's headless-browser test (tests/viewer.rs).
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  else
    sudo apt-get update -qq && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  fi
fi
scripts/build_viewer.sh
step "cargo fmt --check"
cargo fmt --all -- --check
step "cargo clippy -D warnings"
cargo clippy --workspace --all-targets --quiet -- -D warnings
step "cargo test"
SCENESMITH_HOME="$root" cargo test --quiet
step "python package scenesmith (pyo3 wheel)"
scripts/build_python.sh
step "pytest drake_bridge and the python package"
.venv/bin/python -m pytest drake_bridge/tests src/python/tests -q
step "all tests passed"
