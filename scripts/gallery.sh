#!/usr/bin/env bash
# Regenerates the README's gallery, docs/images/*.png, by running the examples with the
# parameters the README's captions give. Takes about four minutes on 2 cores after the build
# (the whitecaps sweep and the three renders are most of it). Run from anywhere: bash scripts/gallery.sh
#
# The examples write into out/ under the directory they run in; this script runs them in a
# temporary directory and copies what the gallery shows into docs/images/. Indexed PNGs of
# 256 colours (--palette) keep the committed pictures small.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
images="$root/docs/images"
mkdir -p "$images"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cargo build --release --manifest-path "$root/Cargo.toml" -p ocean-fft-examples --examples

run() {
    local name="$1"
    shift
    echo "== $name $*"
    (cd "$work" && cargo run --quiet --release --manifest-path "$root/Cargo.toml" \
        -p ocean-fft-examples --example "$name" -- "$@")
}

run render --preset storm --width 512 --height 288 --palette --out "$images/render_storm.png"
run render --preset fresh_breeze --width 512 --height 288 --palette --out "$images/render_fresh_breeze.png"
run render --preset calm --width 512 --height 288 --palette --out "$images/render_calm.png"
run sea_states --tile 144 --palette
cp "$work/out/sea_states.png" "$images/sea_states.png"
run spectrum --width 720 --height 450 --palette
cp "$work/out/spectrum.png" "$images/spectrum.png"
run buoyancy --palette
cp "$work/out/buoyancy.png" "$images/buoyancy.png"
run whitecaps --palette
cp "$work/out/whitecaps.png" "$images/whitecaps.png"
run weather --palette
cp "$work/out/weather.png" "$images/weather.png"
cp "$work/out/weather_strip.png" "$images/weather_strip.png"
run second_order --palette
cp "$work/out/second_order.png" "$images/second_order.png"
run wake --palette
cp "$work/out/wake.png" "$images/wake_top.png"
cp "$work/out/wake_depth.png" "$images/wake_depth.png"

# The Bevy plugin's sea example (bevy_ocean_fft/), headless under Xvfb with Mesa's software
# Vulkan (needs xvfb mesa-vulkan-drivers libvulkan1 libxkbcommon-x11-0; about a minute after
# its build, which is long: see bevy_ocean_fft/README.md), without anisotropic filtering.
cargo build --release --manifest-path "$root/Cargo.toml" -p bevy_ocean_fft --example sea
(cd "$work" && xvfb-run -a -s "-screen 0 1920x1080x24" "$root/target/release/examples/sea" \
    --frames 60 --anisotropy 1 --screenshot "$images/bevy_sea.png")
for preset in calm storm; do
    (cd "$work" && xvfb-run -a -s "-screen 0 1920x1080x24" "$root/target/release/examples/sea" \
        --frames 30 --anisotropy 1 --preset "$preset" --screenshot "$images/bevy_$preset.png")
done
# Its boats' wakes: the first boat at 8 m/s on a calm sea, the camera 40 m above following it
# (Bevy's virtual time takes at most 0.25 s a frame: 40 frames are about 10 s of sea time).
(cd "$work" && xvfb-run -a -s "-screen 0 1920x1080x24" "$root/target/release/examples/sea" \
    --frames 40 --anisotropy 1 --preset calm --boat-speed 8 --follow-boat \
    --camera 19.3,40,6.4 --look-at -2.2,0,-16.8 --screenshot "$images/wake_bevy.png")
# From the first boat's deck (it starts at (-7, 0, -8) heading along (-0.48, 0, 0.88)): 2.5 m
# above its stern, looking back along its track.
(cd "$work" && xvfb-run -a -s "-screen 0 1920x1080x24" "$root/target/release/examples/sea" \
    --frames 40 --anisotropy 1 --preset calm --boat-speed 8 --follow-boat \
    --camera -5.56,2.5,-10.63 --look-at 7.4,0,-34.3 --screenshot "$images/wake_deck_bevy.png")

# The island coast (its depth map and ground) under a moderate breeze, from the example's
# view of it.
(cd "$work" && xvfb-run -a -s "-screen 0 1920x1080x24" "$root/target/release/examples/sea" \
    --frames 30 --anisotropy 1 --preset moderate_breeze --coast island \
    --screenshot "$images/coast_bevy.png")

ls -l "$images"
du -ch "$images"/*.png | tail -n 1
