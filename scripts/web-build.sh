#!/usr/bin/env bash
# The WebAssembly build of the decoder (issue 17): zstd's decompressor and
# Draco's decoder compiled from Debian's own source packages, then the same
# format + decoder sources as the native build plus the C ABI glue in
# web/src/, compiled with and without WebAssembly SIMD (dbss_wasm.*,
# dbss_wasm_scalar.*), each linked twice: an ES module for browsers
# (build-web/dist/) and a node build for the tests (build-web/node/).  Also checks that the decoder
# compiles with emscripten's libc++ (em++ -fsyntax-only) and installs the
# npm packages of web/package-lock.json.  Nothing here is committed; the
# sources and libraries are kept in build-web/ (gitignored) between runs.
#
#   bash scripts/web-build.sh [OUT_DIR]     default build-web
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=${1:-build-web}
mkdir -p "$out"
out=$(cd "$out" && pwd)
# One build per output folder at a time: two at once leave a JS glue file
# that does not match its wasm (the module then fails to load with a
# LinkError).  A second run waits for the first.
exec 9>"$out/.web-build.lock"
flock 9
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/install-deps.sh web
t0=$SECONDS
phase() { echo "web-build: $1 ($((SECONDS - t0)) s so far)"; }

# --- Debian source packages of zstd and Draco -------------------------------
# A private apt configuration with deb-src entries for the configured Debian
# mirror, so the machine's own apt sources stay untouched.  Only the main
# suite: the security mirror does not keep every source it once published.
src=$out/src
apt_dir=$out/apt
fetch_sources() {
  mkdir -p "$apt_dir/parts" "$apt_dir/lists/partial" "$apt_dir/cache" "$src"
  local uri="" suite=""
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    uri=$(sed -n 's/^URIs:[[:space:]]*//p' /etc/apt/sources.list.d/debian.sources | head -1 | awk '{print $1}')
    suite=$(sed -n 's/^Suites:[[:space:]]*//p' /etc/apt/sources.list.d/debian.sources | head -1 | awk '{print $1}')
  fi
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    read -r uri suite < <(awk '$1 == "deb" && $0 !~ /security/ { i = 2; if ($2 ~ /^\[/) i = 3; print $i, $(i + 1); exit }' /etc/apt/sources.list)
  fi
  uri=${uri:-http://deb.debian.org/debian}
  suite=${suite:-bookworm}
  printf 'Types: deb-src\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    "$uri" "$suite" > "$apt_dir/parts/debian-src.sources"
  : > "$apt_dir/empty.list"
  local apt_opts=(-o "Dir::Etc::SourceList=$apt_dir/empty.list" -o "Dir::Etc::SourceParts=$apt_dir/parts"
    -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o "APT::Sandbox::User=root")
  echo "web-build: fetching the zstd and Draco source packages from $uri $suite"
  apt-get "${apt_opts[@]}" update -qq
  (cd "$src" && apt-get "${apt_opts[@]}" source -qq --download-only libzstd draco)
  rm -rf "$src/zstd" "$src/draco"
  (cd "$src" && dpkg-source -x libzstd_*.dsc zstd >/dev/null 2>&1 && dpkg-source -x draco_*.dsc draco >/dev/null 2>&1)
}
[ -f "$src/zstd/lib/zstd.h" ] && [ -f "$src/draco/CMakeLists.txt" ] || { fetch_sources; phase "sources fetched"; }

export NODE_PATH=/usr/share/nodejs  # em++'s own JavaScript tools
cflags=(-O3 -ffp-contract=off -fno-fast-math)

# Runs "$@" in the background, at most $jobs at once; wait_all fails when any did.
pids=()
spawn() {
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 0.05; done
  "$@" &
  pids+=($!)
}
wait_all() {
  local failed=0
  for p in "${pids[@]}"; do wait "$p" || failed=1; done
  pids=()
  [ "$failed" -eq 0 ] || { echo "web-build: a compile failed" >&2; exit 1; }
}

# --- zstd: decompression and the common files only ---------------------------
zlib=$out/lib/libzstd_dec.a
if [ ! -f "$zlib" ]; then
  echo "web-build: zstd (decompress + common) for wasm"
  mkdir -p "$out/obj/zstd" "$out/lib"
  objs=()
  for f in "$src"/zstd/lib/common/{entropy_common,error_private,fse_decompress,zstd_common,xxhash}.c \
           "$src"/zstd/lib/decompress/{huf_decompress,zstd_ddict,zstd_decompress,zstd_decompress_block}.c; do
    o=$out/obj/zstd/$(basename "${f%.c}").o
    spawn emcc "${cflags[@]}" -DZSTD_DISABLE_ASM -DZSTD_LEGACY_SUPPORT=0 -DDEBUGLEVEL=0 -c "$f" -o "$o"
    objs+=("$o")
  done
  wait_all
  emar rcs "$zlib.tmp" "${objs[@]}" && mv "$zlib.tmp" "$zlib"
  phase "zstd built"
fi

# --- Draco: the decoder's object libraries only -------------------------------
dlib=$out/lib/libdraco_dec.a
if [ ! -f "$dlib" ]; then
  echo "web-build: Draco decoder for wasm"
  EMSCRIPTEN=/usr/share/emscripten emcmake cmake -S "$src/draco" -B "$out/draco" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DDRACO_JS_GLUE=OFF -DDRACO_TESTS=OFF -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_CXX_FLAGS="-ffp-contract=off" >/dev/null
  draco_targets=(draco_attributes draco_compression_attributes_dec draco_compression_attributes_pred_schemes_dec
    draco_compression_bit_coders draco_dec_config draco_compression_decode draco_compression_entropy
    draco_compression_mesh_traverser draco_compression_mesh_dec draco_compression_options
    draco_compression_point_cloud_dec draco_core draco_mesh draco_metadata_dec draco_metadata
    draco_point_cloud draco_points_dec)
  cmake --build "$out/draco" -j "$jobs" --target "${draco_targets[@]}"
  mapfile -t dobjs < <(for t in "${draco_targets[@]}"; do [ -d "$out/draco/CMakeFiles/$t.dir" ] && find "$out/draco/CMakeFiles/$t.dir" -name '*.o'; done; true)
  emar rcs "$dlib.tmp" "${dobjs[@]}" && mv "$dlib.tmp" "$dlib"
  phase "Draco built"
fi

# --- dbss: the native build's format + decoder sources, and the glue ----------
mapfile -t dbss_sources < <(
  sed -n 's/^ *\(src\/[a-z_0-9]*\.cpp\).*/format\/\1/p' format/CMakeLists.txt
  sed -n 's/^ *\(src\/[a-z_0-9]*\.cpp\).*/decoder\/\1/p' decoder/CMakeLists.txt)
[ "${#dbss_sources[@]}" -ge 10 ] || { echo "web-build: could not read the source lists of format/ and decoder/" >&2; exit 1; }
includes=(-Iformat/include -Idecoder/include -isystem "$src/zstd/lib" -isystem "$src/draco/src" -isystem "$out/draco")
cxxflags=(-std=c++20 "${cflags[@]}" -Wall -Wextra -Werror -fno-math-errno)

# The decoder stays within emscripten 3.1.6's libc++ 13 (no std::ranges
# algorithms, std::format, std::bit_cast ...): a syntax check of every file.
echo "web-build: em++ -fsyntax-only over format/ and decoder/"
# Two calls of several files each: em++'s start-up costs more than a file.
half=$(( (${#dbss_sources[@]} + 1) / 2 ))
spawn em++ "${cxxflags[@]}" "${includes[@]}" -fsyntax-only "${dbss_sources[@]:0:$half}"
spawn em++ "${cxxflags[@]}" "${includes[@]}" -fsyntax-only "${dbss_sources[@]:$half}"
wait_all
phase "syntax check passed"

# Two modules from the same sources: with WebAssembly SIMD (-msimd128; the
# decoder then runs Kernels::paired, two edges per f64x2 vector, the same
# bits, 11-22% faster per level) as dbss_wasm.*, and without it as
# dbss_wasm_scalar.*, for browsers that lack SIMD (Chrome < 91, Firefox < 89,
# Safari < 16.4): loadModule() picks one by probing the engine.
exports=$(sed -n 's/^[a-zA-Z].* \**\(dbss_[a-z_0-9]*\)(.*/_\1/p' web/src/dbss_wasm.cpp | paste -sd, -)
mkdir -p "$out/dist" "$out/node"
# build_module NAME [FLAGS...]: compiles into obj/NAME, links dist/NAME.mjs
# (+ .wasm) and node/NAME.cjs (+ .wasm).
build_module() {
  local name=$1
  shift
  local obj=$out/obj/${name/dbss_wasm/dbss}  # obj/dbss, obj/dbss_scalar
  mkdir -p "$obj"
  # Objects built with other flags are rebuilt.
  local flags="${cxxflags[*]} $*"
  [ "$(cat "$obj/flags" 2>/dev/null)" = "$flags" ] || rm -f "$obj"/*.o
  echo "$flags" > "$obj/flags"
  local objs=() f o
  for f in "${dbss_sources[@]}" web/src/dbss_wasm.cpp; do
    o=$obj/$(echo "${f%.cpp}" | tr / _).o
    objs+=("$o")
    if [ ! -f "$o" ] || [ "$f" -nt "$o" ] || [ -n "$(find format/include decoder/include decoder/src format/src -newer "$o" -print -quit)" ]; then
      spawn em++ "${cxxflags[@]}" "$@" "${includes[@]}" -c "$f" -o "$o"
    fi
  done
  wait_all
  # emmalloc: 3 KB less gzipped than dlmalloc, and no slower here (the
  # decoder's large arrays are few and reused).
  local link=(-O3 "${objs[@]}" "$dlib" "$zlib" -sEXPORTED_FUNCTIONS="$exports,_malloc,_free"
    -sEXPORTED_RUNTIME_METHODS=UTF8ToString -sALLOW_MEMORY_GROWTH=1 -sMODULARIZE=1 -sEXPORT_NAME=createDbssModule
    -sFILESYSTEM=0 -sMALLOC=emmalloc ${DBSS_WASM_LINK_FLAGS:-})
  # Web: an ES module (also loads in a module worker).
  spawn em++ "${link[@]}" -sEXPORT_ES6=1 -sENVIRONMENT=web,worker -o "$out/dist/$name.mjs"
  # Node: CommonJS (3.1.6's ES6 output calls require()), compiled
  # synchronously (node 20 cannot await the asynchronous compilation here).
  spawn em++ "${link[@]}" -sENVIRONMENT=node -sWASM_ASYNC_COMPILATION=0 -o "$out/node/$name.cjs"
  wait_all
  echo "web-build: $name: $(stat -c %s "$out/dist/$name.wasm") bytes of wasm ($(gzip -9c "$out/dist/$name.wasm" | wc -c) gzipped)"
}
echo "web-build: dbss format + decoder for wasm, with SIMD"
build_module dbss_wasm -msimd128
echo "web-build: dbss format + decoder for wasm, without SIMD"
build_module dbss_wasm_scalar
phase "dbss linked"

# --- npm packages (three.js, playwright-core, draco3d) ------------------------
if [ -f web/package-lock.json ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
echo "web-build: done in $((SECONDS - t0)) s: $out/dist (web), $out/node (node)"
