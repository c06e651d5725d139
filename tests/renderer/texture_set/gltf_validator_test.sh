#!/usr/bin/env bash
# Every glTF file `nenrin bake uv --gltf` writes passes the Khronos glTF validator (npm
# gltf-validator, installed into tests/node by scripts/install-deps) with zero errors and zero
# warnings: the UV-test cube (six charts, a matte finish), the table top (oiled), a bare-finish
# piece (no coat, no anisotropy: the extensions left out), and a bake whose input mesh is itself
# a glTF (.glb), and the nineteen part sets of `nenrin furniture`'s oak chair (seventeen
# pieces, the seat glued from three boards) and the whole chair's .gltf and .glb. Usage: gltf_validator_test.sh NENRIN SOURCE_DIR (ctest label gltf).
set -euo pipefail
nenrin="$1"
src="$2"
validator="$src/tests/node/validate-gltf.mjs"
if [[ ! -d "$src/tests/node/node_modules/gltf-validator" ]]; then
  echo "FAIL: the glTF validator is not installed: run scripts/install-deps (npm ci in tests/node)"
  exit 1
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

bake() {  # SCENE OBJECT FOLDER
  mkdir -p "$3"
  "$nenrin" bake uv --scene "$1" --object "$2" --res 256 --gltf -o "$3" -q > /dev/null
}
check() {  # FILE...: zero errors and zero warnings
  local out
  out="$(node "$validator" "$@")" || { echo "$out"; echo "FAIL: validator errors"; exit 1; }
  echo "$out"
  if grep -q "[1-9][0-9]* warnings" <<< "$out"; then
    echo "FAIL: validator warnings"
    exit 1
  fi
}

bake "$src/tests/data/scenes/uv-cube.json" cube "$work/cube"
check "$work/cube/cube.gltf" "$work/cube/cube.glb"
bake "$src/scenes/table-top-mesh.json" slab "$work/slab"
check "$work/slab/slab.gltf" "$work/slab/slab.glb"
grep -q KHR_materials_clearcoat "$work/slab/slab.gltf"
grep -q KHR_materials_anisotropy "$work/slab/slab.gltf"

# Bare wood: neither extension is declared or used.
sed -e 's/"finish": "matte"/"finish": "bare"/' \
    -e "s#\"../../../scenes/#\"$src/scenes/#; s#\"../grain/#\"$src/tests/data/grain/#; s#\"../meshes/#\"$src/tests/data/meshes/#" \
    "$src/tests/data/scenes/uv-cube.json" > "$work/bare.json"
bake "$work/bare.json" cube "$work/bare"
check "$work/bare/cube.glb"
if grep -q "KHR_materials" "$work/bare/cube.gltf"; then
  echo "FAIL: a bare finish declares a material extension"
  exit 1
fi

# A glTF mesh as the bake's input: the cube's own .glb, baked again.
sed -e "s#\"file\": \"../meshes/uv-cube.obj\", \"scale\": 0.5#\"file\": \"$work/cube/cube.glb\"#" \
    -e "s#\"../../../scenes/#\"$src/scenes/#; s#\"../grain/#\"$src/tests/data/grain/#" \
    "$src/tests/data/scenes/uv-cube.json" > "$work/from-glb.json"
grep -q "cube.glb" "$work/from-glb.json"
bake "$work/from-glb.json" cube "$work/from-glb"
check "$work/from-glb/cube.gltf" "$work/from-glb/cube.glb"
# nenrin furniture: every wood part's texture set of the oak chair (charts of its own).
"$nenrin" furniture "$src/tests/data/furniture/oak-chair/oakChair.obj" --unit cm \
  --grain "$src/scenes/grain/species/european-oak.json" --res 64 --preview 32 -q \
  -o "$work/chair" > /dev/null
sets=("$work"/chair/textures/*/*.glb)
[[ ${#sets[@]} -eq 19 ]] || { echo "FAIL: ${#sets[@]} chair part sets, expected 19"; exit 1; }
check "${sets[@]}"
# The whole chair as one model, every part a node showing its set.
check "$work/chair/oakChair.gltf" "$work/chair/oakChair.glb"
echo "PASS"
