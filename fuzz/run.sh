#!/usr/bin/env bash
# Run every fuzz target for a bounded time, one after the other.
#   fuzz/run.sh [SECONDS] [TARGET...]   (default: 60 s each, every target)
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`).
# Crashers land in fuzz/artifacts/TARGET/; reproduce one with
#   cargo +nightly fuzz run TARGET fuzz/artifacts/TARGET/crash-...
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(scene_file obj gltf light_pass shadow)
fi
for t in "${targets[@]}"; do
    mkdir -p "fuzz/corpus/$t"
    # Seeds, read only: the bundled scenes, and a few small OBJ files.
    seeds=()
    [ "$t" = scene_file ] && seeds=(scenes)
    [ -d "fuzz/seeds/$t" ] && seeds+=("fuzz/seeds/$t")
    echo "== $t for ${seconds} s"
    cargo +nightly fuzz run "$t" "fuzz/corpus/$t" "${seeds[@]}" -- \
        -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1
done
