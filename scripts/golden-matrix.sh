#!/usr/bin/env bash
# Golden hashes on the seven targets of the determinism contract, in debug and
# release: x86_64 (native, and built for x86-64-v3 in release), i686, aarch64, armv7, s390x (big-endian) under
# qemu-user, wasm32-wasip1 under node, and a bare-metal Cortex-M4
# (thumbv7em-none-eabihf, no_std, no allocator) under qemu-system-arm.
#
# The hosted targets run `cargo test --test golden`; the Cortex-M4 runs
# cross/cortex-m4, which includes the same scene file (tests/golden_scenes/mod.rs)
# and checks the same committed constants.
#
# Installs what it needs, idempotently: Debian packages (qemu-user-static,
# qemu-system-arm, cross gcc and libc for each foreign Linux target; nodejs only if
# node is missing) and rustup targets. Without apt-get (or root/sudo) and with a
# package missing, it fails loudly: nothing is ever skipped.
#
# Prints one line per target and profile, logs under target/golden-matrix/, and
# exits non-zero if any target fails.
#
#   scripts/golden-matrix.sh                 # everything
#   GOLDEN_TARGETS="s390x thumbv7em" scripts/golden-matrix.sh   # a subset (substring match)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
LOGS="$ROOT/target/golden-matrix"
mkdir -p "$LOGS"

# One of these timeouts firing is a failure, never a hang of CI.
TEST_TIMEOUT=${GOLDEN_TEST_TIMEOUT:-1800}
M4_TIMEOUT=${GOLDEN_M4_TIMEOUT:-1800}

start_all=$SECONDS
# Every golden scene is one test in tests/golden.rs and one entry of the
# Cortex-M4's list: a run must pass exactly this many.
SCENES=$(grep -c '^#\[test\]' tests/golden.rs)
M4_SCENES=$(grep -c '^    ("' cross/cortex-m4/src/main.rs)
[ "$SCENES" = "$M4_SCENES" ] || {
  printf 'golden-matrix: ERROR: %s\n' "tests/golden.rs has $SCENES scenes, cross/cortex-m4 lists $M4_SCENES" >&2
  exit 2
}
say() { printf '%s\n' "$*"; }
die() {
  printf 'golden-matrix: ERROR: %s\n' "$*" >&2
  exit 2
}

# ---- Debian packages -----------------------------------------------------------

APT_PACKAGES=(
  qemu-user-static qemu-system-arm
  gcc-i686-linux-gnu libc6-dev-i386-cross
  gcc-aarch64-linux-gnu libc6-dev-arm64-cross
  gcc-arm-linux-gnueabihf libc6-dev-armhf-cross
  gcc-s390x-linux-gnu libc6-dev-s390x-cross
)
command -v node >/dev/null 2>&1 || APT_PACKAGES+=(nodejs)

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }

missing=()
if command -v dpkg-query >/dev/null 2>&1; then
  for p in "${APT_PACKAGES[@]}"; do installed "$p" || missing+=("$p"); done
else
  missing=("${APT_PACKAGES[@]}")
fi
if ((${#missing[@]})); then
  t0=$SECONDS
  say "installing Debian packages: ${missing[*]}"
  command -v apt-get >/dev/null 2>&1 || die "apt-get not found; install by hand: ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then
    SUDO=()
  elif command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
  else
    die "not root and no sudo; install by hand: ${missing[*]}"
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${SUDO[@]}" apt-get update -qq || die "apt-get update failed"
  "${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >"$LOGS/apt.log" 2>&1 ||
    { tail -n 30 "$LOGS/apt.log" >&2; die "apt-get install failed (log: $LOGS/apt.log)"; }
  say "  installed in $((SECONDS - t0)) s"
fi
for tool in qemu-i386-static qemu-aarch64-static qemu-arm-static qemu-s390x-static qemu-system-arm node \
  i686-linux-gnu-gcc aarch64-linux-gnu-gcc arm-linux-gnueabihf-gcc s390x-linux-gnu-gcc; do
  command -v "$tool" >/dev/null 2>&1 || die "$tool not found after installing packages"
done

# ---- Rust targets --------------------------------------------------------------

command -v rustup >/dev/null 2>&1 || die "rustup not found"
RUST_TARGETS=(i686-unknown-linux-gnu aarch64-unknown-linux-gnu armv7-unknown-linux-gnueabihf
  s390x-unknown-linux-gnu wasm32-wasip1 thumbv7em-none-eabihf)
have_targets=$(rustup target list --installed)
need_targets=()
for t in "${RUST_TARGETS[@]}"; do grep -qx "$t" <<<"$have_targets" || need_targets+=("$t"); done
if ((${#need_targets[@]})); then
  t0=$SECONDS
  say "adding rustup targets: ${need_targets[*]}"
  rustup target add "${need_targets[@]}" >"$LOGS/rustup.log" 2>&1 ||
    { cat "$LOGS/rustup.log" >&2; die "rustup target add failed"; }
  say "  added in $((SECONDS - t0)) s"
fi

# The Cortex-M4 crate has its own lock file: it must build the engine with the
# very dependency versions the main crate tests with.
engine_deps() { cargo tree --locked -e normal --target thumbv7em-none-eabihf --prefix none "$@"; }
if ! diff <(engine_deps --no-default-features) <(cd cross/cortex-m4 && engine_deps -p arphysics) \
  >"$LOGS/engine-deps.diff" 2>&1; then
  cat "$LOGS/engine-deps.diff" >&2
  die "cross/cortex-m4/Cargo.lock pins other engine dependencies than Cargo.lock: copy Cargo.lock there and rebuild"
fi

# ---- the matrix ----------------------------------------------------------------

passed=0
failed=0
failures=()
selected() {
  [ -z "${GOLDEN_TARGETS:-}" ] && return 0
  local s
  for s in $GOLDEN_TARGETS; do [[ $1 == *"$s"* ]] && return 0; done
  return 1
}

# record TARGET PROFILE HOW STATUS SECONDS LOG
record() {
  local target=$1 profile=$2 how=$3 status=$4 secs=$5 log=$6 hashes
  # "pyramid hash after 300 steps: 0x…" (host) or "pyramid: 0x… ok" (Cortex-M4)
  # become "pyramid=0x…", in one order for every target.
  # (on wasm the line follows libtest's "test name ... " on the same line).
  hashes=$(grep -Eo '[a-z -]+( hash after [0-9]+ steps)?: 0x[0-9a-f]{16}' "$log" 2>/dev/null |
    sed -E 's/^ *([a-z-]+)[a-z -]*( hash after [0-9]+ steps)?: (0x[0-9a-f]{16}).*/\1=\3/' | sort | tr '\n' ' ' || true)
  if [ "$status" -eq 0 ]; then
    passed=$((passed + 1))
    printf 'PASS  %-32s %-7s %-26s %4d s  %s\n' "$target" "$profile" "$how" "$secs" "$hashes"
  else
    failed=$((failed + 1))
    failures+=("$target $profile")
    printf 'FAIL  %-32s %-7s %-26s %4d s  (log: %s)\n' "$target" "$profile" "$how" "$secs" "$log"
    sed -n '/hash after\|panicked\|assertion\|left:\|right:\|error\|MISMATCH\|FAILED\|panic:/p' "$log" |
      head -n 30 | sed 's/^/      /'
  fi
}

# Linkers and runners of the foreign hosted targets (cargo reads them per target).
export CARGO_TARGET_I686_UNKNOWN_LINUX_GNU_LINKER=i686-linux-gnu-gcc
export CARGO_TARGET_I686_UNKNOWN_LINUX_GNU_RUNNER=qemu-i386-static
export CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_LINKER=aarch64-linux-gnu-gcc
export CARGO_TARGET_AARCH64_UNKNOWN_LINUX_GNU_RUNNER=qemu-aarch64-static
export CARGO_TARGET_ARMV7_UNKNOWN_LINUX_GNUEABIHF_LINKER=arm-linux-gnueabihf-gcc
export CARGO_TARGET_ARMV7_UNKNOWN_LINUX_GNUEABIHF_RUNNER=qemu-arm-static
export CARGO_TARGET_S390X_UNKNOWN_LINUX_GNU_LINKER=s390x-linux-gnu-gcc
export CARGO_TARGET_S390X_UNKNOWN_LINUX_GNU_RUNNER=qemu-s390x-static
# (The WASI flag is needed by node 18, Debian's nodejs, and accepted by later nodes.)
export CARGO_TARGET_WASM32_WASIP1_RUNNER="node --no-warnings --experimental-wasi-unstable-preview1 $ROOT/scripts/wasi-run.mjs"
# The golden scenes keep their WorldBuffers on the stack (the banded pyramid's
# are 0.8 MB), and wasm-ld gives a module 1 MB of stack by default, shared with
# the test harness: the test binaries get 8 MB (a game with large buffers on
# the stack needs the same link argument).
export CARGO_TARGET_WASM32_WASIP1_RUSTFLAGS="-C link-arg=-zstack-size=8388608"

# target  how  QEMU_LD_PREFIX (the target's libc, for qemu-user's dynamic loader)
FOREIGN=(
  "i686-unknown-linux-gnu|qemu-i386-static|/usr/i686-linux-gnu"
  "aarch64-unknown-linux-gnu|qemu-aarch64-static|/usr/aarch64-linux-gnu"
  "armv7-unknown-linux-gnueabihf|qemu-arm-static|/usr/arm-linux-gnueabihf"
  "s390x-unknown-linux-gnu|qemu-s390x-static (BE)|/usr/s390x-linux-gnu"
  "wasm32-wasip1|node (WASI)|"
)

# Foreign builds leave out debug info, which only slows compiling and linking:
# "debug" here means the test profile's opt-level 1 with debug assertions and
# overflow checks, which stay as Cargo.toml sets them. The native build keeps
# the profiles untouched so it reuses what `cargo test` built.
NODEBUGINFO=(CARGO_PROFILE_DEV_DEBUG=false CARGO_PROFILE_TEST_DEBUG=false CARGO_PROFILE_RELEASE_DEBUG=false)

# golden TARGET PROFILE HOW [VAR=VALUE…]: cargo test --test golden, then record.
# TARGET "native" builds for the host without --target (sharing target/debug
# and target/release with the plain `cargo test`).
golden() {
  local target=$1 profile=$2 how=$3
  shift 3
  local name=$target args=(--locked --test golden) t0=$SECONDS status=0
  if [ "$target" = native ]; then
    name=$HOST
  elif [ "$target" = native-v3 ]; then
    name=$HOST-x86-64-v3
  else
    args+=(--target "$target")
  fi
  [ "$profile" = release ] && args+=(--release)
  local log="$LOGS/$name-$profile.log"
  env "$@" timeout "$TEST_TIMEOUT" cargo test "${args[@]}" -- --nocapture >"$log" 2>&1 || status=$?
  # A run that printed no result line has not run the tests.
  [ "$status" -eq 0 ] && ! grep -q "^test result: ok. $SCENES passed" "$log" && status=1
  record "$name" "$profile" "$how" "$status" "$((SECONDS - t0))" "$log"
}

say "golden matrix: cargo test --test golden (debug and release) per target, then the Cortex-M4"

HOST=$(rustc -vV | sed -n 's/^host: //p')
if selected "$HOST"; then
  for profile in debug release; do golden native "$profile" native; done
fi
# x86-64 with AVX2 compiled in (the contact kernels' eight-lane path without
# runtime dispatch), in a target directory of its own so the flags do not
# rebuild the native one. The native runs above take the runtime-dispatched
# AVX2 path where the processor has it, and tests/simd_parity.rs compares it
# with the portable path.
if [ "$(uname -m)" = x86_64 ] && selected "x86-64-v3"; then
  golden native-v3 release "x86-64-v3 (AVX2 built in)" RUSTFLAGS="-C target-cpu=x86-64-v3" \
    CARGO_TARGET_DIR="$ROOT/target/x86-64-v3"
fi

# One cargo invocation builds every selected foreign target of a profile, so the
# two cores stay busy across targets; each target then runs on its own (and a
# target that failed to build fails there, with its own log).
foreign_targets=()
for f in "${FOREIGN[@]}"; do
  IFS='|' read -r target _ _ <<<"$f"
  selected "$target" && foreign_targets+=(--target "$target")
done
for profile in debug release; do
  ((${#foreign_targets[@]})) || break
  t0=$SECONDS flags=()
  [ "$profile" = release ] && flags=(--release)
  if env "${NODEBUGINFO[@]}" timeout "$TEST_TIMEOUT" cargo test --locked --no-run --test golden "${flags[@]}" \
    "${foreign_targets[@]}" >"$LOGS/build-foreign-$profile.log" 2>&1; then
    say "built $((${#foreign_targets[@]} / 2)) foreign targets ($profile) in $((SECONDS - t0)) s"
  else
    say "building the foreign targets together failed ($profile, $((SECONDS - t0)) s); each target retries alone"
  fi
  for f in "${FOREIGN[@]}"; do
    IFS='|' read -r target how prefix <<<"$f"
    selected "$target" || continue
    golden "$target" "$profile" "$how" "${NODEBUGINFO[@]}" QEMU_LD_PREFIX="$prefix"
  done
done

# The Cortex-M4: cross/cortex-m4's `cargo run` runs the ELF on qemu-system-arm
# (mps2-an386, see its .cargo/config.toml); exit status 0 only if every scene matched.
if selected thumbv7em-none-eabihf; then
  for profile in debug release; do
    log="$LOGS/thumbv7em-none-eabihf-$profile.log" flags=() t0=$SECONDS status=0
    [ "$profile" = release ] && flags=(--release)
    (cd cross/cortex-m4 && timeout "$M4_TIMEOUT" cargo run --locked "${flags[@]}") >"$log" 2>&1 </dev/null ||
      status=$?
    [ "$status" -eq 0 ] && ! grep -q "^golden: $SCENES passed, 0 failed" "$log" && status=1
    record thumbv7em-none-eabihf "$profile" "qemu-system-arm mps2-an386" "$status" "$((SECONDS - t0))" "$log"
  done
fi

((passed + failed)) || die "GOLDEN_TARGETS='${GOLDEN_TARGETS:-}' selects no target"
say "golden matrix finished in $((SECONDS - start_all)) s; logs in $LOGS"
if ((failed)); then
  printf 'failed: %s\n' "${failures[@]}"
fi
say "golden-matrix: $passed passed, $failed failed"
((failed == 0))
