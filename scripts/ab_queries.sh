#!/usr/bin/env bash
# Times the batch queries of this checkout against another commit in one process:
#   bash scripts/ab_queries.sh REV [THREADS] [ROUNDS]
# Both versions of the crate are linked into one harness (scripts/ab_queries/main.rs), built
# on the default ocean and alternated batch by batch, so a machine whose speed wanders gives
# both the same minutes. Prints ns a point (fastest and first-quartile batch) of `heights_at`
# and `surfaces_at` over 100 to 100 000 points scattered across 2 km (the criterion benches'
# points), and their ratios.
# Needs REV to have `heights_at` and `surfaces_at` (0.2 and later). Builds both crates in
# release (about five minutes on 2 cores), then runs for about a minute.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
rev="${1:?usage: scripts/ab_queries.sh REV [THREADS] [ROUNDS]}"
threads="${2:-1}"
rounds="${3:-15}"
work="$(mktemp -d)"
trap 'git -C "$root" worktree remove --force "$work/old" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT

git -C "$root" worktree add -f --detach -q "$work/old" "$rev"
# Two packages of one name need different versions to be linked together.
sed -i '0,/^version = /s/^version = .*/version = "0.0.0-old"/' "$work/old/Cargo.toml"
mkdir -p "$work/harness/src"
cp "$root/scripts/ab_queries/main.rs" "$work/harness/src/main.rs"
cp "$root/benches/common/points.rs" "$work/harness/src/points.rs"
cat > "$work/harness/Cargo.toml" <<TOML
[package]
name = "ab-queries"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
old = { package = "ocean-fft", path = "$work/old" }
new = { package = "ocean-fft", path = "$root" }
rayon = "1"

[workspace]
TOML
cargo build --release -q --manifest-path "$work/harness/Cargo.toml"
"$work/harness/target/release/ab-queries" "$threads" "$rounds"
