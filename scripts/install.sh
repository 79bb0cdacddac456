#!/usr/bin/env sh
# Installs the C library the way cargo-c's `cargo cinstall` does, without
# needing cargo-c: libscatterkit.a and/or libscatterkit.so into PREFIX/lib, the
# committed header into PREFIX/include, and PREFIX/lib/pkgconfig/scatterkit.pc.
#
#   scripts/install.sh PREFIX [--static-only | --shared-only]
#
# Then: cc app.c $(PKG_CONFIG_PATH=PREFIX/lib/pkgconfig pkg-config --cflags --libs scatterkit)
# (add --static to pkg-config when linking the static library).
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
cp "$root/include/scatterkit.h" "$root/include/scatterkit_table.h" "$prefix/include/"
[ "$mode" = "--shared-only" ] || cp "$target/libscatterkit.a" "$prefix/lib/"
[ "$mode" = "--static-only" ] || cp "$target/libscatterkit.so" "$prefix/lib/"
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
echo "installed scatterkit $version into $prefix ($mode)" >&2
