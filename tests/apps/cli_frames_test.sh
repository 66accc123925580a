#!/usr/bin/env bash
# Clouds in any frame: a cloud in a world frame with its camera pose as the PCD VIEWPOINT or
# --camera-pose gives the grasps of the same cloud in the camera frame, written in the world
# frame; an object-only world cloud (GPD's tutorial style) gives a grasp on the object; a cloud
# whose points lie behind the camera gets an error naming the options.
source "$(dirname "$0")/cli_lib.sh"
command -v python3 >/dev/null || { echo "SKIP: python3 is needed to read the JSON"; exit 0; }

"$BIN" simulate --scene barbell --out "$T/cam" >/dev/null 2>&1 || bad "simulate (camera frame)"
"$BIN" simulate --scene barbell --frame world --out "$T/world" >/dev/null 2>&1 || bad "simulate --frame world"
grep -a -q "^VIEWPOINT 0 0 0 1 0 0 0" "$T/world/cloud.pcd" && bad "a world-frame cloud has the identity VIEWPOINT"
C="$T/cam/config.yaml"
# The sampler's focus (grasp.sampler.focus) draws later candidates near the ones that passed, so
# a candidate that float rounding moves across a check moves the later draws too: the same
# grasps to the digit need it off (with it on, the best grasps are as good, not the same).
S="grasp.sampler.focus=false"
"$BIN" detect "$T/cam/cloud.pcd" --config "$C" --set "$S" --json "$T/cam.json" >/dev/null 2>&1 || bad "detect in the camera frame"
"$BIN" detect "$T/world/cloud.pcd" --config "$C" --set "$S" --json "$T/world.json" >"$T/w.txt" 2>&1 || bad "detect, VIEWPOINT"
grep -q "camera pose from the cloud's VIEWPOINT" "$T/w.txt" && ok || bad "detect does not say it used the VIEWPOINT"
# The camera pose as the VIEWPOINT holds it (X Y Z QW QX QY QZ) -> --camera-pose X,Y,Z,QX,QY,QZ,QW
read -r _ x y z qw qx qy qz < <(grep -a -m1 "^VIEWPOINT" "$T/world/cloud.pcd")
"$BIN" detect "$T/cam/cloud.pcd" --frame camera --config "$C" --camera-pose "$x,$y,$z,$qx,$qy,$qz,$qw" \
  >/dev/null 2>&1 && bad "--camera-pose with --frame camera is accepted"

# Same best grasp: the world file's pose is the camera file's moved by the camera pose. With the
# default settings the best grasps may differ, but lie on the same part of the object.
"$BIN" detect "$T/cam/cloud.pcd" --config "$C" --json "$T/cam_d.json" >/dev/null 2>&1 || bad "detect (defaults)"
"$BIN" detect "$T/world/cloud.pcd" --config "$C" --json "$T/world_d.json" >/dev/null 2>&1 || bad "detect, VIEWPOINT (defaults)"
python3 - "$T/cam.json" "$T/world.json" "$x,$y,$z,$qx,$qy,$qz,$qw" "$T/cam_d.json" "$T/world_d.json" <<'PY' && ok || bad "world-frame grasps differ"
import json, math, sys
c, w = (json.load(open(p)) for p in sys.argv[1:3])
x, y, z, qx, qy, qz, qw = map(float, sys.argv[3].split(","))
def rot(v):  # q * v * q^-1
    tx, ty, tz = 2 * (qy * v[2] - qz * v[1]), 2 * (qz * v[0] - qx * v[2]), 2 * (qx * v[1] - qy * v[0])
    return [v[0] + qw * tx + qy * tz - qz * ty, v[1] + qw * ty + qz * tx - qx * tz,
            v[2] + qw * tz + qx * ty - qy * tx]
assert c["frame"] == "camera_optical" and w["frame"] == "world", (c["frame"], w["frame"])
gc, gw = c["grasps"][0], w["grasps"][0]
p = [a + b for a, b in zip(rot(gc["position"]), (x, y, z))]
assert math.dist(p, gw["position"]) < 1e-3, (p, gw["position"])
assert math.dist(rot(gc["approach"]), gw["approach"]) < 1e-3
assert abs(gc["width"] - gw["width"]) < 1e-4 and abs(gc["score"] - gw["score"]) < 1e-4
c, w = (json.load(open(p)) for p in sys.argv[4:6])
p = [a + b for a, b in zip(rot(c["grasps"][0]["position"]), (x, y, z))]
assert w["frame"] == "world" and math.dist(p, w["grasps"][0]["position"]) < 0.05, (p, w["grasps"][0]["position"])
PY

# A world cloud without its VIEWPOINT: the points lie behind the camera's origin -> clear error.
python3 - "$T/world/cloud.pcd" "$T/noview.pcd" <<'PY'
import re, sys
data = open(sys.argv[1], "rb").read()
open(sys.argv[2], "wb").write(re.sub(rb"\nVIEWPOINT [^\n]*\n", b"\nVIEWPOINT 0 0 0 1 0 0 0\n", data, count=1))
PY
expect 2 "behind the camera.*--camera-pose" -- detect "$T/noview.pcd" --json "$T/out/g.json"
expect 2 "behind the camera.*--camera-pose" -- segment "$T/noview.pcd" --out-dir "$T/out"
expect 2 "--frame world needs" -- detect "$T/noview.pcd" --frame world --json "$T/out/g.json"
expect 2 "--camera-pose" -- detect "$T/noview.pcd" --camera-pose 1,2,3,0,0,0,2 --json "$T/out/g.json"
expect 2 "--camera-pose" -- detect "$T/noview.pcd" --camera-pose 1,2,3 --json "$T/out/g.json"
# ... and with --camera-pose it is the world cloud again.
"$BIN" detect "$T/noview.pcd" --config "$C" --set "$S" --camera-pose "$x,$y,$z,$qx,$qy,$qz,$qw" --json "$T/cp.json" \
  >/dev/null 2>&1 || bad "detect --camera-pose"
python3 - "$T/cp.json" "$T/world.json" <<'PY' && ok || bad "--camera-pose gives other grasps than the same pose as VIEWPOINT"
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
# The pose as printed in the header differs from the binary one by float rounding, which moves
# points across voxel boundaries: the same grasp, not the same digits.
assert a["frame"] == "world" and a["grasps"] and b["grasps"]
assert math.dist(a["grasps"][0]["position"], b["grasps"][0]["position"]) < 0.01
PY

# GPD's tutorial style: the object alone, in the world frame, with the camera pose given.
"$BIN" simulate --scene barbell --frame world --object-only --out "$T/obj" >/dev/null 2>&1 || bad "simulate --object-only"
"$BIN" segment "$T/obj/cloud.pcd" --out-dir "$T/objseg" >/dev/null 2>&1 || bad "segment an object-only world cloud"
grep -a -q "^VIEWPOINT $x $y $z" "$T/objseg/segment_000.pcd" && ok || bad "segments lose the cloud's VIEWPOINT"
"$BIN" detect "$T/obj/cloud.pcd" --json "$T/obj.json" >"$T/o.txt" 2>&1 || bad "detect on an object-only world cloud: $(tail -1 "$T/o.txt")"
"$BIN" evaluate --truth "$T/obj/truth.yaml" --grasps "$T/obj.json" --json "$T/objeval.json" >/dev/null 2>&1 || bad "evaluate"
# The fingers close on the barbell; the only thing they may meet is the seafloor the cloud
# does not show.
python3 - "$T/objeval.json" <<'PY' && ok || bad "the object-only cloud's best grasp misses the object"
import json, sys
j = json.load(open(sys.argv[1]))["judgements"][0]
assert j["outcome"] == "holds" or (j["outcome"] == "collision" and j["object"] == "seafloor"), j
PY

# --object point: is in the cloud's frame: the barbell of the thesis scene sits at the world's origin.
"$BIN" simulate --scene thesis --frame world --out "$T/th" >/dev/null 2>&1 || bad "simulate thesis --frame world"
"$BIN" detect "$T/th/cloud.pcd" --object point:0,0,0.04 --json "$T/th.json" >/dev/null 2>&1 || bad "detect --object point:"
"$BIN" evaluate --truth "$T/th/truth.yaml" --grasps "$T/th.json" --json "$T/theval.json" >/dev/null 2>&1 || bad "evaluate thesis"
python3 - "$T/theval.json" <<'PY' && ok || bad "--object point: in the world frame did not select the barbell"
import json, sys
j = json.load(open(sys.argv[1]))["judgements"][0]
assert j["outcome"] not in ("miss", "other_object"), j
PY

# A depth camera four times noisier than the simulated default: the normals' window grows, the
# points move onto their windows' range fits, and detect says the surface noise is what is left in
# them; with the move off, neither.
"$BIN" simulate --scene barbell --set sim.noise.sigma_k=0.008 --out "$T/noisy" >/dev/null 2>&1 || bad "simulate a noisier sensor"
"$BIN" detect "$T/noisy/cloud.pcd" --config "$T/noisy/config.yaml" >"$T/noisy.txt" 2>&1 &&
  grep -q "^normals: 9 x 9 pixel windows .*; points moved onto their windows' range fits, [0-9.]* mm left at 1 m" "$T/noisy.txt" &&
  grep -q "^shape: .*(the depth error left in the points moved onto their windows' range fits" "$T/noisy.txt" &&
  ok || bad "a noisier frame's points are not moved: $(grep -E '^(normals|shape):' "$T/noisy.txt")"
"$BIN" segment "$T/noisy/cloud.pcd" --set preprocess.organised.move_onto_quadrics=false >"$T/still.txt" 2>&1 &&
  grep -q "^normals: 9 x 9 pixel windows" "$T/still.txt" && ! grep -q "moved onto" "$T/still.txt" &&
  ok || bad "move_onto_quadrics=false still moves: $(grep normals: "$T/still.txt")"

# PCL's sample clouds carry a VIEWPOINT (a half turn about x) their points do not follow: as given,
# the points are in front of the camera; the VIEWPOINT would put them all behind it.
MUG="$DATA/clouds/table_scene_mug_stereo_textured.pcd"
if [[ -f $MUG ]]; then
  "$BIN" segment "$MUG" >"$T/mug.txt" 2>&1 && grep -q "VIEWPOINT would put the points behind the camera" "$T/mug.txt" &&
    ok || bad "the mug's VIEWPOINT is not recognised as inconsistent: $(grep frame: "$T/mug.txt")"
  expect 2 "behind the camera" -- segment "$MUG" --frame world --out-dir "$T/out"
fi
finish
