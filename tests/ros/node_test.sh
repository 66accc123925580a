#!/usr/bin/env bash
# uwgrasp_node against a real roscore (ctest "ros_node"): a bag written by `uwgrasp simulate --bag`
# (FRAMES frames of the thesis scene) played to the node started by uwgrasp.launch gives the grasps
# `uwgrasp detect --bag` gives for the same clouds and seed; markers, poses and diagnostics arrive;
# the best grasp in the world frame (through tf) is judged on the true barbell; malformed clouds,
# an unknown frame and a bad config key are each one ROS_ERROR and the next good cloud is
# processed; ~set_enabled and ~detect_once work; the node shuts down cleanly. Prints the latency (median, 95th percentile).
# Usage: node_test.sh UWGRASP PROBE DEVEL_SETUP FRAMES MIN_PUBLISHED
# (a sanitizer build takes seconds a frame: it plays fewer frames and the node, working on the
# newest cloud, publishes fewer; every cloud is then either published or counted as dropped)
set -u
BIN=$1 PROBE=$2 SETUP=$3 FRAMES=$4 MIN=$5
T=$(mktemp -d)
fails=0
bad() { echo "FAIL: $1"; fails=$((fails + 1)); }
cleanup() {
  [[ -n ${PLAYER:-} ]] && kill -INT "$PLAYER" 2>/dev/null
  [[ -n ${LAUNCH:-} ]] && kill -INT "$LAUNCH" 2>/dev/null
  [[ -n ${CORE:-} ]] && kill -INT "$CORE" 2>/dev/null
  wait 2>/dev/null
  rm -rf "$T"
}
trap cleanup EXIT

set +u  # catkin's setup scripts read unset variables
# shellcheck disable=SC1090
source "$SETUP"
set -u
PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://127.0.0.1:$PORT ROS_HOME=$T/ros ROS_LOG_DIR=$T/log ROS_IP=127.0.0.1
roscore -p "$PORT" >"$T/roscore.log" 2>&1 &
CORE=$!
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.3; done
rostopic list >/dev/null 2>&1 || { echo "FAIL: roscore did not start: $(tail -3 "$T/roscore.log")"; exit 1; }

# The scene, its bag (FRAMES frames at 1 Hz, played at half speed)
# and what the CLI finds in it.
"$BIN" simulate --scene thesis --out "$T/sim" >/dev/null || bad "simulate"
# The barbell (the truth's object of interest) by the point at its bar, in the camera frame.
POINT=$(python3 - "$T/sim/truth.yaml" <<'PY'
import sys, yaml
t = yaml.safe_load(open(sys.argv[1]))["camera"]["world_from_camera"]
(x, y, z), (qx, qy, qz, qw) = t["position"], t["orientation_xyzw"]
R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
     [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
     [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
d = [0 - x, 0 - y, 0.04 - z]
print(",".join("%.6f" % sum(R[r][c] * d[r] for r in range(3)) for c in range(3)))
PY
)
SETS=(--set segment.object.by=point --set "segment.object.point=[$POINT]")
"$BIN" simulate --scene thesis --config "$T/sim/config.yaml" --bag "$T/scene.bag" --frames "$FRAMES" --rate 1 \
  >/dev/null || bad "simulate --bag"
"$BIN" detect --bag "$T/scene.bag" --config "$T/sim/config.yaml" "${SETS[@]}" --json "$T/expected.jsonl" \
  >"$T/detect.txt" || bad "detect --bag: $(tail -2 "$T/detect.txt")"

# The node, with the object chosen through private parameters (any config key works so).
rosparam set /uwgrasp_node/segment/object/by point
rosparam set /uwgrasp_node/segment/object/point "[$POINT]"
roslaunch uwgrasp_ros uwgrasp.launch config:="$T/sim/config.yaml" fixed_frame:=world >"$T/launch.log" 2>&1 &
LAUNCH=$!
for _ in $(seq 100); do rostopic info /camera/depth/points 2>/dev/null | grep -q uwgrasp_node && break; sleep 0.3; done
"$PROBE" listen "$T/got.jsonl" "$FRAMES" 300 &
PROBE_PID=$!
sleep 1
# -d: rosbag's publisher waits before the first message while the node's and the probe's
# subscriptions connect to it; a message sent before a subscriber connects is lost by the transport
# (neither processed nor dropped by the node). 2 s was once too short on a loaded 2-core machine.
# -k: the player stays up after the bag's last message until the probe has what it waits for. A
# player that exits at once can take the last cloud (10 MB, still being written to the sockets by
# roscpp's poll thread) with it: a local CI run once published 19 of 20 so. Kept alive, it is
# stopped here, or by cleanup if the test ends first.
rosbag play -q -k -d 5 -r 0.5 "$T/scene.bag" --topics /camera/depth/points /tf /tf_static /imu/data </dev/null >/dev/null 2>&1 &
PLAYER=$!
wait $PROBE_PID
kill -0 "$PLAYER" 2>/dev/null || bad "rosbag play ended before the probe (it keeps alive until stopped)"
kill -INT "$PLAYER" 2>/dev/null
wait "$PLAYER" 2>/dev/null
PLAYER=""
"$PROBE" bad "$T/scene.bag" "$T/bad.jsonl" 30 || bad "probe bad: exit $?"

kill -INT "$LAUNCH"
wait "$LAUNCH"
LAUNCH=""
if grep -q "process has died\|escalating to SIG" "$T/launch.log"; then bad "the node did not shut down cleanly: $(grep -m1 died "$T/launch.log")"; fi

python3 - "$T" "$BIN" "$FRAMES" "$MIN" <<'PY' || fails=$((fails + 1))
import json, math, subprocess, sys, yaml
T, BIN = sys.argv[1:3]
FRAMES, MIN = int(sys.argv[3]), int(sys.argv[4])
def lines(p): return [json.loads(l) for l in open(p)]
got, bad = lines(T + "/got.jsonl"), lines(T + "/bad.jsonl")
summary, arrays = got[-1], got[:-1]
expected = {round(e["stamp"], 3): e for e in lines(T + "/expected.jsonl")}
ok = True
def check(cond, what):
    global ok
    if not cond: print("FAIL:", what); ok = False
check(len(arrays) >= MIN, "%d of %d frames published (want %d)" % (len(arrays), FRAMES, MIN))
missing = sorted(set(expected) - {round(a["stamp"], 3) for a in arrays})
check(arrays and len(arrays) + arrays[-1]["dropped"] == FRAMES,
      "published %d + dropped %s != %d clouds sent (not published: %d of them, first %s, last %s)" % (
          len(arrays), arrays[-1]["dropped"] if arrays else "?", FRAMES, len(missing),
          missing[0] if missing else "-", missing[-1] if missing else "-"))
for a in arrays:
    e = expected[round(a["stamp"], 3)]
    same = len(a["grasps"]) == len(e["grasps"]) and all(
        math.dist(g["position"], h["position"]) < 1e-9 and abs(g["score"] - h["score"]) < 1e-9
        for g, h in zip(a["grasps"], e["grasps"]))
    check(same, "frame %.3f: the node's grasps differ from detect --bag" % a["stamp"])
with_grasps = sum(1 for a in arrays if a["grasps"])
check(summary["poses"] >= len(arrays) and summary["markers"] >= with_grasps and summary["diagnostics"] >= len(arrays),
      "poses %d, markers %d, diagnostics %d for %d frames" % (summary["poses"], summary["markers"],
                                                              summary["diagnostics"], len(arrays)))
check(summary["errors"] == [], "errors during the bag: %s" % summary["errors"])
# tf: the best grasp in the world frame is the CLI's best (camera frame) moved by the true camera pose.
t = yaml.safe_load(open(T + "/sim/truth.yaml"))["camera"]["world_from_camera"]
(x, y, z), (qx, qy, qz, qw) = t["position"], t["orientation_xyzw"]
def to_world(v):
    tx, ty, tz = 2 * (qy * v[2] - qz * v[1]), 2 * (qz * v[0] - qx * v[2]), 2 * (qx * v[1] - qy * v[0])
    return [v[0] + qw * tx + qy * tz - qz * ty + x, v[1] + qw * ty + qz * tx - qx * tz + y,
            v[2] + qw * tz + qx * ty - qy * tx + z]
best = summary["best"]
check(len(best) == with_grasps and all(b["frame_id"] == "world" for b in best), "best_grasp not in 'world'")
for b in best:
    e = expected[round(b["stamp"], 3)]["grasps"][0]
    check(math.dist(b["position"], to_world(e["position"])) < 0.02, "best grasp off by more than 2 cm in world")
# ... and judged on the true barbell: the fingers close on it.
judged = 0
for b in best:
    json.dump({"frame": "world", "grasps": [{"position": b["position"], "orientation_xyzw": b["orientation_xyzw"],
                                             "score": 1.0}]}, open(T + "/best.json", "w"))
    r = subprocess.run([BIN, "evaluate", "--truth", T + "/sim/truth.yaml", "--grasps", T + "/best.json",
                        "--json", T + "/eval.json"], capture_output=True, text=True)
    j = json.load(open(T + "/eval.json"))["judgements"][0]
    judged += j["outcome"] not in ("miss", "other_object")
check(best and judged == len(best), "%d of %d best grasps close on the barbell" % (judged, len(best)))
# The malformed messages: one error each, naming the problem; then a good cloud gave grasps.
errors = bad[-1]["errors"]
for word in ["no field 'y'", "point_step", "bytes", "no finite point", "empty", "nowhere_optical", "no_such_key"]:
    check(sum(word in e for e in errors) == 1, "expected one ROS_ERROR naming %r, got %s" % (word, errors))
check(len(errors) == 7, "%d errors for 7 bad inputs" % len(errors))
check(len(bad) >= 2 and bad[0]["grasps"], "no grasps for the good cloud after the bad ones")
# ~set_enabled false: a cloud is not processed; ~detect_once processes it and says so.
check(bad[-1].get("while_disabled") == 0, "the disabled node processed a cloud")
once = bad[-1].get("detect_once", {})
check(once.get("success") and "grasps" in once.get("message", "") and len(bad) == 3,
      "~detect_once: %s, %d GraspArrays" % (once, len(bad) - 1))
lat = sorted(a["latency_ms"] for a in arrays)
if lat:
    print("latency from arrival to published grasps over %d frames: median %.1f ms, 95th percentile %.1f ms"
          % (len(lat), lat[len(lat) // 2], lat[min(len(lat) - 1, int(0.95 * (len(lat) - 1) + 0.5))]))
print("dropped %d; %d frames with grasps; %d best grasps judged on the barbell" % (arrays[-1]["dropped"] if arrays else -1,
                                                                                  with_grasps, judged))
sys.exit(0 if ok else 1)
PY
[[ $fails -eq 0 ]] && echo "ros_node: passed" || { echo "--- launch.log"; tail -20 "$T/launch.log"; exit 1; }
