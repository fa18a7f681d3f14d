#!/usr/bin/env bash
# Builds the libFuzzer harnesses in fuzz/ with clang, AddressSanitizer and UBSan (into
# build-fuzz/) and runs each for SECONDS (default 30) from its seed corpus in fuzz/corpus/, with
# its dictionary and random seed 1 (the same inputs on every run). Any crash, sanitizer finding,
# leak, hang (10 s) or allocation beyond 2 GB stops the run with the input that caused it.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
flags="-fsanitize=fuzzer-no-link,address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer -g -O1"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLIGHTCONE_FUZZ=ON -DLIGHTCONE_PYTHON=OFF -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene fuzz_mesh fuzz_image fuzz_stars
for harness in scene mesh image stars; do
  work=$(mktemp -d)
  cp -r "fuzz/corpus/$harness/." "$work/"
  dict=()
  [ -f "fuzz/$harness.dict" ] && dict=(-dict="fuzz/$harness.dict")
  echo "fuzzing $harness for $seconds s"
  status=0
  ./build-fuzz/fuzz_$harness "$work" "${dict[@]}" -max_total_time="$seconds" -seed=1 -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/" >"build-fuzz/fuzz_$harness.log" 2>&1 || status=$?
  grep -E "^(Done|stat::number_of_executed_units)|ERROR|SUMMARY" "build-fuzz/fuzz_$harness.log" || true
  rm -rf "$work"
  if [ "$status" -ne 0 ]; then
    echo "fuzz_$harness failed (status $status); the input is in build-fuzz/ (see its log)"
    exit 1
  fi
done
echo "fuzzers: no crash"
