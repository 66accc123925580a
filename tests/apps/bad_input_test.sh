#!/usr/bin/env bash
# The bad-input table of docs/reliability.md, one row per case: each must end in one line on
# stderr naming the problem, exit 2, and no output file (nothing in $T/out). With
# BAD_INPUT_TABLE=FILE the rows are also written to FILE as the markdown table the doc shows.
source "$(dirname "$0")/cli_lib.sh"
TABLE=${BAD_INPUT_TABLE:-}
rows=""
O="$T/out"
# row "INPUT" WORD -- ARGS...: expect 2 WORD, and record the row.
row() {
  local input=$1 word=$2; shift 2
  expect 2 "$word" "$@"
  shift
  local said; said=$(head -c 300 "$T/stderr" | sed "s|$T/||g; s/|/\\\\|/g")
  rows+="| $input | \`uwgrasp ${*//$T\//}\` | $said | $last_code |"$'\n'
}

pcd_head() {  # pcd_head FIELDS WIDTH HEIGHT POINTS DATA
  local n; n=$(wc -w <<<"$1")
  printf 'VERSION .7\nFIELDS %s\nSIZE%s\nTYPE%s\nCOUNT%s\nWIDTH %s\nHEIGHT %s\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %s\nDATA %s\n' \
    "$1" "$(printf ' 4%.0s' $(seq "$n"))" "$(printf ' F%.0s' $(seq "$n"))" "$(printf ' 1%.0s' $(seq "$n"))" "$2" "$3" "$4" "$5"
}
ascii_cloud() {  # ascii_cloud FILE "x y z" lines...
  local f=$1; shift
  { pcd_head "x y z" "$#" 1 "$#" ascii; printf '%s\n' "$@"; } >"$f"
}

# A simulated frame: its truth, depth and colour images are the valid half of some rows.
"$BIN" simulate --scene barbell --out "$T/sim" >/dev/null 2>&1 || bad "simulate for the evaluate and output rows"

# ---- cloud files
: >"$T/empty.pcd"
mkdir -p "$T/dir.pcd"
{ pcd_head "x y z" 100 1 100 binary; head -c 64 /dev/zero; } >"$T/truncated.pcd"
{ pcd_head "x y z" 100 1 100 binary_compressed; printf '\x40\x00\x00\x00\xb0\x04\x00\x00'; head -c 16 /dev/zero; } >"$T/truncated_lzf.pcd"
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 1\n' >"$T/ply_named.pcd"
printf '\x89PNG\r\n\x1a\n0000000000000000' >"$T/png_named.pcd"
{ pcd_head "x y z" 4294967295 1 4294967295 binary; head -c 12 /dev/zero; } >"$T/absurd.pcd"
{ pcd_head "x y z" 65536 65536 4294967296 ascii; echo "0 0 1"; } >"$T/absurd_points.pcd"
{ printf 'VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n0 0 1\n'; } >"$T/no_points_line.pcd"
{ pcd_head "a b c" 1 1 1 ascii; echo "0 0 1"; } >"$T/noxyz.pcd"
ascii_cloud "$T/nan.pcd" "nan nan nan" "nan nan nan" "nan nan nan"
ascii_cloud "$T/inf.pcd" "inf 0 1" "0 -inf 1" "0 0 inf"
ascii_cloud "$T/one.pcd" "0.1 0.2 1.5"
ascii_cloud "$T/collinear.pcd" "0 0 1" "0.1 0 1" "0.2 0 1"
ascii_cloud "$T/huge.pcd" "1e30 1e30 1e30" "-1e30 2e30 1e30" "1e30 0 -1e30" "0 0 1e30"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0000' >"$T/truncated.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n' >"$T/noend.ply"
printf '0 0 1\n' >"$T/cloud.xyz"

row "missing file" "no such file" -- detect "$T/missing.pcd" --json "$O/g.json"
row "empty file" "empty" -- detect "$T/empty.pcd" --json "$O/g.json"
row "a directory instead of a file" "directory" -- detect "$T/dir.pcd" --json "$O/g.json"
row "binary PCD cut short" "truncated" -- detect "$T/truncated.pcd" --json "$O/g.json"
row "binary_compressed PCD cut short" "truncated.pcd\|truncated_lzf" -- detect "$T/truncated_lzf.pcd" --json "$O/g.json"
row "a PLY file named .pcd" "malformed" -- detect "$T/ply_named.pcd" --json "$O/g.json"
row "a PNG named .pcd (wrong magic)" "malformed" -- detect "$T/png_named.pcd" --json "$O/g.json"
row "4294967295 points declared, 12 bytes of data" "absurd.pcd" -- detect "$T/absurd.pcd" --json "$O/g.json"
row "POINTS beyond 2^32" "POINTS" -- detect "$T/absurd_points.pcd" --json "$O/g.json"
row "PCD header without POINTS" "POINTS" -- detect "$T/no_points_line.pcd" --json "$O/g.json"
row "no x, y, z fields" "x, y and z" -- detect "$T/noxyz.pcd" --json "$O/g.json"
row "every coordinate NaN" "nan.pcd: input cloud has no finite point" -- detect "$T/nan.pcd" --json "$O/g.json"
row "every point has an infinite coordinate" "inf.pcd: input cloud has no finite point" -- detect "$T/inf.pcd" --json "$O/g.json"
row "a single point" "point" -- detect "$T/one.pcd" --json "$O/g.json"
row "three collinear points" "point" -- detect "$T/collinear.pcd" --json "$O/g.json"
row "coordinates of 1e30" "1e+30\|range\|no finite\|point" -- detect "$T/huge.pcd" --json "$O/g.json"
row "binary PLY cut short" "truncated.ply" -- detect "$T/truncated.ply" --json "$O/g.json"
row "PLY header without end_header" "noend.ply" -- detect "$T/noend.ply" --json "$O/g.json"
row "unsupported extension" "unsupported extension" -- detect "$T/cloud.xyz" --json "$O/g.json"

# ---- configs (on a valid cloud: a 20 x 20 patch 1 m ahead)
awk 'BEGIN { for (i = 0; i < 20; i++) for (j = 0; j < 20; j++) printf "%.3f %.3f 1\n", i * 0.01, j * 0.01 }' >"$T/pts"
{ pcd_head "x y z" 400 1 400 ascii; cat "$T/pts"; } >"$T/ok.pcd"
C="$T/ok.pcd"
printf 'preprocess:\n  voxl:\n    leaf: 0.01\n' >"$T/typo.yaml"
printf 'grasp: [1, 2\n' >"$T/notyaml.yaml"
printf 'grasp:\n  gripper:\n    max_aperture: .nan\n' >"$T/nan.yaml"
printf 'seed: -3\n' >"$T/negseed.yaml"
row "config: unknown key" "unknown key 'preprocess.voxl'" -- detect "$C" --config "$T/typo.yaml" --json "$O/g.json"
row "config: not YAML" "notyaml.yaml" -- detect "$C" --config "$T/notyaml.yaml" --json "$O/g.json"
row "config file missing" "nosuch.yaml" -- detect "$C" --config "$T/nosuch.yaml" --json "$O/g.json"
row "config: NaN in the file" "grasp.gripper.max_aperture" -- detect "$C" --config "$T/nan.yaml" --json "$O/g.json"
row "config: negative seed" "seed" -- detect "$C" --config "$T/negseed.yaml" --json "$O/g.json"
row "--set: wrong type" "preprocess.voxel.leaf" -- detect "$C" --set preprocess.voxel.leaf=abc --json "$O/g.json"
row "--set: out of range" "out of range" -- detect "$C" --set segment.region.k=0 --json "$O/g.json"
row "--set: weights that sum to 0" "sum to 0" -- detect "$C" --set grasp.score.weights.normal=0 \
  --set grasp.score.weights.orientation=0 --set grasp.score.weights.contact=0 \
  --set grasp.score.weights.inliers=0 --json "$O/g.json"
row "--set: negative aperture" "grasp.gripper.max_aperture" -- detect "$C" --set grasp.gripper.max_aperture=-0.01 --json "$O/g.json"
row "--set: NaN" "grasp.gripper.max_aperture" -- detect "$C" --set grasp.gripper.max_aperture=nan --json "$O/g.json"
row "--set: infinity" "preprocess.range.max" -- detect "$C" --set preprocess.range.max=inf --json "$O/g.json"
row "--set without =" "--set" -- detect "$C" --set preprocess.voxel.leaf --json "$O/g.json"
row "--set: unknown key" "unknown key" -- detect "$C" --set grasp.nonsense=1 --json "$O/g.json"
row "--camera-pose: not a unit quaternion" "camera-pose" -- detect "$C" --camera-pose 0,0,0,0,0,0,0 --json "$O/g.json"

# ---- scenes, meshes, truth, grasps, calibrations
printf 'objects: [{name: a, parts: [{shape: box, sizes: [1, 1, 1]}]}]\n' >"$T/badkey.yaml"
printf 'objects: [{name: a, interest: true, parts: [{shape: mesh, file: no_such.obj}]}]\n' >"$T/nomesh.yaml"
printf 'this is not a mesh\n' >"$T/bad.obj"
printf 'objects: [{name: a, interest: true, parts: [{shape: mesh, file: bad.obj}]}]\n' >"$T/badmesh.yaml"
printf 'objects: [{name: a, parts: [{shape: box, size: [1, -1, 1]}]}]\n' >"$T/negsize.yaml"
printf 'name: x\nsensor: rgbd\nseed: 1\nobjects: []\n' >"$T/nocamera.yaml"
printf '{"grasps": [{"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0, 2], "score": 1}]}\n' >"$T/badquat.json"
printf '{"grasps": [' >"$T/cut.json"
printf 'image_width: 640\nimage_height: 480\n' >"$T/nok.yaml"
row "scene: unknown key" "objects\[0\].parts\[0\].sizes" -- simulate --scene "$T/badkey.yaml" --out "$O"
row "scene: negative size" "size\[1\]" -- simulate --scene "$T/negsize.yaml" --out "$O"
row "scene: mesh file missing" "no_such.obj" -- simulate --scene "$T/nomesh.yaml" --out "$O"
row "scene: mesh file not a mesh" "bad.obj" -- simulate --scene "$T/badmesh.yaml" --out "$O"
row "unknown built-in scene" "atlantis" -- simulate --scene atlantis --out "$O"
row "truth.yaml without a camera" "camera" -- evaluate --truth "$T/nocamera.yaml" --grasps "$T/badquat.json" --json "$O/e.json"
row "grasps.json cut short" "cut.json" -- evaluate --truth "$T/sim/truth.yaml" --grasps "$T/cut.json" --json "$O/e.json"
row "grasps.json: not a unit quaternion" "orientation_xyzw" -- evaluate --truth "$T/sim/truth.yaml" --grasps "$T/badquat.json" --json "$O/e.json"

# ---- output paths: a simulated RGB-D frame to a 4 MB cloud
printf 'image_width: 640\nimage_height: 480\ncamera_matrix:\n  rows: 3\n  cols: 3\n  data: [554.3827, 0, 319.5, 0, 554.3827, 239.5, 0, 0, 1]\n' >"$T/cam.yaml"
D=("$T/sim/depth.png" "$T/sim/rgb.png" --camera "$T/cam.yaml")
row "an image that is not an image" "ok.pcd" -- rgbd "$T/ok.pcd" "$T/sim/rgb.png" --camera "$T/cam.yaml" --out "$O/c.pcd"
row "calibration without camera_matrix" "camera_matrix" -- rgbd "${D[@]:0:3}" "$T/nok.yaml" --out "$O/c.pcd"
mkdir -p "$T/isdir.pcd"
row "output path is a directory" "isdir.pcd" -- rgbd "${D[@]}" --out "$T/isdir.pcd"
row "output folder does not exist" "nodir" -- rgbd "${D[@]}" --out "$T/nodir/c.pcd"
# A full disk: a 64 KiB file size limit (uwgrasp ignores SIGXFSZ, so the write fails with EFBIG).
REAL=$BIN
printf '#!/usr/bin/env bash\nmkdir -p "%s"\nulimit -f 64\nexec "%s" "$@"\n' "$O" "$REAL" >"$T/small_disk.sh"
chmod +x "$T/small_disk.sh"
BIN="$T/small_disk.sh"
row "disk full (64 KiB file size limit)" "File too large" -- rgbd "${D[@]}" --out "$O/c.pcd"
BIN=$REAL
# Permissions: root reads and writes anything, so as root these rows run as nobody.
mkdir -p "$T/ro" && chmod 555 "$T/ro" && chmod 711 "$T" && chmod 644 "$T/ok.pcd" && cp "$T/ok.pcd" "$T/secret.pcd" && chmod 000 "$T/secret.pcd"
chmod -R a+rX "$T/sim" "$T/cam.yaml"
if [[ $(id -u) -eq 0 ]]; then
  printf '#!/usr/bin/env bash\nexec setpriv --reuid=65534 --regid=65534 --clear-groups "%s" "$@"\n' "$REAL" >"$T/as_nobody.sh"
  chmod 755 "$T/as_nobody.sh"; BIN="$T/as_nobody.sh"
fi
if "$BIN" --version >/dev/null 2>&1; then
  row "unreadable file" "secret.pcd" -- detect "$T/secret.pcd" --json "$O/g.json"
  row "read-only output folder" "ro/c.pcd" -- rgbd "${D[@]}" --out "$T/ro/c.pcd"
  [[ -z "$(ls -A "$T/ro")" ]] && ok || bad "a file was left in the read-only folder: $(ls -A "$T/ro")"
else
  echo "SKIP: the permission rows (cannot run uwgrasp as an unprivileged user here)"
fi
BIN=$REAL

if [[ -n $TABLE ]]; then
  { echo "| # | input | command | uwgrasp says (stderr, one line) | exit |"; echo "|---|---|---|---|---|"
    n=0; while IFS= read -r r; do n=$((n + 1)); echo "| $n $r"; done <<<"${rows%$'\n'}"; } >"$TABLE"
fi
echo "$(grep -c . <<<"$rows") rows"
finish
