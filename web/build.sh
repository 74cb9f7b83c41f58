#!/bin/sh
# The showcase for the browser: `web/build.sh [webgl2|webgpu]` builds it into target/web/BACKEND
# (index.html, showcase.js, showcase_bg.wasm), a static folder any file server can serve:
#   python3 -m http.server -d target/web/webgl2 8000    then open http://127.0.0.1:8000
# webgl2 (the default) runs in every browser; webgpu needs a browser with WebGPU. Bevy picks its
# backend at build time; the crate's shaders pick storage buffers or textures at run time
# (`GpuLayout`). It installs what it needs when missing: the wasm32 target and wasm-bindgen-cli
# (the version in Cargo.lock); wasm-opt (binaryen 116 or later) shrinks the result when it is on
# the PATH.
set -eu
backend=${1:-webgl2}
case "$backend" in
webgl2 | webgpu) ;;
*)
    echo "usage: web/build.sh [webgl2|webgpu]" >&2
    exit 2
    ;;
esac
cd "$(dirname "$0")/.."
rustup target add wasm32-unknown-unknown >/dev/null
version=$(sed -n '/^name = "wasm-bindgen"$/{n;s/^version = "\(.*\)"$/\1/p;}' Cargo.lock)
[ -n "$version" ] || {
    echo "no wasm-bindgen in Cargo.lock" >&2
    exit 1
}
if ! wasm-bindgen --version 2>/dev/null | grep -q " $version\$"; then
    # Not --locked: the lock file published with 0.2.130 pins a webpki-roots release the index
    # no longer offers.
    cargo install wasm-bindgen-cli --version "$version"
fi
features="render,egui,bevy/web,bevy/$backend"
cargo build --locked --profile web --target wasm32-unknown-unknown --example showcase \
    --features "$features"
target=${CARGO_TARGET_DIR:-target}
out=target/web/$backend
rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --no-typescript --target web --out-dir "$out" --out-name showcase \
    "$target/wasm32-unknown-unknown/web/examples/showcase.wasm"
# wasm-opt before binaryen 116 breaks wasm-bindgen's reference-typed function table.
opt_version=$(wasm-opt --version 2>/dev/null | sed -n 's/^wasm-opt version \([0-9]*\).*/\1/p')
if [ "${opt_version:-0}" -ge 116 ]; then
    before=$(wc -c <"$out/showcase_bg.wasm")
    if wasm-opt -Os --all-features "$out/showcase_bg.wasm" -o "$out/opt.wasm"; then
        mv "$out/opt.wasm" "$out/showcase_bg.wasm"
        echo "wasm-opt: $before -> $(wc -c <"$out/showcase_bg.wasm") bytes"
    else
        rm -f "$out/opt.wasm"
        echo "wasm-opt failed: the wasm is left as wasm-bindgen wrote it"
    fi
fi
cp web/index.html "$out/"
ls -l "$out"
