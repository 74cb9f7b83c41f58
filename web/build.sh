#!/bin/sh
# The showcase for the browser: `web/build.sh [webgl2|webgpu]` builds it into target/web/BACKEND
# (index.html, showcase.js, showcase_bg.wasm, and a .br and .gz of each big file), a static folder:
#   python3 web/serve.py target/web/webgl2        then open http://127.0.0.1:8000
# (web/serve.py sends the compressed files to browsers that take them; any static server works.)
# webgl2 (the default) runs in every browser; webgpu needs a browser with WebGPU. Bevy picks its
# backend at build time; the crate's shaders pick storage buffers or textures at run time
# (`GpuLayout`). It installs what it needs when missing: the wasm32 target, wasm-bindgen-cli (the
# version in Cargo.lock, about 2 minutes once) and wasm-opt (binaryen from npm, which runs on
# Node.js; Debian's binaryen 108 is too old for wasm-bindgen's output). The first build takes
# 20-30 minutes on two cores; the profile `web` (Cargo.toml) optimises for size with LTO.
# WINDFALL_WEB_PROFILE=web-ci builds the same showcase faster and larger, without wasm-opt, npm or
# Node.js (CI's browser checks).
set -eu
profile=${WINDFALL_WEB_PROFILE:-web}
backend=${1:-webgl2}
case "$backend" in
webgl2 | webgpu) ;;
*)
    echo "usage: web/build.sh [webgl2|webgpu]" >&2
    exit 2
    ;;
esac
cd "$(dirname "$0")/.."
started=$(date +%s)
rustup target add wasm32-unknown-unknown >/dev/null
version=$(sed -n '/^name = "wasm-bindgen"$/{n;s/^version = "\(.*\)"$/\1/p;}' Cargo.lock)
[ -n "$version" ] || {
    echo "no wasm-bindgen in Cargo.lock" >&2
    exit 1
}
if ! wasm-bindgen --version 2>/dev/null | grep -q " $version\$"; then
    # Not --locked: the lock file published with 0.2.130 pins a webpki-roots release the index
    # no longer offers. Without its default TLS (the CLI downloads nothing here): 2 minutes
    # instead of 7.
    cargo install wasm-bindgen-cli --version "$version" --no-default-features
fi
# wasm-opt from binaryen 116 or later: the one on the PATH, else npm's package in target/ (only
# the size-optimised profile runs it).
wasm_opt=wasm-opt
opt_version=$(wasm-opt --version 2>/dev/null | sed -n 's/^wasm-opt version \([0-9]*\).*/\1/p')
if [ "$profile" = web ] && [ "${opt_version:-0}" -lt 116 ]; then
    tools=target/web-tools
    wasm_opt=$tools/node_modules/.bin/wasm-opt
    if [ ! -x "$wasm_opt" ]; then
        command -v npm >/dev/null || {
            echo "web/build.sh needs wasm-opt (binaryen 116 or later) or npm to install it" >&2
            exit 1
        }
        npm install --silent --no-audit --no-fund --prefix "$tools" binaryen@132
    fi
fi
# WebAssembly SIMD (simd128) for the leaves' lane step: every current browser has it.
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="${CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS:-} -C target-feature=+simd128"
features="render,egui,bevy/web,bevy/$backend"
cargo build --locked --ignore-rust-version --profile "$profile" --target wasm32-unknown-unknown --example showcase \
    --features "$features"
target=${CARGO_TARGET_DIR:-target}
out=target/web/$backend
rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --no-typescript --target web --out-dir "$out" --out-name showcase \
    "$target/wasm32-unknown-unknown/$profile/examples/showcase.wasm"
before=$(wc -c <"$out/showcase_bg.wasm")
# The features Rust's wasm32 target uses by default, and SIMD.
if [ "$profile" = web ]; then
    "$wasm_opt" -Oz --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
        --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd \
        "$out/showcase_bg.wasm" -o "$out/opt.wasm"
    mv "$out/opt.wasm" "$out/showcase_bg.wasm"
fi
bytes=$(wc -c <"$out/showcase_bg.wasm")
sed "s/__WASM_BYTES__/$bytes/" web/index.html >"$out/index.html"
# Compressed copies beside the originals: web/serve.py sends the smallest the browser takes
# (brotli by Node.js's zlib, at its best quality; gzip everywhere). Not for CI's build.
if [ "$profile" = web ]; then
    for file in showcase_bg.wasm showcase.js; do
        gzip -9 -k -f "$out/$file"
        node -e 'const z = require("zlib"), fs = require("fs"), f = process.argv[1];
            fs.writeFileSync(f + ".br", z.brotliCompressSync(fs.readFileSync(f), { params: {
                [z.constants.BROTLI_PARAM_QUALITY]: 11, [z.constants.BROTLI_PARAM_LGWIN]: 24 } }));' \
            "$out/$file"
    done
    echo "showcase_bg.wasm: $bytes bytes ($before before wasm-opt)," \
        "$(wc -c <"$out/showcase_bg.wasm.gz") gzipped, $(wc -c <"$out/showcase_bg.wasm.br") brotli"
else
    echo "showcase_bg.wasm: $bytes bytes (profile $profile)"
fi
echo "built in $(($(date +%s) - started)) s"
ls -l "$out"
