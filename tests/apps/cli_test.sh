#!/usr/bin/env bash
# CLI contract (INTERFACE.md): bad input -> one line on stderr naming the problem, exit 2, and no
# output file; --help works everywhere; a good run exits 0 and writes its files.
source "$(dirname "$0")/cli_lib.sh"

printf 'VERSION .7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2\n' >"$T/noxyz.pcd"
printf 'VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 100\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 100\nDATA binary\n' >"$T/truncated.pcd"
head -c 64 /dev/urandom >>"$T/truncated.pcd"
printf 'garbage\n' >"$T/malformed.pcd"
printf 'preprocess:\n  voxl:\n    leaf: 0.01\n' >"$T/typo.yaml"
printf 'VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\nnan nan nan\nnan nan nan\n' >"$T/allnan.pcd"

expect 2 "no such file" -- segment "$T/missing.pcd" --out-dir "$T/out"
expect 2 "truncated.pcd" -- segment "$T/truncated.pcd" --out-dir "$T/out"
expect 2 "malformed" -- segment "$T/malformed.pcd" --out-dir "$T/out"
expect 2 "x, y and z" -- segment "$T/noxyz.pcd" --out-dir "$T/out"
expect 2 "no finite point" -- segment "$T/allnan.pcd" --out-dir "$T/out"
expect 0 "" -- segment --help
expect 0 "" -- --help
expect 2 "" -- segment
expect 2 "" -- frobnicate
expect 0 "" -- detect --help
expect 2 "no such file" -- detect "$T/missing.pcd" --json "$T/out/g.json"

# An object-only scan (no floor): the plane stage keeps the object's faces and a grasp is found.
MILK="$DATA/clouds/milk_color.pcd"
if [[ -f "$MILK" ]]; then
  if "$BIN" detect "$MILK" --object largest >"$T/milk.txt" 2>&1 && grep -q "best grasp" "$T/milk.txt" &&
     grep -q "13704 points in, 13536 after preprocessing" "$T/milk.txt"; then ok; else
    bad "detect on the object-only milk scan: $(tail -3 "$T/milk.txt")"; fi
fi

MUG="$DATA/clouds/table_scene_mug_stereo_textured.pcd"
if [[ -f "$MUG" ]]; then
  expect 2 "unknown key 'preprocess.voxl'" -- segment "$MUG" --config "$T/typo.yaml" --out-dir "$T/out"
  expect 2 "preprocess.voxel.leaf" -- segment "$MUG" --set preprocess.voxel.leaf=abc --out-dir "$T/out"
  expect 2 "out of range" -- segment "$MUG" --set segment.region.k=0 --out-dir "$T/out"
  # A good run: table printed, one file per segment plus the labelled cloud.
  if "$BIN" segment "$MUG" --out-dir "$T/good" >"$T/stdout" 2>"$T/stderr" &&
     grep -q "stage times" "$T/stdout" && [[ -f "$T/good/labelled.pcd" ]] &&
     [[ -f "$T/good/segment_000.pcd" ]]; then
    passes=$((passes + 1))
  else
    echo "FAIL: good segment run: $(cat "$T/stderr")"; fails=$((fails + 1))
  fi
  # detect: bad values are named, nothing is written.
  J="$T/out/grasps.json"
  expect 2 "grasp.gripper.max_aperture" -- detect "$MUG" --object nearest --set grasp.gripper.max_aperture=-0.01 --json "$J"
  expect 2 "sum to 0" -- detect "$MUG" --object nearest --set grasp.score.weights.normal=0 \
    --set grasp.score.weights.orientation=0 --set grasp.score.weights.contact=0 \
    --set grasp.score.weights.inliers=0 --json "$J"
  expect 2 "--object" -- detect "$MUG" --object colour --json "$J"
  expect 2 "does not exist" -- detect "$MUG" --object label:399 --json "$J"
  # A good run on the mug (the nearest object): exit 0, the shape line, grasps.json written, and
  # what stdout says agrees with the file. The mug's best-predicted grasps sit near
  # min_robustness (0.1): seeds 1-6 give a top-1 that holds on its model in 25-35 % of its
  # perturbed poses, with 4-10 of the 40 measured passing (levelled by the table; taken as level,
  # seed 1 found none). Which side a seed falls on turns with the model's noise, so either outcome
  # is right here; that a grasp is found where the outcome is not marginal is asserted on the
  # RGB-D frame below. The frame has no attitude: it is levelled by its table (level_from_floor
  # auto), 33 degrees from a level camera's.
  if "$BIN" detect "$MUG" --object nearest --json "$T/d1.json" --threads 1 >"$T/stdout" 2>"$T/stderr" &&
     grep -Eq "^level: roll -?[0-9.]+, pitch -3[0-9]\.[0-9] deg from the seafloor plane \(no capture attitude given" "$T/stdout" &&
     grep -Eq "^shape: [0-9]+ seen points, surface noise [0-9]+\.[0-9] mm" "$T/stdout" &&
     { { grep -q "^best grasp" "$T/stdout" && grep -q '"orientation_xyzw"' "$T/d1.json"; } ||
       { grep -q "^no feasible grasp: the 40 best-predicted" "$T/stdout" && grep -q '"grasps": \[\]' "$T/d1.json"; }; }; then
    passes=$((passes + 1))
  else
    echo "FAIL: good detect run: $(cat "$T/stderr")"; fails=$((fails + 1))
  fi
  # Same seed, same grasps.json at 1 and 2 threads (wall-clock times and the thread count aside).
  "$BIN" detect "$MUG" --object nearest --json "$T/d2.json" --threads 2 >/dev/null 2>&1
  strip() { sed '/"timing_ms": {/,/}/d; /"threads":/d' "$1"; }
  if diff <(strip "$T/d1.json") <(strip "$T/d2.json") >/dev/null; then passes=$((passes + 1)); else
    echo "FAIL: grasps.json differs between 1 and 2 threads"; fails=$((fails + 1)); fi
  # An attitude given in the config is kept: the table is then 15+ degrees off level, and detect
  # says how to level by it instead.
  if "$BIN" detect "$MUG" --object nearest --set grasp.frames.capture_pitch=0.1 >"$T/stdout" 2>"$T/stderr" &&
     grep -q "^level: the seafloor plane is [0-9]* deg from level as configured" "$T/stdout"; then
    passes=$((passes + 1))
  else
    echo "FAIL: a configured attitude was not kept: $(grep '^level' "$T/stdout") $(cat "$T/stderr")"; fails=$((fails + 1))
  fi
  # Nothing fits between the fingers: exit 0, an empty list and the rejection counts.
  if "$BIN" detect "$MUG" --object nearest --set grasp.gripper.max_aperture=0.004 \
       --set grasp.gripper.clearance=0 --json "$T/none.json" >"$T/stdout" 2>"$T/stderr" &&
     grep -q "no feasible grasp" "$T/stdout" && grep -q '"grasps": \[\]' "$T/none.json"; then
    passes=$((passes + 1))
  else
    echo "FAIL: no-feasible detect run: $(cat "$T/stdout" "$T/stderr")"; fails=$((fails + 1))
  fi
  # Feasible candidates, none robust (nothing holds at mu 0.001): the line says why, not only
  # "no feasible grasp" under "N feasible".
  if "$BIN" detect "$MUG" --object nearest --set grasp.score.robust.mu=0.001 >"$T/stdout" 2>"$T/stderr" &&
     grep -q "no feasible grasp: the 40 best-predicted candidates held .* (not_robust); the [1-9][0-9]* feasible" "$T/stdout"; then
    passes=$((passes + 1))
  else
    echo "FAIL: none-robust detect run: $(cat "$T/stdout" "$T/stderr")"; fails=$((fails + 1))
  fi
  # Same seed, same files, whatever the thread count.
  "$BIN" segment "$MUG" --threads 1 --out-dir "$T/t1" >/dev/null 2>&1
  "$BIN" segment "$MUG" --threads 2 --out-dir "$T/t2" >/dev/null 2>&1
  if diff -r "$T/t1" "$T/t2" >/dev/null; then passes=$((passes + 1)); else
    echo "FAIL: outputs differ between 1 and 2 threads"; fails=$((fails + 1)); fi
else
  echo "skipped the real-data CLI cases: $MUG not found"
fi
# A real RGB-D frame whose largest object (a box) has grasps that hold on its model in most
# perturbed poses: the best grasp is printed and written, with the vehicle pose it requires.
LEARN0="$DATA/clouds/mOSD_learn0.pcd"
if [[ -f "$LEARN0" ]]; then
  if "$BIN" detect "$LEARN0" --object largest --json "$T/box.json" >"$T/box.txt" 2>&1 &&
     grep -q "^best grasp" "$T/box.txt" && grep -q "^  vehicle pose" "$T/box.txt" &&
     grep -q '"orientation_xyzw"' "$T/box.json" && grep -q '"vehicle_pose"' "$T/box.json"; then ok; else
    bad "detect on mOSD_learn0: $(tail -3 "$T/box.txt")"; fi
else
  echo "skipped the RGB-D frame's detect run: $LEARN0 not found"
fi
# Simulator: bad scenes, meshes, water and views are one-line errors with exit 2, nothing written.
printf 'objects: [{name: a, parts: [{shape: mesh, file: %s/missing.dae}]}]\n' "$T" >"$T/nomesh.yaml"
printf 'objects: [{name: a, parts: [{shape: mesh, file: %s/malformed.pcd}]}]\n' "$T" >"$T/badmesh.yaml"
printf 'vehicle: {position: [0, 0, 50], rpy: [0, 1.5, 0]}\ncamera_mount: {rpy: [0, 1.5, 0]}\nseafloor: {size: 1}\n' >"$T/blind.yaml"
printf 'water: {attenuation: [0.1, -1, 0.1]}\nobjects: [{name: a, parts: [{shape: box, size: [1, 1, 1]}]}]\n' >"$T/badwater.yaml"
expect 2 "unknown scene 'atlantis'" -- simulate --scene atlantis --out "$T/out"
expect 2 "missing.dae" -- simulate --scene "$T/nomesh.yaml" --out "$T/out"
expect 2 "malformed.pcd" -- simulate --scene "$T/badmesh.yaml" --out "$T/out"
expect 2 "sees nothing" -- simulate --scene "$T/blind.yaml" --out "$T/out"
expect 2 "water.attenuation" -- simulate --scene "$T/badwater.yaml" --out "$T/out"
expect 2 "hfov" -- simulate --scene barbell --set sim.camera.hfov=4 --out "$T/out"
expect 2 "" -- simulate --scene barbell --water muddy --out "$T/out"
expect 0 "" -- simulate --help
expect 0 "" -- demo --help
# A good simulation writes every file; the same seed writes identical ones at any thread count.
if "$BIN" simulate --scene thesis --sensor stereo --water coastal --threads 1 --out "$T/s1" >/dev/null 2>&1 &&
   "$BIN" simulate --scene thesis --sensor stereo --water coastal --threads 2 --out "$T/s2" >/dev/null 2>&1 &&
   diff -r -x config.yaml "$T/s1" "$T/s2" >/dev/null &&
   [[ -s $T/s1/cloud.pcd && -s $T/s1/rgb.png && -s $T/s1/depth.png && -s $T/s1/left.png && -s $T/s1/right.png &&
      -s $T/s1/stereo.yaml && -s $T/s1/truth.yaml ]] &&
   "$BIN" detect "$T/s1/cloud.pcd" --config "$T/s1/config.yaml" --json "$T/s1/g.json" --png "$T/s1/g.png" >/dev/null 2>&1 &&
   [[ -s $T/s1/g.json && -s $T/s1/g.png ]]; then passes=$((passes + 1)); else
  echo "FAIL: simulate/detect on a simulated scene"; fails=$((fails + 1)); fi
# The demo: three objects, a grasp on each, grasps.json and grasps.png.
if "$BIN" demo --out "$T/demo" >"$T/demo.txt" 2>&1 && [[ -s $T/demo/grasps.json && -s $T/demo/grasps.png ]] &&
   [[ $(grep -cE '^  (barbell|ring|cross) ' "$T/demo.txt") -eq 3 ]]; then passes=$((passes + 1)); else
  echo "FAIL: demo: $(cat "$T/demo.txt")"; fails=$((fails + 1)); fi
# Approach onto a demo grasp: bad input is named, a good run writes the trajectory and its plot.
G=$T/demo/grasps.json
printf '{"grasps": [{"vehicle_pose": {"position": [1, 0], "orientation_xyzw": [0, 0, 0, 1]}}]}' >"$T/short.json"
expect 2 "missing.json" -- approach --grasps "$T/missing.json" --out "$T/out"
expect 2 "not valid JSON" -- approach --grasps "$T/malformed.pcd" --out "$T/out"
expect 2 "vehicle_pose.position" -- approach --grasps "$T/short.json" --out "$T/out"
expect 2 "rank 99" -- approach --grasps "$G" --rank 99 --out "$T/out"
expect 2 "no object named 'anchor'" -- approach --grasps "$G" --object anchor --out "$T/out"
expect 2 "--current" -- approach --grasps "$G" --current 0.2,0 --out "$T/out"
expect 2 "vehicle.mass" -- approach --grasps "$G" --set vehicle.mass=0 --out "$T/out"
expect 2 "allocation matrix has rank" -- approach --grasps "$G" --set vehicle.thrusters.t5.direction=[1,0,0] --set vehicle.thrusters.t6.direction=[1,0,0] --set vehicle.thrusters.t7.direction=[1,0,0] --set vehicle.thrusters.t8.direction=[1,0,0] --out "$T/out"
expect 2 "cannot create output directory" -- demo --out "$T/demo/grasps.json"
expect 2 "inside the hull" -- demo --set "grasp.frames.gripper.position=[0.1,0,0]" --out "$T/out"
if "$BIN" approach --grasps "$G" --object ring --current 0.1,0,0 --out "$T/ap" >"$T/ap.txt" 2>&1 &&
   grep -q "reached: yes" "$T/ap.txt" && [[ -s $T/ap/approach.png && $(head -1 "$T/ap/approach.csv" | cut -d, -f1-2) == "t,phase" ]] &&
   [[ $(wc -l <"$T/ap/approach.csv") -gt 100 ]]; then passes=$((passes + 1)); else
  echo "FAIL: approach: $(cat "$T/ap.txt")"; fails=$((fails + 1)); fi
# Evaluate: bad truth, grasps and options are named; a good run judges the demo's grasps.
TR=$T/demo/truth.yaml
sed 's|shape: box|shape: mesh\n        file: /nonexistent/part.obj|' "$TR" >"$T/nomesh_truth.yaml"
grep -v '    fx:' "$TR" >"$T/nofx_truth.yaml"
printf '{"grasps": [{"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0, 1]}]}' >"$T/noscore.json"
printf '{"grasps": [{"position": [0, 0, 1], "orientation_xyzw": [0, 0, 0.5, 1], "score": 1}]}' >"$T/nonunit.json"
expect 2 "part.obj" -- evaluate --truth "$T/nomesh_truth.yaml" --grasps "$G" --object barbell --json "$T/out/e.json"
expect 2 "camera.intrinsics.fx" -- evaluate --truth "$T/nofx_truth.yaml" --grasps "$G" --object ring --json "$T/out/e.json"
expect 2 "missing.yaml" -- evaluate --truth "$T/missing.yaml" --grasps "$G" --json "$T/out/e.json"
expect 2 "grasps\[0\].score" -- evaluate --truth "$TR" --grasps "$T/noscore.json" --json "$T/out/e.json"
expect 2 "not a unit quaternion" -- evaluate --truth "$TR" --grasps "$T/nonunit.json" --json "$T/out/e.json"
expect 2 "positive" -- evaluate --truth "$TR" --grasps "$G" --object ring --mu 0.4,0 --json "$T/out/e.json"
expect 2 "positive" -- evaluate --truth "$TR" --grasps "$G" --object ring --mu -0.2 --json "$T/out/e.json"
expect 2 "'x'" -- evaluate --truth "$TR" --grasps "$G" --object ring --mu 0.4,x --json "$T/out/e.json"
expect 2 "--object" -- evaluate --truth "$TR" --grasps "$G" --json "$T/out/e.json"
expect 2 "anchor" -- evaluate --truth "$TR" --grasps "$G" --object anchor --json "$T/out/e.json"
expect 0 "" -- evaluate --help
if "$BIN" evaluate --truth "$TR" --grasps "$G" --object cross --json "$T/ev.json" --png "$T/ev.png" >"$T/ev.txt" 2>&1 &&
   grep -q "precision@1/5/10" "$T/ev.txt" && grep -q "robust success of the top-1" "$T/ev.txt" &&
   grep -q '"top1_success"' "$T/ev.json" && [[ $(grep -c '"verdict"' "$T/ev.json") -eq 10 ]] && [[ -s $T/ev.png ]]; then
  passes=$((passes + 1)); else echo "FAIL: evaluate: $(cat "$T/ev.txt")"; fails=$((fails + 1)); fi
# Same seed, same verdicts at any thread count.
"$BIN" evaluate --truth "$TR" --grasps "$G" --object ring --threads 1 --json "$T/ev1.json" >/dev/null 2>&1
"$BIN" evaluate --truth "$TR" --grasps "$G" --object ring --threads 2 --json "$T/ev2.json" >/dev/null 2>&1
if cmp -s "$T/ev1.json" "$T/ev2.json"; then passes=$((passes + 1)); else
  echo "FAIL: evaluate differs between 1 and 2 threads"; fails=$((fails + 1)); fi
# Experiments: bad options stop before anything is written; one short run writes the report.
expect 2 "" -- experiments --iterations 0 --out "$T/out"
expect 2 "" -- experiments --water muddy --out "$T/out"
expect 2 "preprocess.voxl" -- experiments --set preprocess.voxl.leaf=1 --out "$T/out"
expect 0 "" -- experiments --help
if "$BIN" experiments --iterations 1 --water clear --out "$T/exp" >/dev/null 2>"$T/exp.txt" &&
   grep -q "Table 8.4" "$T/exp/report.md" && grep -q "iteration 1/1" "$T/exp.txt" &&
   grep -q "whole vehicle fits" "$T/exp/report.md" && [[ -s $T/exp/vehicle_qo_qv.png ]] &&
   grep -q "Judged against the truth" "$T/exp/report.md" &&
   [[ $(ls "$T/exp"/clear_fig8.1[3-6]_*.png | wc -l) -eq 4 ]]; then passes=$((passes + 1)); else
  echo "FAIL: experiments: $(tail -3 "$T/exp.txt")"; fails=$((fails + 1)); fi
# The judged study: unknown scenes stop before any work; a short run writes its report.
expect 2 "unknown scene 'atlantis'" -- experiments --study judged --scenes barbell,atlantis --iterations 1 --out "$T/out"
expect 2 "clear-noisy" -- experiments --water clear-noisy --iterations 1 --out "$T/out"
if "$BIN" experiments --study judged --scenes cross --water clear --water coastal --iterations 1 --out "$T/jd" \
     >/dev/null 2>"$T/jd.txt" && grep -q "## Judged success" "$T/jd/report.md" &&
   grep -q "## Calibration" "$T/jd/report.md" && grep -q "cross, coastal" "$T/jd/report.md" &&
   [[ -s $T/jd/judged_cross.png ]]; then passes=$((passes + 1)); else
  echo "FAIL: judged study: $(tail -3 "$T/jd.txt")"; fails=$((fails + 1)); fi
# --water scene: each scene file's own water. Water so dark the camera sees nothing stops the
# detection; the same scene in coastal water is detected.
printf 'name: murky\nvehicle: {position: [-0.819, 0, 0.519]}\ncamera_mount: {position: [0.2, 0, 0], rpy: [0, -0.6, 0]}\nwater: {attenuation: [60, 60, 60], veiling: [0.1, 0.1, 0.1]}\nobjects:\n  - {name: block, interest: true, color: [210, 25, 25], pose: {position: [0, 0, 0.035]}, parts: [{shape: box, size: [0.05, 0.09, 0.07]}]}\n' >"$T/murky.yaml"
if "$BIN" experiments --study judged --scenes "$T/murky.yaml" --water scene --water coastal --iterations 1 \
     --no-calibration --out "$T/jw" >/dev/null 2>"$T/jw.txt" &&
   grep -q "murky.yaml,scene's water,1,no grasp (detection stopped),.*no finite point" "$T/jw/runs.csv" &&
   grep -Eq "murky.yaml,coastal,1,[a-z].*,$" "$T/jw/runs.csv"; then passes=$((passes + 1)); else
  echo "FAIL: judged study in the scene's own water: $(tail -3 "$T/jw.txt")"; fails=$((fails + 1)); fi
expect 2 "only the judged study" -- experiments --water scene --iterations 1 --out "$T/out"
expect 2 "only the judged study" -- experiments --withhold-attitude --iterations 1 --out "$T/out"
expect 2 "slope" -- experiments --study judged --scenes cross --slope 60 --iterations 1 --out "$T/out"
# The attitude withheld, or a sloping seafloor's: the report says what the detector was told.
if "$BIN" experiments --study judged --scenes cross --water clear --iterations 1 --no-calibration --robust 0 \
     --withhold-attitude --slope 10 --out "$T/ja" >/dev/null 2>"$T/ja.txt" &&
   grep -q "| attitude | withheld" "$T/ja/report.md" && grep -q "| seafloor | rising 10.0 deg" "$T/ja/report.md"; then
  passes=$((passes + 1)); else echo "FAIL: judged study, attitude withheld: $(tail -3 "$T/ja.txt")"; fails=$((fails + 1)); fi
if [[ -d "$DATA/meshes" ]]; then
  if "$BIN" experiments --study judged --scenes sugar_box_turned --water clear --iterations 1 --out "$T/jm" \
       >/dev/null 2>&1 && grep -q "sugar_box_turned, clear" "$T/jm/report.md"; then passes=$((passes + 1)); else
    echo "FAIL: judged study on a mesh scene"; fails=$((fails + 1)); fi
fi
# config/default.yaml is what `uwgrasp config` prints, plus comments.
if diff <("$BIN" config) <(grep -v '^ *#' "$SRC/config/default.yaml" | sed 's/  # .*$//') >/dev/null; then passes=$((passes + 1)); else
  echo "FAIL: config/default.yaml differs from 'uwgrasp config'"; fails=$((fails + 1)); fi

finish
