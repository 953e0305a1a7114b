#!/usr/bin/env bash
# Times the library's compile in a game's dev profile (clients/dev-profile: Bevy's advice,
# dependencies at opt-level 3 with debug assertions, overflow checks and debug info) against
# its plain `cargo build --release`, each from cold in a target directory of its own, and fails
# when the dev build takes more than BOUND times as long (default 1.5). Prints both times.
# Usage: bash scripts/dev_profile_build.sh [BOUND]
set -euo pipefail
cd "$(dirname "$0")/.."
bound=${1:-1.5}

# The ocean-fft unit's compile time in seconds, from the newest `--timings` report in $1.
unit_seconds() {
    python3 - "$1" <<'PY'
import glob, json, os, sys
report = max(glob.glob(os.path.join(sys.argv[1], "cargo-timings", "cargo-timing-*.html")),
             key=os.path.getmtime)
text = open(report).read()
start = text.index("UNIT_DATA = ") + len("UNIT_DATA = ")
units = json.loads(text[start:text.index("];", start) + 1])
print(sum(u["duration"] for u in units if u["name"] == "ocean-fft" and u["target"].strip() in ("", "(lib)")))
PY
}

release_dir=target/timing-release
rm -rf "$release_dir/cargo-timings"
# The library from cold, its dependencies reused: a warm target would time nothing.
cargo clean -q --release -p ocean-fft --target-dir "$release_dir" 2>/dev/null || true
cargo build --release --lib --locked --timings --target-dir "$release_dir" -q
release=$(unit_seconds "$release_dir")

dev_dir=$PWD/target/timing-dev-profile
rm -rf "$dev_dir/cargo-timings"
# A game depends on the crate from git or crates.io (the README's install line), which cargo
# never compiles incrementally; the client's path dependency would be, so incremental is off.
(cd clients/dev-profile && { cargo clean -q -p ocean-fft --target-dir "$dev_dir" 2>/dev/null || true; } \
    && CARGO_INCREMENTAL=0 cargo build --timings --target-dir "$dev_dir" -q)
dev=$(unit_seconds "$dev_dir")
# The game runs: the batch queries' group path in this build answers.
"$dev_dir/debug/game-dev-profile"

python3 - "$release" "$dev" "$bound" <<'PY'
import sys
release, dev, bound = map(float, sys.argv[1:])
ratio = dev / release
print(f"ocean-fft compile: release {release:.1f} s, a game's dev profile {dev:.1f} s, "
      f"ratio {ratio:.2f} (bound {bound})")
sys.exit(0 if ratio <= bound else 1)
PY
