#!/usr/bin/env bash
# Writes the fuzz targets' seed corpora (scripts/fuzz.sh calls it; see the README's "Fuzzing"):
#
#   scripts/fuzz-corpus.sh <out folder> <wisp_fuzz_seeds binary>
#
# <out>/<target>/ gets: tiny hand-made files written below (one per format and variant, so the
# seeds exist without any assets), the files Wisp's own writers make (wisp_fuzz_seeds: a project,
# presets, strand files), the bundled presets, and the shared test assets (../shared/assets, or
# $WISP_SHARED_ASSETS) when that folder exists. Assets are read where they are, never copied into
# the source tree. fuzz_mesh's inputs start with a byte that picks the format (fuzz/fuzz_mesh.cpp):
# '0' OBJ, '1' PLY, '2' OFF, '3' STL.
set -euo pipefail

cd "$(dirname "$0")/.."
out=${1:?usage: scripts/fuzz-corpus.sh <out folder> <wisp_fuzz_seeds binary>}
seeds_binary=${2:?usage: scripts/fuzz-corpus.sh <out folder> <wisp_fuzz_seeds binary>}
assets=${WISP_SHARED_ASSETS:-../shared/assets}

rm -rf "$out"
mkdir -p "$out"/{mesh,gltf,hair,preset,project,params}

# Little-endian binary helpers: u32 / u16 / f32 (from a hex bit pattern) as raw bytes.
u32() { printf "$(printf '\\x%02x\\x%02x\\x%02x\\x%02x' $(($1 & 255)) $(($1 >> 8 & 255)) $(($1 >> 16 & 255)) $(($1 >> 24 & 255)))"; }
u16() { printf "$(printf '\\x%02x\\x%02x' $(($1 & 255)) $(($1 >> 8 & 255)))"; }
f32() { u32 "$1"; }  # f32 0x3e4ccccd = 0.2
# The tetrahedron (0,0,0) (0.2,0,0) (0,0.2,0) (0,0,0.2) as little-endian floats.
tetra_le() { f32 0; f32 0; f32 0; f32 0x3e4ccccd; f32 0; f32 0; f32 0; f32 0x3e4ccccd; f32 0; f32 0; f32 0; f32 0x3e4ccccd; }

# --- fuzz_mesh: selector byte + file -----------------------------------------------------------
m=$out/mesh
printf '0v 0 0 0\nv 0.2 0 0\nv 0 0.2 0\nv 0 0 0.2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$m/tetra.obj"
printf '0# quads, slashes, negative indices, groups\nmtllib none.mtl\no cube\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nvt 0 0\nvn 0 0 1\ng front\nusemtl skin\nf 5/1/1 6/1/1 7/1/1 8/1/1\nf -8 -5 -6 -7\ns 1\nf 1//1 2//1 6//1 5//1\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nl 1 2\np 3\n' > "$m/cube.obj"
printf '1ply\nformat ascii 1.0\ncomment hand-made\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1\n0.2 0 0 2\n0 0.2 0 3\n0 0 0.2 4\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$m/tetra-ascii.ply"
{ printf '1ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n'
  tetra_le; printf '\x03'; u32 0; u32 2; u32 1; printf '\x04'; u32 0; u32 1; u32 3; u32 2; } > "$m/tetra-le.ply"
{ printf '1ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n'
  for v in "0 0 0" "3fc999999999999a 0 0" "0 3fc999999999999a 0" "0 0 3fc999999999999a"; do
    for c in $v; do h=$(printf '%016x' "0x$c"); printf "$(echo "$h" | sed 's/../\\x&/g')"; done
  done
  printf '\x00\x00\x00\x06\x00\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x02\xff\xff\xff\xff\x00\x00\x00\x03\x00\x00\x00\x01'; } > "$m/strips-be.ply"
printf '2OFF\n4 4 6\n0 0 0\n0.2 0 0\n0 0.2 0\n0 0 0.2\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$m/tetra.off"
printf '2COFF\n# coloured\n4 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n4 0 1 2 3\n' > "$m/quad-colour.off"
printf '3solid tetra\n facet normal 0 0 -1\n  outer loop\n   vertex 0 0 0\n   vertex 0 0.2 0\n   vertex 0.2 0 0\n  endloop\n endfacet\n facet normal 0 -1 0\n  outer loop\n   vertex 0 0 0\n   vertex 0.2 0 0\n   vertex 0 0 0.2\n  endloop\n endfacet\nendsolid tetra\n' > "$m/tetra-ascii.stl"
{ printf '3'; printf 'binary STL, hand-made%59s' ''; u32 2
  for tri in "0 0 0  0 0 0  0 0x3e4ccccd 0  0x3e4ccccd 0 0" "0 0 0  0 0 0  0x3e4ccccd 0 0  0 0 0x3e4ccccd"; do
    for c in $tri; do f32 "$c"; done; u16 0
  done; } > "$m/two-binary.stl"

# --- fuzz_gltf: the file as it is ---------------------------------------------------------------
g=$out/gltf
# One triangle: 3 vec3 positions (36 bytes) then 3 uint16 indices (6 bytes), as a data URI.
tri_bin() { f32 0; f32 0; f32 0; f32 0x3e4ccccd; f32 0; f32 0; f32 0; f32 0x3e4ccccd; f32 0; u16 0; u16 1; u16 2; }
gltf_json() {  # $1: the buffer's "uri" member, or nothing for a GLB's BIN chunk
  printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,1,0],"children":[1]},{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,-1,0,0,0,0,1]}],'
  printf '"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4},{"attributes":{"POSITION":0},"mode":5}]}],'
  printf '"buffers":[{"byteLength":42%s}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],' "$1"
  printf '"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[0.2,0.2,0]},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]}'
}
gltf_json ",\"uri\":\"data:application/octet-stream;base64,$(tri_bin | base64 -w0)\"" > "$g/triangle.gltf"
{ json=$(gltf_json "")
  while (( ${#json} % 4 )); do json+=" "; done
  bin_len=44  # 42 bytes padded to 4
  u32 0x46546c67; u32 2; u32 $((12 + 8 + ${#json} + 8 + bin_len))
  u32 ${#json}; u32 0x4e4f534a; printf '%s' "$json"
  u32 $bin_len; u32 0x004e4942; tri_bin; printf '\x00\x00'; } > "$g/triangle.glb"

# --- fuzz_hair: the file as it is ---------------------------------------------------------------
h=$out/hair
{ u32 2; u32 2; f32 0; f32 0; f32 0; f32 0x3e4ccccd; f32 0; f32 0; u32 1; f32 0x3e4ccccd; f32 0x3e4ccccd; f32 0x3e4ccccd; } > "$h/hand-made.data"
printf 'wisp-strands 1\n# hand-made\nstrands 2 points 4\n2 0 0 0 0 0.1 0\n2 0.1 0 0 0.1 0.1 0\n' > "$h/two-strands.txt"

# --- fuzz_params --------------------------------------------------------------------------------
printf '# windy afternoon\ngravity = 9.81\nwind_speed = 12\n\n  clump_degree=0.5 # tight\n' > "$out/params/windy.txt"

# --- what Wisp's writers make, and the bundled presets --------------------------------------------
"$seeds_binary" "$out"
cp resources/presets/*.json "$out/preset/"

# --- the shared assets, when present ------------------------------------------------------------
if [ -d "$assets" ]; then
  for f in "$assets"/heads/*.obj; do [ -f "$f" ] && { printf '0'; cat "$f"; } > "$m/asset-$(basename "$f")"; done
  # The 3 MB scan is left out: libFuzzer would spend its first minute on it alone.
  for f in "$assets"/heads/*.ply "$assets"/hair/*.ply; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 2000000 ] && { printf '1'; cat "$f"; } > "$m/asset-$(basename "$f")"
  done
  find "$assets/gltf" -type f \( -name '*.gltf' -o -name '*.glb' \) | while read -r f; do
    cp "$f" "$g/asset-$(basename "$(dirname "$f")")-$(basename "$f")"
  done
  for f in "$assets"/hair/*.hair "$assets"/hair/*.data; do [ -f "$f" ] && cp "$f" "$h/asset-$(basename "$f")"; done
  echo "== fuzz seeds: hand-made, Wisp's writers and $assets"
else
  echo "== fuzz seeds: hand-made and Wisp's writers only ($assets is absent)"
fi
chmod -R u+w "$out"
for t in "$out"/*/; do echo "   $(basename "$t"): $(find "$t" -type f | wc -l) files, $(du -sk "$t" | cut -f1) KiB"; done
