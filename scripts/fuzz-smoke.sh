#!/usr/bin/env bash
# Builds the cargo-fuzz targets and runs each for SECONDS (default 60),
# from libFuzzer seed FUZZ_SEED (default 1: a smoke run explores the same
# inputs every time, so its verdict is reproducible; campaigns that look
# for new failures run `cargo fuzz run` without a seed, docs/fuzzing.md).
# Uses the nightly toolchain when it is installed (libFuzzer with
# sanitizer coverage), else stable with `-s none`. A crash fails.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-60}
if ! cargo fuzz --version >/dev/null 2>&1; then
  cargo install cargo-fuzz --locked
fi
if rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
  run=(cargo +nightly fuzz)
  build_flags=()
else
  run=(cargo fuzz)
  build_flags=(-s none)
fi
"${run[@]}" build "${build_flags[@]}"
for target in $("${run[@]}" list); do
  mkdir -p "corpus/$target"
  extra=()
  [ -d "corpus/seeds/$target" ] && extra+=("corpus/seeds/$target")
  echo "--- fuzz $target for ${seconds}s"
  "${run[@]}" run "${build_flags[@]}" "$target" "corpus/$target" "${extra[@]}" -- -max_total_time="$seconds" -seed="${FUZZ_SEED:-1}" -print_final_stats=1
done
