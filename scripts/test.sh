#!/usr/bin/env bash
# The whole test suite: formatting and lints, Rust unit and integration tests (which drive the
# real Drake bridge), and the bridge's pytest suite. Sets up .venv on first use.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
step() { echo "== $* ($(date +%H:%M:%S))" >&2; }

step "python environment"
scripts/setup.sh
step "cargo fmt --check"
cargo fmt --all -- --check
step "cargo clippy -D warnings"
cargo clippy --all-targets --quiet -- -D warnings
step "cargo test"
SCENESMITH_HOME="$root" cargo test --quiet
step "pytest drake_bridge"
.venv/bin/python -m pytest drake_bridge/tests -q
step "all tests passed"
