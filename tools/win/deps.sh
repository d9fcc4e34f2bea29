#!/usr/bin/env bash
# Builds banyan's C and C++ dependencies for Windows x64 with Debian's
# mingw-w64 (tools/win/mingw64.cmake), from pinned sources, into a cache
# outside the repository:
#   ${BANYAN_WIN_CACHE:-~/.cache/banyan/win}/deps-<key>/   (the prefix)
#   ${BANYAN_WIN_CACHE:-~/.cache/banyan/win}/src/          (the downloads)
# <key> hashes this script, the toolchain file and the patches, so a change
# of a pinned version (or of how it is built) builds into a new prefix;
# each dependency leaves a stamp, so an interrupted run resumes where it
# stopped. Prints the prefix on its last line.
#
# Sources: Debian 12's source packages (apt-get source with a private
# deb-src list; the machine's own apt lists are not touched), checked
# against the .dsc's SHA-256; header-only libraries (Boost, stb, tinyexr)
# from the Debian packages installed for the Linux build. SLEEF is not
# among them: its source is in the repository (third_party/sleef),
# compiled by banyan's own CMake on Linux and Windows alike.
#   JOBS   parallel jobs (default 2)
#   BANYAN_WIN_DEPS_PREFIX  build into this prefix instead (development)
#   BANYAN_WIN_DEPS_STEPS   only these steps, e.g. "cjson libdeflate" (development)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cache=${BANYAN_WIN_CACHE:-$HOME/.cache/banyan/win}
jobs=${JOBS:-2}

# The pins: Debian source package = version.
pins=(
  onetbb=2021.8.0-2+deb12u1
  embree=3.13.5+dfsg-2
  openvdb=10.0.1-2
  cjson=1.7.15-1+deb12u4
  libdeflate=1.14-1
  meshoptimizer=0.18+dfsg-2
  tinygltf=2.7.0+dfsg-2
  nlohmann-json3=3.11.2-2
)
# Built with Debian's own patches (cJSON's security fixes change what it
# parses; tinygltf's fix its build and includes). Embree's and OpenVDB's
# Debian tarballs answer 404 here: their upstream source as it is.
debian_patched=(onetbb cjson libdeflate meshoptimizer tinygltf)

key=$( (cat "$0" "$here/mingw64.cmake"; ls "$here"/patches/* 2>/dev/null | sort | xargs cat) |
      sha256sum | cut -c1-12)
prefix=${BANYAN_WIN_DEPS_PREFIX:-$cache/deps-$key}
src=$cache/src
work=$cache/build-$key
[ -n "${BANYAN_WIN_DEPS_PREFIX:-}" ] && work=$cache/build-dev
mkdir -p "$prefix" "$src" "$work"
export BANYAN_WIN_PREFIX=$prefix
log() { echo "win-deps: $*" >&2; }

# ------------------------------------------------------------- downloads
apt_opts=()
apt_ready=0
apt_setup() {
  [ $apt_ready = 1 ] && return
  local lists=$cache/apt-lists
  mkdir -p "$lists/partial"
  cat > "$cache/deb-src.sources" <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
  apt_opts=(-o "Dir::Etc::sourcelist=$cache/deb-src.sources" -o Dir::Etc::sourceparts=/dev/null
            -o "Dir::State::Lists=$lists")
  apt-get "${apt_opts[@]}" update -q >&2
  apt_ready=1
}

# A pinned source package's file whose name matches pattern (the orig
# tarball, or Debian's patches), checked against the .dsc; its path on
# stdout. Some Debian tarballs answer 404 here (Embree's, OpenVDB's); banyan's
# own patches are in tools/win/patches.
file_of() {
  local name=$1 ver=$2 pattern=$3 dsc=$src/${1}_${2}.dsc
  if [ ! -f "$dsc" ]; then
    apt_setup
    (cd "$src" && apt-get "${apt_opts[@]}" source --download-only "$name=$ver" >&2) || true
  fi
  [ -f "$dsc" ] || { log "no $dsc"; exit 1; }
  local line file sum
  line=$(sed -n '/^Checksums-Sha256:/,/^[A-Z]/p' "$dsc" | grep -E "$pattern" | grep -v '\.asc$' | head -1)
  sum=$(echo "$line" | awk '{print $1}')
  file=$(echo "$line" | awk '{print $3}')
  [ -f "$src/$file" ] || { log "no $src/$file"; exit 1; }
  echo "$sum  $src/$file" | sha256sum -c --quiet - >&2 || { log "$file: checksum differs from $dsc"; exit 1; }
  echo "$src/$file"
}

pin() { local p; for p in "${pins[@]}"; do [ "${p%%=*}" = "$1" ] && { echo "${p#*=}"; return; }; done; exit 1; }

# Unpacks a pinned package's upstream source into $work/<name> (once).
unpack() {
  local name=$1 dir=$work/$1
  if [ ! -d "$dir" ]; then
    local tar
    tar=$(file_of "$name" "$(pin "$name")" '\.orig\.tar\.')
    mkdir -p "$dir.tmp"
    tar xf "$tar" -C "$dir.tmp" --strip-components=1
    if [[ " ${debian_patched[*]} " == *" $name "* ]]; then # Debian's patches, as the Linux build has them
      tar xf "$(file_of "$name" "$(pin "$name")" '\.debian\.tar\.')" -C "$dir.tmp"
      local p
      for p in $(cat "$dir.tmp/debian/patches/series"); do patch -s -d "$dir.tmp" -p1 < "$dir.tmp/debian/patches/$p"; done
    fi
    if [ -f "$here/patches/$name.patch" ]; then patch -s -d "$dir.tmp" -p1 < "$here/patches/$name.patch"; fi
    # windres reads no UTF-16: Embree's resource script in UTF-8.
    if [ "$name" = embree ]; then
      iconv -f UTF-16 -t UTF-8 "$dir.tmp/kernels/embree.rc" | sed '1s/^\xEF\xBB\xBF//' > "$dir.tmp/kernels/embree.rc.u8"
      mv "$dir.tmp/kernels/embree.rc.u8" "$dir.tmp/kernels/embree.rc"
      touch "$dir.tmp/readme.pdf" # installed with the library, left out of Debian's tarball
    fi
    mv "$dir.tmp" "$dir"
  fi
  echo "$dir"
}

cmake_dep() { # name source-dir cmake-args...
  local name=$1 dir=$2
  shift 2
  cmake -S "$dir" -B "$work/b-$name" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$here/mingw64.cmake" \
        -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" "$@" >&2
  cmake --build "$work/b-$name" -j "$jobs" >&2
  cmake --install "$work/b-$name" >&2
}

step() { # name function: runs it once, timed
  local name=$1 t0
  [ -f "$prefix/.done-$name" ] && return
  [ -n "${BANYAN_WIN_DEPS_STEPS:-}" ] && [[ " $BANYAN_WIN_DEPS_STEPS " != *" $name "* ]] && return
  t0=$(date +%s)
  log "building $name"
  "$2"
  echo "$(( $(date +%s) - t0 ))" > "$prefix/.done-$name"
  log "$name took $(cat "$prefix/.done-$name") s"
}

# ---------------------------------------------------------- dependencies
tbb() {
  cmake_dep tbb "$(unpack onetbb)" -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF -DTBB_ENABLE_IPO=OFF
}

# Embree 3.13.5 with the SSE2 and SSE4.2 kernels: GCC cannot align stack
# variables past 16 bytes on Win64 (GCC bug 54412), so its AVX kernels
# would fault on aligned spills. The patch lets Embree's build take GCC
# on Windows for what it is (it took it for MSVC) and drops its ELF-only
# linker flags (-z relro) there. banyan's hosts are user geometry
# (csrc/hosts/hosts.c) asked by rays and point queries, so Embree's own
# primitive kernels (triangles, quads, curves, grids, points, subdivision,
# instances) are left out: a tenth of the build time, the same bytes.
embree() {
  cmake_dep embree "$(unpack embree)" -DEMBREE_TUTORIALS=OFF -DEMBREE_ISPC_SUPPORT=OFF -DEMBREE_TASKING_SYSTEM=TBB \
    -DTBB_DIR="$prefix/lib/cmake/TBB" -DEMBREE_MAX_ISA=NONE -DEMBREE_ISA_SSE2=ON -DEMBREE_ISA_SSE42=ON \
    -DEMBREE_ISA_AVX=OFF -DEMBREE_ISA_AVX2=OFF -DEMBREE_ISA_AVX512=OFF -DEMBREE_STATIC_LIB=OFF -DEMBREE_ZIP_MODE=OFF \
    -DEMBREE_GEOMETRY_TRIANGLE=OFF -DEMBREE_GEOMETRY_QUAD=OFF -DEMBREE_GEOMETRY_CURVE=OFF -DEMBREE_GEOMETRY_GRID=OFF \
    -DEMBREE_GEOMETRY_POINT=OFF -DEMBREE_GEOMETRY_SUBDIVISION=OFF -DEMBREE_GEOMETRY_INSTANCE=OFF
}

cjson() {
  cmake_dep cjson "$(unpack cjson)" -DENABLE_CJSON_TEST=OFF -DENABLE_CJSON_UTILS=OFF -DBUILD_SHARED_LIBS=OFF \
    -DBUILD_SHARED_AND_STATIC_LIBS=OFF -DENABLE_CUSTOM_COMPILER_FLAGS=OFF
}

# libdeflate 1.14 has only a Makefile (its mingw static library is named
# libdeflatestatic.lib); installed with a pkg-config file as on Linux.
libdeflate() {
  local dir
  dir=$(unpack libdeflate)
  make -C "$dir" -j "$jobs" CC=x86_64-w64-mingw32-gcc-posix AR=x86_64-w64-mingw32-gcc-ar-posix libdeflatestatic.lib >&2
  mkdir -p "$prefix/lib/pkgconfig" "$prefix/include"
  cp "$dir/libdeflatestatic.lib" "$prefix/lib/libdeflate.a"
  cp "$dir/libdeflate.h" "$prefix/include/"
  printf 'prefix=%s\nName: libdeflate\nDescription: deflate\nVersion: 1.14\nLibs: -L${prefix}/lib -ldeflate\nCflags: -I${prefix}/include\n' \
    "$prefix" > "$prefix/lib/pkgconfig/libdeflate.pc"
}

meshoptimizer() {
  cmake_dep meshoptimizer "$(unpack meshoptimizer)" -DMESHOPT_BUILD_SHARED_LIBS=OFF
}

# tinygltf as Debian builds it (nlohmann json; stb_image and
# stb_image_write from a static libstb, as Debian's libstb), static here.
tinygltf() {
  cmake_dep nlohmann-json3 "$(unpack nlohmann-json3)" -DJSON_BuildTests=OFF -DJSON_Install=ON
  mkdir -p "$work/stb" "$prefix/include/stb"
  cp /usr/include/stb/stb_image.h /usr/include/stb/stb_image_write.h "$prefix/include/stb/"
  printf '#define STB_IMAGE_IMPLEMENTATION\n#include <stb_image.h>\n#define STB_IMAGE_WRITE_IMPLEMENTATION\n#include <stb_image_write.h>\n' \
    > "$work/stb/stb.c"
  x86_64-w64-mingw32-gcc-posix -O2 -I"$prefix/include/stb" -c "$work/stb/stb.c" -o "$work/stb/stb.o"
  rm -f "$prefix/lib/libstb.a"
  x86_64-w64-mingw32-gcc-ar-posix rcs "$prefix/lib/libstb.a" "$work/stb/stb.o"
  cmake_dep tinygltf "$(unpack tinygltf)" -DBUILD_SHARED_LIBS=OFF -DBUILD_TESTING=OFF \
    -DTINYGLTF_BUILD_LOADER_EXAMPLE=OFF -DTINYGLTF_BUILD_GL_EXAMPLES=OFF -DTINYGLTF_BUILD_VALIDATOR_EXAMPLE=OFF \
    -Dstb_INCLUDE_DIRS="$prefix/include/stb" -Dstb_LIBRARY="$prefix/lib/libstb.a"
  # Static: its users link nlohmann_json's target too (header-only).
  local cfg=$prefix/lib/cmake/TinyGLTF/TinyGLTFConfig.cmake
  grep -q find_dependency "$cfg" ||
    { printf 'include(CMakeFindDependencyMacro)\nfind_dependency(nlohmann_json 3)\n'; cat "$cfg"; } > "$cfg.new"
  [ -f "$cfg.new" ] && mv "$cfg.new" "$cfg"
  return 0
}

# OpenVDB 10.0.1, the core library alone: no file I/O codecs (Blosc,
# zlib; the fused roots surface never reads or writes .vdb files), no
# delayed loading (Boost.Iostreams), OpenVDB's own half type; Boost's
# headers from the installed libboost-dev.
# Of its library sources, only those banyan_vdb.dll's imports need (the
# grid, its metadata and transform, the stream code that FloatGrid's
# virtual I/O methods reference) and what they in turn reference; the
# patch (tools/win/patches/openvdb.patch) takes the list. Left out:
# openvdb.cc and points/points.cc (initialize() and its registration of
# every grid type, which the shim never calls; most of the full library's
# build time), the point attributes, io::Stream, io::Queue, TempFile,
# Proximity and Platform.cc. The headers are installed whole, and the
# mesher and level set code is header templates compiled into the shim,
# so its output is the full library's. A shim needing a left-out source
# fails to link banyan_vdb.dll (an undefined reference).
openvdb_sources=(Grid.cc MetaMap.cc Metadata.cc io/Archive.cc io/Compression.cc io/DelayedLoadMetadata.cc io/File.cc
                 io/GridDescriptor.cc math/Half.cc math/Maps.cc math/QuantizedUnitVec.cc math/Transform.cc
                 points/StreamCompression.cc util/Formats.cc util/Util.cc)
openvdb() {
  mkdir -p "$prefix/boost-include"
  ln -sfn /usr/include/boost "$prefix/boost-include/boost"
  local dir
  dir=$(unpack openvdb)
  # A source tree unpacked before the patch existed (the shared build-dev
  # of BANYAN_WIN_DEPS_PREFIX) would build the whole library.
  grep -q OPENVDB_LIBRARY_SOURCE_SUBSET "$dir/openvdb/openvdb/CMakeLists.txt" ||
    { log "$dir lacks tools/win/patches/openvdb.patch: remove it to unpack again"; exit 1; }
  cmake_dep openvdb "$dir" -DOPENVDB_BUILD_BINARIES=OFF -DOPENVDB_CORE_STATIC=OFF \
    "-DOPENVDB_LIBRARY_SOURCE_SUBSET=$(IFS=';'; echo "${openvdb_sources[*]}")" \
    -DOPENVDB_USE_DELAYED_LOADING=OFF -DUSE_BLOSC=OFF -DUSE_ZLIB=OFF -DUSE_IMATH_HALF=OFF -DUSE_EXR=OFF -DUSE_PNG=OFF \
    -DUSE_EXPLICIT_INSTANTIATION=OFF -DUSE_CCACHE=OFF -DTBB_ROOT="$prefix" -DTbb_INCLUDE_DIR="$prefix/include" \
    -DOPENVDB_DISABLE_BOOST_IMPLICIT_LINKING=OFF -DDISABLE_DEPENDENCY_VERSION_CHECKS=ON -DOPENVDB_ENABLE_RPATH=OFF \
    "-DCMAKE_CXX_FLAGS=-isystem $prefix/boost-include -Wa,-mbig-obj"
}

# tinyexr: header-only (its implementation is compiled into banyan's
# csrc/pp2/exr_half.cpp), from the installed libtinyexr-dev.
tinyexr() {
  mkdir -p "$prefix/include"
  cp /usr/include/tinyexr.h "$prefix/include/"
}

# The mingw runtime DLLs the libraries import, beside them.
runtime() {
  local d
  for d in libstdc++-6.dll libgcc_s_seh-1.dll; do
    cp "$(x86_64-w64-mingw32-g++-posix -print-file-name=$d)" "$prefix/bin/"
  done
  cp /usr/x86_64-w64-mingw32/lib/libwinpthread-1.dll "$prefix/bin/"
}

step tbb tbb
step embree embree
step cjson cjson
step libdeflate libdeflate
step meshoptimizer meshoptimizer
step tinygltf tinygltf
step tinyexr tinyexr
step runtime runtime
step openvdb openvdb
echo "$prefix"
