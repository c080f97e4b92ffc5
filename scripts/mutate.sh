#!/usr/bin/env bash
# Mutation check of the test suite: applies known small bugs, one at a
# time, to a scratch copy of this work tree, rebuilds it incrementally
# (gcc, Release, no benchmarks) and runs the whole CTest suite.  A mutation
# is caught when some test fails that passes on the unmutated copy; it
# survives when none does.  Never touches this tree; not part of CI.
#
#   bash scripts/mutate.sh            every mutation
#   bash scripts/mutate.sh NAME...    only these
#   bash scripts/mutate.sh --list     the mutations, nothing built
#
# MUTATE_DIR (default /tmp/dbss-mutate) holds the copy and its build, kept
# between runs so the next run only rebuilds what changed; JOBS (default
# nproc) is the build and ctest parallelism; MUTATE_TIMEOUT (default 300)
# the per-test timeout in seconds.  Exit status 1 when a mutation survives.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
work=${MUTATE_DIR:-/tmp/dbss-mutate}
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
timeout=${MUTATE_TIMEOUT:-300}

# name | file | exact text (must occur once) | replacement
names=() files=() olds=() news=()
m() { names+=("$1"); files+=("$2"); olds+=("$3"); news+=("$4"); }

# The five of issue 20.
m quantizer-floor encoder/include/dbss/encoder/quantize.h \
  'std::nearbyint(distance / step)' 'std::floor(distance / step)'
m carving-26-neighbours encoder/src/cell_carving.cpp \
  '    if (i > 0) visit(i - 1, j, k);' \
  '    for (int dk = -1; dk <= 1; ++dk) for (int dj = -1; dj <= 1; ++dj) for (int di = -1; di <= 1; ++di) { const int x = i + di, y = j + dj, z = k + dk; if (x >= 0 && y >= 0 && z >= 0 && x < g.n[0] && y < g.n[1] && z < g.n[2]) visit(x, y, z); }'
m normal-ring-not-closed decoder/src/normals.cpp \
  'const uint32_t pairs = count == 6 ? 6 : 3;' 'const uint32_t pairs = count == 6 ? 5 : 3;'
m boundary-four-point-weights decoder/src/butterfly_terms.h \
  $'    add(tri[prev_half(x)], -1.0 / 16);\n    add(u, 9.0 / 16);\n    add(w, 9.0 / 16);\n    add(tri[next_half(t.vertex_start[w])], -1.0 / 16);' \
  $'    add(tri[prev_half(x)], -1.0 / 8);\n    add(u, 5.0 / 8);\n    add(w, 5.0 / 8);\n    add(tri[next_half(t.vertex_start[w])], -1.0 / 8);'
m reader-crc-unchecked format/src/reader.cpp \
  'if (stored != actual && limits_.verify_checksums)' 'if (false && stored != actual && limits_.verify_checksums)'
# Format.
m varint-five-bytes format/src/rules.cpp 'if (shift == 28)' 'if (shift == 35)'
m varint-range-unchecked format/src/rules.cpp '    if (z > kMaxZ) return bad_value(i);' ''
m varint-noncanonical-accepted format/src/rules.cpp 'if (b == 0 && shift != 0)' 'if (false && b == 0 && shift != 0)'
m varint-fast-path-seven format/src/rules.cpp \
  'for (size_t k = 0; k < 8; ++k) q[i + k]' 'for (size_t k = 0; k < 7; ++k) q[i + k]'
m writer-crc-short format/src/writer.cpp \
  'crc32c(std::span<const uint8_t>(out.data() + start, out.size() - start))' \
  'crc32c(std::span<const uint8_t>(out.data() + start, out.size() - start - 1))'
# LEVL coding 2 (spec section 9b).
m context-adapt-shift-4 format/src/context_coding.cpp \
  'constexpr uint32_t kAdaptShift = 5;' 'constexpr uint32_t kAdaptShift = 4;'
m context-overrun-unchecked format/src/context_coding.cpp \
  '    if (d.overrun()) return overrun(i);
    q[i] = v;' '    q[i] = v;'
m context-leftover-accepted format/src/context_coding.cpp \
  'if (d.at() != stream.size())' 'if (false && d.at() != stream.size())'
# Decoder.
m reflected-wing-signs decoder/src/butterfly_terms.h \
  $'        add(tri[x], -1.0 / 16);\n        add(tri[next_half(x)], -1.0 / 16);\n        add(away, 1.0 / 16);' \
  $'        add(tri[x], 1.0 / 16);\n        add(tri[next_half(x)], -1.0 / 16);\n        add(away, -1.0 / 16);'
m valence-4-weights decoder/src/butterfly_weights.inc \
  '    0x0.0p+0, -0x1.0000000000000p-3, 0x0.0p+0, 0x1.6666666666666p-2,' \
  '    -0x1.0000000000000p-4, 0x0.0p+0, -0x1.0000000000000p-4, 0x1.6666666666666p-2,'
m fast-normal-pair-swapped decoder/src/odd_vertex_kernels.inc \
  'n = add_cross_zxy(n, dw, w);' 'n = add_cross_zxy(n, w, dw);'
m edge-order-by-second-half decoder/src/topology.cpp \
  'if (o == kNoHalfEdge || o > h) {' 'if (o == kNoHalfEdge || o < h) {'
m valence-limit-unchecked decoder/src/topology.cpp 'if (valence > kMaxValence)' 'if (false && valence > kMaxValence)'
# Encoder.
m step-doubled encoder/include/dbss/encoder/quantize.h \
  'static_cast<float>(2 * error * diagonal)' 'static_cast<float>(4 * error * diagonal)'
m sampler-farthest-hit encoder/src/sampling.cpp \
  '(!hit || std::abs(t) < std::abs(best))' '(!hit || std::abs(t) > std::abs(best))'
m sampler-query-axes-swapped encoder/src/sampling.cpp \
  'const float q[3] = {static_cast<float>(pd[0]), static_cast<float>(pd[1]), static_cast<float>(pd[2])};' \
  'const float q[3] = {static_cast<float>(pd[1]), static_cast<float>(pd[0]), static_cast<float>(pd[2])};'
m carving-no-give-back encoder/src/cell_carving.cpp \
  'g.state[id] = touches_air ? CellGrid::kAir : CellGrid::kInside;' 'g.state[id] = CellGrid::kInside;'
m ply-never-byte-swapped io/src/ply.cpp \
  'const bool swap = (fmt == big) != (std::endian::native == std::endian::big);' 'const bool swap = false;'
m triangle-distance-corner-region encoder/src/triangle_tree.cpp \
  'if (d3 >= 0 && d4 <= d3) return dist2(p, b);' 'if (d3 >= 0 && d4 >= d3) return dist2(p, b);'
# Issue 15's sampler and quantizer, issue 14's io library.
m dead-zone-off encoder/include/dbss/encoder/quantize.h \
  'inline constexpr double kDeadZoneSteps = 1.0;' 'inline constexpr double kDeadZoneSteps = 0.5;'
m zero-levels-coded encoder/include/dbss/encoder/quantize.h \
  'if (coarser > points) return HUGE_VAL;' 'if (false && coarser > points) return HUGE_VAL;'
m fit-ignored encoder/src/sampling.cpp 'if (f.ok && (std::abs(f.height)' 'if (false && f.ok && (std::abs(f.height)'
m fit-not-robust encoder/src/surface_fit.cpp 'for (int round = 0; round < 2; ++round)' 'for (int round = 0; round < 0; ++round)'
m control-bits-one-short encoder/src/control_mesh_codec.cpp 'std::ceil(std::log2(extent / step))' 'std::floor(std::log2(extent / step))'
m obj-negative-index-off-by-one io/src/obj.cpp 'const long long index = i > 0 ? i - 1 : n + i;' 'const long long index = i > 0 ? i - 1 : n + i + 1;'

if [ "${1:-}" = --list ]; then
  for i in "${!names[@]}"; do printf '%-32s %s\n' "${names[$i]}" "${files[$i]}"; done
  exit 0
fi
selected=()
if [ $# -eq 0 ]; then
  selected=("${!names[@]}")
else
  for want in "$@"; do
    found=
    for i in "${!names[@]}"; do [ "${names[$i]}" = "$want" ] && selected+=("$i") && found=1; done
    [ -n "$found" ] || { echo "mutate: no mutation named '$want' (see --list)" >&2; exit 2; }
  done
fi

# Exact, single-occurrence text replacement.
replace() {  # file old new
  python3 - "$@" <<'EOF'
import sys
path, old, new = sys.argv[1:4]
text = open(path, encoding="utf-8").read()
n = text.count(old)
if n != 1:
    sys.exit(f"mutate: {path}: the text to mutate occurs {n} times, not once")
open(path, "w", encoding="utf-8").write(text.replace(old, new))
EOF
}

# The copy: this work tree as it is now (uncommitted edits included),
# without builds, git data or test data (the scans are linked).  tar keeps
# the modification times, so an unchanged file is not rebuilt.
copy="$work/src" build="$work/build"
mkdir -p "$work"
rm -rf "$copy"
mkdir -p "$copy"
tar -C "$src" --exclude='./build*' --exclude=./.git --exclude=./test-data -cf - . | tar -C "$copy" -xf -
[ -d "$src/test-data" ] && ln -s "$src/test-data" "$copy/test-data"

applied=
backup="$work/original"
cleanup() {
  # Interrupted with a mutation applied: put the file back and drop the
  # build, whose objects no longer match the sources.
  if [ -n "$applied" ]; then
    cp "$backup" "$copy/$applied"
    rm -rf "$build"
  fi
}
trap cleanup EXIT

cmake -S "$copy" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ \
  -DDBSS_BUILD_BENCH=OFF -DDBSS_WERROR=OFF >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; exit 2; }

# Failed test names of a ctest log, one a line.
failed_tests() { sed -n 's/^[[:space:]]*[0-9][0-9]* - \(.*\) ([A-Za-z* ]*)$/\1/p' "$1" | sort -u; }
run_suite() {  # log
  ctest --test-dir "$build" -j "$jobs" --timeout "$timeout" >"$1" 2>&1 || true
}

start=$(date +%s)
echo "mutate: baseline build and suite in $work"
cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || { tail -30 "$work/build.log"; exit 2; }
run_suite "$work/baseline.log"
failed_tests "$work/baseline.log" >"$work/baseline.failed"
total=$(sed -n 's/.*tests failed out of \([0-9]*\)$/\1/p' "$work/baseline.log")
if [ -s "$work/baseline.failed" ]; then
  echo "mutate: $(wc -l <"$work/baseline.failed") of $total tests fail without any mutation; they are ignored:"
  sed 's/^/  /' "$work/baseline.failed"
else
  echo "mutate: baseline: all $total tests pass ($(( $(date +%s) - start )) s)"
fi

survived=0 caught=0 broken=0
report="$work/report.txt"
: >"$report"
for i in "${selected[@]}"; do
  name=${names[$i]} file=${files[$i]}
  t0=$(date +%s)
  cp "$copy/$file" "$backup"
  replace "$copy/$file" "${olds[$i]}" "${news[$i]}"
  applied=$file
  touch "$copy/$file"
  if ! cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1; then
    line=$(printf '%-9s %-32s %s: does not compile' "BROKEN" "$name" "$file")
    broken=$((broken + 1))
  else
    run_suite "$work/$name.log"
    failed_tests "$work/$name.log" | comm -23 - "$work/baseline.failed" >"$work/$name.failed"
    n=$(wc -l <"$work/$name.failed")
    if [ "$n" -gt 0 ]; then
      caught=$((caught + 1))
      line=$(printf '%-9s %-32s %s: %d test(s) fail (%d s): %s' "caught" "$name" "$file" "$n" \
        $(( $(date +%s) - t0 )) "$(head -3 "$work/$name.failed" | paste -sd'|' - | sed 's/|/ | /g')")
    else
      survived=$((survived + 1))
      line=$(printf '%-9s %-32s %s: every test passes (%d s)' "SURVIVED" "$name" "$file" $(( $(date +%s) - t0 )))
    fi
  fi
  echo "$line" | tee -a "$report"
  cp "$backup" "$copy/$file"
  touch "$copy/$file"
  applied=
done
# Leave the build matching the unmutated sources for the next run.
cmake --build "$build" -j "$jobs" >"$work/build.log" 2>&1 || rm -rf "$build"

echo "mutate: ${#selected[@]} mutation(s): $caught caught, $survived survived, $broken did not compile ($(( $(date +%s) - start )) s in all)"
[ "$survived" -eq 0 ]
