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
finish
