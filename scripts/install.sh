#!/usr/bin/env sh
# Installs the C library the way cargo-c's `cargo cinstall` does, without
# needing cargo-c: libscatterkit.a and/or the shared library into PREFIX/lib
# (libscatterkit.so.MAJOR.MINOR, its SONAME, with the libscatterkit.so link
# beside it), every header into PREFIX/include (scatterkit.h,
# scatterkit_inline.h, scatterkit_table.h and the header-only
# scatterkit_portable.h), pkg-config files in PREFIX/lib/pkgconfig
# (scatterkit.pc links the shared library where it is installed, else the
# static one; scatterkit-static.pc always the static one, by its path;
# scatterkit-portable.pc the header-only tier, no library) and a CMake
# package in PREFIX/lib/cmake/scatterkit (find_package(scatterkit CONFIG)
# gives the imported targets scatterkit::scatterkit, the library, and
# scatterkit::portable, the headers alone).
#
#   scripts/install.sh PREFIX [--static-only | --shared-only]
#
# Then, with PKG_CONFIG_PATH=PREFIX/lib/pkgconfig:
#   cc app.c $(pkg-config --cflags --libs scatterkit) -Wl,-rpath,PREFIX/lib   # shared
#   cc app.c $(pkg-config --cflags --libs scatterkit-static)                  # static
#   cc kernel_host.c $(pkg-config --cflags scatterkit-portable)               # header only
set -eu
prefix=${1:?usage: scripts/install.sh PREFIX [--static-only | --shared-only]}
mode=${2:-both}
root=$(cd "$(dirname "$0")/.." && pwd)
cargo=${CARGO:-cargo}
"$cargo" build --release -p scatterkit-capi --manifest-path "$root/Cargo.toml" >&2
target=${CARGO_TARGET_DIR:-$root/target}/release
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$root/Cargo.toml" | head -n 1)
# The native libraries a static link needs (`--print native-static-libs`).
native="-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"
mkdir -p "$prefix/lib/pkgconfig" "$prefix/include"
cp "$root/include/scatterkit.h" "$root/include/scatterkit_table.h" "$root/include/scatterkit_inline.h" \
  "$root/include/scatterkit_portable.h" "$prefix/include/"
if [ "$mode" != "--shared-only" ]; then
  cp "$target/libscatterkit.a" "$prefix/lib/"
  # Rust's compiler-builtins puts weak, hidden copies of C math functions
  # (cbrt, fma, fmax, floor, sqrt, ...) in every static library it builds.
  # A linker that reaches the archive before -lm gives the program those
  # instead of the C library's, changing the user's own results
  # (rust-lang/rust#142119). Made local in the installed copy, they answer
  # no call from outside their own member: the program's calls reach the
  # C library's (-lm is among the libraries a static link needs).
  archive="$prefix/lib/libscatterkit.a"
  if command -v readelf >/dev/null 2>&1 && command -v objcopy >/dev/null 2>&1; then
    names=$(mktemp)
    readelf -s --wide "$archive" 2>/dev/null |
      awk '$4 == "FUNC" && $5 == "WEAK" && $6 == "HIDDEN" && $7 != "UND" && $8 !~ /^_/ { print $8 }' |
      sort -u >"$names"
    status=0
    objcopy --localize-symbols="$names" "$archive" || status=$?
    rm -f "$names"
    [ "$status" -eq 0 ] || exit "$status"
  else
    echo "install.sh: no readelf/objcopy: link -lm before libscatterkit.a," \
      "or the program may get Rust's copies of cbrt, fma, fmax, ..." >&2
  fi
fi
soname=libscatterkit.so.$(echo "$version" | cut -d. -f1-2)
if [ "$mode" != "--static-only" ]; then
  cp "$target/libscatterkit.so" "$prefix/lib/$soname"
  ln -sf "$soname" "$prefix/lib/libscatterkit.so"
fi
cat > "$prefix/lib/pkgconfig/scatterkit.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: scatterkit
Description: Light-scattering samplers for Monte Carlo light transport
Version: $version
Libs: -L\${libdir} -lscatterkit
Libs.private: $native
Cflags: -I\${includedir}
PC
# The portable tier: headers alone (C, C++, CUDA, HIP and OpenCL C kernels).
cat > "$prefix/lib/pkgconfig/scatterkit-portable.pc" <<PC
prefix=$prefix
includedir=\${prefix}/include

Name: scatterkit-portable
Description: Light-scattering samplers for Monte Carlo light transport (header-only float tier)
Version: $version
Cflags: -I\${includedir}
PC
# The static library by its path, so that no shared library beside it is
# picked instead.
if [ "$mode" != "--shared-only" ]; then
  cat > "$prefix/lib/pkgconfig/scatterkit-static.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: scatterkit-static
Description: Light-scattering samplers for Monte Carlo light transport (static library)
Version: $version
Libs: \${libdir}/libscatterkit.a $native
Cflags: -I\${includedir}
PC
fi
# CMake: an imported target for the shared library if installed, else the
# static one (with the native libraries a static link needs).
mkdir -p "$prefix/lib/cmake/scatterkit"
if [ "$mode" = "--static-only" ]; then
  kind=STATIC; lib='libscatterkit.a'; links="$(echo "$native" | sed 's/-l//g; s/ /;/g')"
else
  kind=SHARED; lib=$soname; links=''
fi
cat > "$prefix/lib/cmake/scatterkit/scatterkitConfig.cmake" <<CM
# scatterkit $version: find_package(scatterkit CONFIG) gives scatterkit::scatterkit.
get_filename_component(_sk_prefix "\${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
if(NOT TARGET scatterkit::scatterkit)
  add_library(scatterkit::scatterkit $kind IMPORTED)
  set_target_properties(scatterkit::scatterkit PROPERTIES
    IMPORTED_LOCATION "\${_sk_prefix}/lib/$lib"
    INTERFACE_INCLUDE_DIRECTORIES "\${_sk_prefix}/include"
    INTERFACE_LINK_LIBRARIES "$links")
endif()
# The header-only tier (scatterkit_portable.h): include directories alone.
if(NOT TARGET scatterkit::portable)
  add_library(scatterkit::portable INTERFACE IMPORTED)
  set_target_properties(scatterkit::portable PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "\${_sk_prefix}/include")
endif()
unset(_sk_prefix)
CM
cat > "$prefix/lib/cmake/scatterkit/scatterkitConfigVersion.cmake" <<CM
set(PACKAGE_VERSION "$version")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE FALSE)
else()
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
endif()
CM
echo "installed scatterkit $version into $prefix ($mode)" >&2
