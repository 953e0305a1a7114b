#!/usr/bin/env bash
# Makes the README's viewer pictures, docs/images/viewer_{calm,fresh_breeze,storm,storm_overview,storm_closeup}.png
# (1280×720), and docs/images/wake_viewer.png and wake_deck_viewer.png, with the real-time viewer rendering headless
# under a virtual X server, with 4×
# MSAA and trilinear filtering: on a machine without a GPU (Mesa's software Vulkan, lavapipe)
# anisotropic filtering makes a frame take minutes instead of about a second (a GPU runs the
# viewer with 16× by default).
# Needs: apt-get install -y xvfb mesa-vulkan-drivers libvulkan1 libxkbcommon-x11-0
# Run from anywhere: bash scripts/viewer_gallery.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
images="$root/docs/images"
mkdir -p "$images"

cargo build --release --manifest-path "$root/Cargo.toml" -p ocean-fft-viewer
viewer="$root/target/release/ocean-fft-viewer"

shot() {
    local name="$1"
    shift
    echo "== viewer_$name: $*"
    xvfb-run -a -s "-screen 0 1920x1080x24" "$viewer" --frames 2 --hide-ui --msaa 4 --anisotropy 1 \
        --width 1280 --height 720 --screenshot "$images/viewer_$name.png" "$@"
}

# A calm sea under a low sun: looking toward it, the glitter path to the horizon.
shot calm --preset calm --camera 0,3,0 --heading 25 --pitch -4 --sun 6,30 --exposure 0.9
# A fresh breeze (Beaufort 5) in the afternoon, the sun behind and to the side: whitecaps,
# the sky in the waves, the buoys and boats riding them.
shot fresh_breeze --preset fresh_breeze --camera 0,9,0 --heading 20 --pitch -7 --sun 35,160
# The storm under an overcast sky, looking across the wind from 25 m up: whitecaps on the
# crests and streaks of foam along the wind.
shot storm --preset storm --camera 150,25,-400 --heading 100 --pitch -9
# The storm from 30 m up, looking down across the wind: whitecaps metres across on the
# crests the breakers compress, residual foam and its streaks between them.
shot storm_overview --preset storm --camera 150,30,-400 --heading 100 --pitch -35
# 2 m above the storm's water: a foam sheet with holes, the ripples finer than the grids.
shot storm_closeup --preset storm --camera 150,2,-400 --pitch -20

# A boat at 8 m/s on a calm sea, seen from 40 m above with the camera following it: its
# Kelvin wedge and foam trail after 8 s of sea time (240 frames; several minutes).
xvfb-run -a -s "-screen 0 1920x1080x24" "$viewer" --preset calm --frames 240 --boat-speed 8 \
    --follow-boat --camera 0,40,0 --heading 0 --pitch -34 --hide-ui \
    --screenshot "$images/wake_viewer.png"
# From the boat's own deck, 3 m above its stern, looking back along its track.
xvfb-run -a -s "-screen 0 1920x1080x24" "$viewer" --preset calm --frames 240 --boat-speed 8 \
    --on-deck --pitch -10 --hide-ui --screenshot "$images/wake_deck_viewer.png"

# Coasts under a moderate breeze, the sun behind the eye: the island from 30 m up, its bay
# from a boat 9 m up, and the breakwater.
coast() {
    local name="$1"
    shift
    echo "== $name: $*"
    xvfb-run -a -s "-screen 0 1920x1080x24" "$viewer" --frames 2 --hide-ui --msaa 4 --anisotropy 1 \
        --width 1280 --height 720 --no-bodies --sun 35,200 --preset moderate_breeze \
        --screenshot "$images/$name.png" "$@"
}
coast coast_viewer --coast island --camera 150,30,-120 --heading 25 --pitch -12
coast surf_viewer --coast island --camera 235,9,-25 --heading 8 --pitch -6
coast breakwater_viewer --coast breakwater --camera 100,40,-180 --heading 40 --pitch -14

ls -l "$images"/viewer_*.png "$images"/wake_viewer.png "$images"/wake_deck_viewer.png \
    "$images"/coast_viewer.png "$images"/surf_viewer.png "$images"/breakwater_viewer.png
