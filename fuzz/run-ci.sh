#!/usr/bin/env bash
# Runs every fuzz target for a short while from the committed seed corpus.
#
#   fuzz/run-ci.sh [seconds-per-target]      (default 60)
#
# Needs a nightly toolchain (cargo-fuzz's coverage flags are unstable). With one
# installed and no cargo-fuzz, installs cargo-fuzz from crates.io. Without a
# nightly toolchain it says so and exits 0, so CI on a stable-only machine passes.
#
# Built without AddressSanitizer (`--sanitizer none`): the engine forbids unsafe
# code, and ASan costs 4-5x the executions per second; panics and overflows are
# caught by the debug assertions and overflow checks the fuzz profile keeps on.
#
# Exits non-zero when any target crashes (a panic, an overflow caught by the debug
# assertions the fuzz profile keeps on, a failed determinism check, or an input
# that takes longer than 30 s). The crashing input is kept under
# fuzz/artifacts/<target>/ and printed decoded; reproduce it with
#   cargo +nightly fuzz run -s none <target> fuzz/artifacts/<target>/<file>
# The committed corpus is only read: new inputs go to a scratch directory.
set -uo pipefail
cd "$(dirname "$0")"

secs="${1:-60}"
# A fixed seed by default, so CI replays the same input sequence every run (a
# slower machine just gets through less of it); FUZZ_SEED=0 picks a random one.
targets=(scene_ops replay_equal snapshot_restore)

if ! rustup run nightly rustc --version >/dev/null 2>&1; then
  echo "fuzz: skipped: no nightly toolchain (rustup toolchain install nightly to run the fuzz targets)"
  exit 0
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz: installing cargo-fuzz"
  cargo install --locked cargo-fuzz || { echo "fuzz: could not install cargo-fuzz"; exit 1; }
fi

echo "fuzz: building the targets ($(rustup run nightly rustc --version))"
cargo +nightly fuzz build --sanitizer none || exit 1

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
failed=()
for t in "${targets[@]}"; do
  mkdir -p "$scratch/$t"
  touch "$scratch/$t.start"
  echo "fuzz: $t for ${secs} s from corpus/$t ($(ls "corpus/$t" | wc -l) seeds)"
  if cargo +nightly fuzz run --sanitizer none "$t" "$scratch/$t" "corpus/$t" -- \
      -max_total_time="$secs" -seed="${FUZZ_SEED:-1}" -timeout=30 -max_len=4096 -len_control=0 -print_final_stats=1 \
      >"$scratch/$t.log" 2>&1; then
    grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec)' "$scratch/$t.log" | sed "s/^/fuzz: $t: /"
  else
    failed+=("$t")
    echo "fuzz: $t FAILED:"
    grep -E -A3 -m3 'panicked at|ERROR: libFuzzer|SUMMARY: ' "$scratch/$t.log"
    echo "fuzz: the last lines of its log:"
    tail -n 30 "$scratch/$t.log"
    for a in $(find "artifacts/$t" -type f -newer "$scratch/$t.start" 2>/dev/null); do
      echo "fuzz: $t: input $a decodes as:"
      cargo +nightly fuzz fmt "$t" "$a" 2>&1 | head -n 200
    done
  fi
done

if [ "${#failed[@]}" -gt 0 ]; then
  echo "fuzz: failed: ${failed[*]}"
  echo "fuzz: $(( ${#targets[@]} - ${#failed[@]} )) passed, ${#failed[@]} failed"
  exit 1
fi
echo "fuzz: ${#targets[@]} passed, 0 failed"
