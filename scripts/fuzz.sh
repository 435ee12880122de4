#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, -fsanitize=fuzzer,address,undefined) in a separate
# build folder, writes their seed corpora and runs each fuzzer for a while.
#   scripts/fuzz.sh [seconds per fuzzer, default 120] [fuzzer ...]
# Fuzzers: ply_fuzzer colmap_fuzzer npy_fuzzer spz_fuzzer compressed_ply_fuzzer sog_fuzzer
# splat_file_fuzzer (default: all). Environment:
#   FUZZ_BUILD_DIR (default build-fuzz), JOBS (ninja -j, default 1), FUZZ_FORKS (parallel
#   fuzzing processes per fuzzer, default 1), FUZZ_KEEP_GOING=1 (fork mode that records
#   crashes, timeouts and OOMs and keeps fuzzing). Crashes land in $FUZZ_BUILD_DIR/artifacts;
#   the growing corpus in $FUZZ_BUILD_DIR/corpus/<fuzzer> is kept between runs.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-120}"
shift || true
fuzzers=("$@")
[ ${#fuzzers[@]} -gt 0 ] || fuzzers=(ply_fuzzer colmap_fuzzer npy_fuzzer spz_fuzzer compressed_ply_fuzzer sog_fuzzer splat_file_fuzzer)
build="${FUZZ_BUILD_DIR:-build-fuzz}"
jobs="${JOBS:-1}"
forks="${FUZZ_FORKS:-1}"

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (run scripts/setup.sh)" >&2; exit 1; }

sanitize="-fsanitize=address,undefined -fsanitize=fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DISEGMAN_FUZZ=ON -DISEGMAN_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$sanitize" -DCMAKE_CXX_FLAGS="$sanitize" >/dev/null
ninja -C "$build" -j"$jobs" make_fuzz_seeds "${fuzzers[@]}"

seeds="$build/fuzz-seeds"
rm -rf "$seeds"
fixtures=""
[ -d ../shared/fixtures ] && fixtures="../shared/fixtures"
"$build/fuzz/make_fuzz_seeds" "$seeds" $fixtures
# The reference tools' files (tests/data/formats) seed the splat-format fuzzers too.
for f in tests/data/formats/*; do
  case "$f" in
    *.sog) cp "$f" "$seeds/sog_fuzzer/" ;;
    *.spz) cp "$f" "$seeds/spz_fuzzer/" ;;
    *.compressed.ply) cp "$f" "$seeds/compressed_ply_fuzzer/" ;;
  esac
  cp "$f" "$seeds/splat_file_fuzzer/"
done

mkdir -p "$build/artifacts"
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
extra=()
if [ "${FUZZ_KEEP_GOING:-0}" = 1 ]; then
  extra=(-fork="$forks" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
elif [ "$forks" -gt 1 ]; then
  extra=(-fork="$forks")
fi
status=0
for f in "${fuzzers[@]}"; do
  mkdir -p "$build/corpus/$f"
  echo "fuzz.sh: $f for ${seconds}s"
  if ! "$build/fuzz/$f" "$build/corpus/$f" "$seeds/$f" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 \
      -print_final_stats=1 "${extra[@]}" \
      -artifact_prefix="$build/artifacts/$f-" 2>&1 | tee "$build/$f.log" | grep -E "^#[0-9]+.*(NEW|DONE|pulse)|ERROR|SUMMARY|stat::|Done" ; then
    :
  fi
  if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error|SUMMARY: UndefinedBehaviorSanitizer|INFO: log from the inner process" "$build/$f.log"; then
    echo "fuzz.sh: $f found a problem; see $build/$f.log and $build/artifacts/" >&2
    status=1
  fi
done
exit $status
