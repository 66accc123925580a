#!/usr/bin/env bash
# CLI contract of the perception commands (calibrate, stereo, rgbd): bad images, calibration files
# and ports are named with exit 2 and nothing written; good runs write what they say.
source "$(dirname "$0")/cli_lib.sh"

# A grey 640 x 480 image with no board in it (PGM, which OpenCV reads), and a smaller one.
{ printf 'P5\n640 480\n255\n'; head -c 307200 /dev/zero | tr '\0' '\200'; } >"$T/blank.pgm"
{ printf 'P5\n320 240\n255\n'; head -c 76800 /dev/zero | tr '\0' '\200'; } >"$T/small.pgm"
printf 'not an image\n' >"$T/junk.png"

expect 0 "" -- calibrate --help
expect 2 "blank.pgm" -- calibrate "$T/blank.pgm" "$T/blank.pgm" "$T/blank.pgm" --board 9x6 --out "$T/out/cam.yaml"
expect 2 "junk.png" -- calibrate "$T/junk.png" --board 9x6 --out "$T/out/cam.yaml"
expect 2 "small.pgm" -- calibrate "$T/blank.pgm" "$T/small.pgm" "$T/blank.pgm" --out "$T/out/cam.yaml"
expect 2 "--board" -- calibrate "$T/blank.pgm" --board nine --out "$T/out/cam.yaml"
expect 2 "--square" -- calibrate "$T/blank.pgm" --square -1 --out "$T/out/cam.yaml"

S="$DATA/stereo"
if [[ -f "$S/left01.jpg" ]]; then
  L=() R=()
  for n in 01 02 03 04 05 06 07 08 09 11 12 13 14; do L+=("$S/left$n.jpg"); R+=("$S/right$n.jpg"); done
  if "$BIN" calibrate "${L[@]}" --right "${R[@]}" --board 9x6 --square 1 --out "$T/rig.yaml" >"$T/cal.txt" 2>&1 &&
     grep -q "RMS reprojection error: stereo 0\." "$T/cal.txt" && grep -q "^baseline:" "$T/rig.yaml"; then ok; else
    bad "stereo calibration of the shared pairs: $(tail -2 "$T/cal.txt")"; fi
  if "$BIN" calibrate "${L[@]}" --board 9x6 --out "$T/left.yaml" >"$T/mono.txt" 2>&1 &&
     grep -q "camera_matrix" "$T/left.yaml" && [[ $(grep -c "RMS 0\." "$T/mono.txt") -ge 12 ]]; then ok; else
    bad "mono calibration of the shared left images: $(tail -2 "$T/mono.txt")"; fi
  # The pair of a left image with a blank right one is named and left out.
  expect 2 "blank.pgm" -- calibrate "$S/left01.jpg" --right "$T/blank.pgm" --out "$T/out/rig.yaml"
fi

# stereo and rgbd on a simulated stereo frame of the thesis scene.
"$BIN" simulate --scene thesis --sensor stereo --out "$T/sim" >/dev/null 2>&1 || bad "simulate --sensor stereo"
printf 'image_width: 640\nimage_height: 480\nleft: {K: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n' >"$T/nok.yaml"
printf 'image_width: 640\nimage_height: 480\nleft: {K: [0, 0, 320, 0, 0, 240, 0, 0, 1], D: [0, 0, 0, 0, 0]}\nright: {K: [0, 0, 320, 0, 0, 240, 0, 0, 1], D: [0, 0, 0, 0, 0]}\nR: [1, 0, 0, 0, 1, 0, 0, 0, 1]\nT: [-0.1, 0, 0]\n' >"$T/singular.yaml"
printf 'distance: 0.01\nthickness: 0.01\nn_air: 1\nn_glass: 0.5\nn_water: 1.34\n' >"$T/badport.yaml"
S="$T/sim"
expect 0 "" -- stereo --help
expect 2 "small.pgm" -- stereo "$S/left.png" "$T/small.pgm" --calib "$S/stereo.yaml" --out "$T/out/c.pcd"
expect 2 "junk.png" -- stereo "$S/left.png" "$T/junk.png" --calib "$S/stereo.yaml" --out "$T/out/c.pcd"
expect 2 "nok.yaml" -- stereo "$S/left.png" "$S/right.png" --calib "$T/nok.yaml" --out "$T/out/c.pcd"
printf 'image_width: 640\nimage_height: 480\nleft: {D: [0, 0, 0, 0, 0]}\nright: {K: [500, 0, 320, 0, 500, 240, 0, 0, 1], D: [0, 0, 0, 0, 0]}\nR: [1, 0, 0, 0, 1, 0, 0, 0, 1]\nT: [-0.1, 0, 0]\n' >"$T/noK.yaml"
expect 2 "missing left.K" -- stereo "$S/left.png" "$S/right.png" --calib "$T/noK.yaml" --out "$T/out/c.pcd"
expect 2 "singular" -- stereo "$S/left.png" "$S/right.png" --calib "$T/singular.yaml" --out "$T/out/c.pcd"
expect 2 "n_glass" -- stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml" --port "$T/badport.yaml" --out "$T/out/c.pcd"
expect 2 "exactly one input" -- detect "$S/cloud.pcd" --stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml"
expect 2 "--calib" -- detect --stereo "$S/left.png" "$S/right.png"
expect 2 "no such file" -- detect --stereo "$S/left.png" "$T/none.png" --calib "$S/stereo.yaml" --json "$T/out/g.json"
if "$BIN" stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml" --out "$T/st.pcd" --png "$T/st.png" >"$T/st.txt" 2>&1 &&
   grep -q "cloud: 640 x 480" "$T/st.txt" && grep -q "stage times" "$T/st.txt" && [[ -s $T/st.pcd && -s $T/st.png ]] &&
   grep -q -- "--set grasp.shape.depth_error=0.0030" "$T/st.txt" &&
   grep -q "^WIDTH 640" <(head -c 400 "$T/st.pcd") && grep -q "^HEIGHT 480" <(head -c 400 "$T/st.pcd"); then ok; else
  bad "stereo on a simulated pair: $(tail -2 "$T/st.txt")"; fi
if "$BIN" detect --stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml" --json "$T/gs.json" >"$T/ds.txt" 2>&1 &&
   grep -q "images to cloud" "$T/ds.txt" && grep -qE "^best grasp|^no feasible grasp" "$T/ds.txt" &&
   grep -q "the sensor's depth error at the object's depth" "$T/ds.txt" && grep -q '"grasps"' "$T/gs.json"; then ok; else
  bad "detect --stereo: $(tail -2 "$T/ds.txt")"; fi
# The issue's memory limit for one 640 x 480 detection (UWGRASP_RSS_LIMIT_MB, unset under the
# sanitizers), with its picture: loading OpenCV's codecs for the images once took this to 151 MB.
peak_mb() {
  python3 - "$@" <<'PY'
import resource, subprocess, sys
code = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
print(code, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024)
PY
}
# within_limit LABEL ARGS...: uwgrasp ARGS exits 0 within the limit.
within_limit() {
  local label=$1 code mb; shift
  read -r code mb < <(peak_mb "$BIN" "$@")
  if [[ $code -eq 0 && $mb -le $UWGRASP_RSS_LIMIT_MB ]]; then ok; else
    bad "$label: exit $code, peak resident set $mb MB (limit $UWGRASP_RSS_LIMIT_MB)"; fi
}
if [[ -n ${UWGRASP_RSS_LIMIT_MB:-} ]]; then
  within_limit "detect --stereo --png" detect --stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml" \
    --json "$T/gm.json" --png "$T/gm.png"
  if [[ -f "$DATA/clouds/table_scene_mug_stereo_textured.pcd" ]]; then
    within_limit "detect on the mug frame --png" detect "$DATA/clouds/table_scene_mug_stereo_textured.pcd" \
      --object largest --json "$T/gm.json" --png "$T/gm.png"
  fi
fi
if "$BIN" stereo "$S/left.png" "$S/right.png" --calib "$S/stereo.yaml" --sparse --detector harris --out "$T/sp.pcd" \
     --png "$T/sp.png" >"$T/sp.txt" 2>&1 && grep -q "harris keypoints" "$T/sp.txt" && [[ -s $T/sp.pcd && -s $T/sp.png ]]; then
  ok; else bad "stereo --sparse: $(tail -2 "$T/sp.txt")"; fi
expect 2 "no feature matched" -- stereo "$T/blank.pgm" "$T/blank.pgm" --calib "$S/stereo.yaml" --sparse --out "$T/out/sp.pcd"
# Behind a flat port: simulate through it, correct it with Pinax.
printf 'distance: 0.02\nthickness: 0.012\nn_air: 1\nn_glass: 1.49\nn_water: 1.34\n' >"$T/port.yaml"
if "$BIN" simulate --scene thesis --sensor stereo --port "$T/port.yaml" --out "$T/simp" >/dev/null 2>&1 &&
   "$BIN" stereo "$T/simp/left.png" "$T/simp/right.png" --calib "$T/simp/stereo.yaml" --port "$T/simp/port.yaml" \
     --out "$T/pp.pcd" >"$T/pp.txt" 2>&1 && grep -q "flat port by Pinax" "$T/pp.txt"; then ok; else
  bad "stereo --port: $(tail -2 "$T/pp.txt")"; fi
# The thesis scene from a simulated stereo pair through the whole chain, and the judged study's stereo condition.
if "$BIN" demo --sensor stereo --out "$T/demo" >"$T/demo.txt" 2>&1 && grep -q "^stereo: rectify" "$T/demo.txt" &&
   [[ -s $T/demo/left.png && -s $T/demo/stereo.yaml && -s $T/demo/grasps.json ]]; then ok; else
  bad "demo --sensor stereo: $(tail -2 "$T/demo.txt")"; fi
if "$BIN" experiments --study judged --scenes cross --water coastal --sensor rgbd,stereo --iterations 1 --no-calibration \
     --out "$T/js" >/dev/null 2>"$T/js.txt" && grep -q "## Stereo" "$T/js/report.md" &&
   grep -q "cross, coastal stereo |" "$T/js/report.md" && grep -q "stereo_depth_error" "$T/js/runs.csv"; then ok; else
  bad "judged study with --sensor stereo: $(tail -2 "$T/js.txt")"; fi
expect 2 "" -- experiments --study judged --sensor sonar --iterations 1 --out "$T/out"
# rgbd: the simulated depth and colour with a camera file made from the simulated intrinsics.
printf 'image_width: 640\nimage_height: 480\ncamera_matrix: {rows: 3, cols: 3, data: [554.3827128226441, 0, 319.5, 0, 554.3827128226441, 239.5, 0, 0, 1]}\ndistortion_model: plumb_bob\ndistortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n' >"$T/cam.yaml"
expect 0 "" -- rgbd --help
expect 2 "rgb.png" -- rgbd "$S/rgb.png" "$S/rgb.png" --camera "$T/cam.yaml" --out "$T/out/c.pcd"
expect 2 "small.pgm" -- rgbd "$S/depth.png" "$T/small.pgm" --camera "$T/cam.yaml" --out "$T/out/c.pcd"
if "$BIN" rgbd "$S/depth.png" "$S/rgb.png" --camera "$T/cam.yaml" --out "$T/rg.pcd" >"$T/rg.txt" 2>&1 &&
   grep -q "cloud: 640 x 480" "$T/rg.txt" && [[ -s $T/rg.pcd ]]; then ok; else bad "rgbd: $(tail -2 "$T/rg.txt")"; fi
if "$BIN" detect --rgbd "$S/depth.png" "$S/rgb.png" --camera "$T/cam.yaml" >"$T/dr.txt" 2>&1 &&
   grep -q "best grasp" "$T/dr.txt"; then ok; else bad "detect --rgbd: $(tail -2 "$T/dr.txt")"; fi
finish
