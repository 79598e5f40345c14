#!/bin/bash
# The display itself split over hosts (config/pipelines/demo-hosts.yaml): network namespaces h1
# (vision: the hand tracker), h2 (display: planner, physics, supervisor), h3 (robot: arm_sim and
# the scripted user) and h4 (monitor: display_metrics), each with its own address on a bridge,
# DDS over UDP only, the real clock. First the user's scripted run end to end: the hand's track,
# the wrist's force, the setpoints and the arm's state cross the hosts, the display switches to
# admittance on the touch, and the monitor judges the contacts. Then each group in turn is frozen
# (SIGSTOP) for 2 s in the middle of the run and thawed:
#   display: the arm holds within 3 of its setpoint stream's periods (250 Hz: 12 ms), noticed at
#            its first tick after them, naming the lost process; thawed, the
#            supervisor starts it again the normal way (its request, then idle -> surface);
#   robot:   the supervisor holds (no wrist reading) and, the arm back, starts it again;
#   vision:  the display carries on with the hand's last track (it never holds for the hand) and
#            the run ends.
# Each freeze is also named by the stream's DDS deadline in the process that reads it. Then each
# group's link is taken down for 2 s: the same holds. Then each group is killed (SIGKILL) and
# started again after 1 s:
#   display: the arm holds as when frozen; the restarted display's setpoint and requests own their
#            topics once the killed writers' liveliness lapsed (0.5 s; the setpoint's deadline may
#            come first), not after its participant's 5 s lease, and its supervisor starts the arm
#            again;
#   robot:   the supervisor holds; the restarted arm stands parked elsewhere, and the supervisor
#            holds it there (no setpoint refused) before the display starts again;
#   vision:  the display carries on.
# Whenever the display's group is lost, the monitor on h4 records joint states, setpoints and the
# arm's status across the loss: the arm held within 3 of the stream's periods as recorded, and no
# joint sped up once the tracker stopped carrying it on (hold_after_loss.py). In every case the
# user's script runs to its end. Needs root; exits 77 (skipped) without it.
# Usage: demo_hosts.sh <build dir> <source dir> <domain>
set -uo pipefail
build=$1 src=$2 domain=$3
cli="$build/bin/wysiwyf"
tag="wd$$"
work=$(mktemp -d)
pids=()

# shellcheck source=namespaces.sh
source "$src/tests/net/namespaces.sh"
make_hosts "$tag" 10.78.0 4

declare -A host=([vision]=h1 [display]=h2 [robot]=h3 [monitor]=h4) pid=()
start_group() {  # start_group <group>: its process in its host, log in $work/<group>.log (appended)
  ip netns exec "$tag-${host[$1]}" "$cli" run "$src/config/pipelines/demo-hosts.yaml" --process "$1" \
    --set domain="$domain" --set metrics.params.summary="$work/metrics.json" --no-progress >>"$work/$1.log" 2>&1 &
  pid[$1]=$!
  pids+=("$!")
}
record_across_the_loss() {  # in $work/joints.yaml, $work/setpoints.yaml and $work/statuses.yaml
  local t
  for t in joints:joint_state setpoints:setpoint statuses:status; do
    ip netns exec "$tag-${host[monitor]}" timeout 2.5 "$cli" topic echo "robot/${t#*:}" --domain "$domain" \
      --transport udp --timeout 2 >"$work/${t%%:*}.yaml" 2>/dev/null &
  done
}
run_display() {  # run_display <group or ""> [stop|link|kill]: one scripted run, the group frozen
  # (SIGSTOP) or cut off (its link down) for 2 s, or killed (SIGKILL) and started again after 1 s
  for g in robot display vision monitor; do
    : >"$work/$g.log"
    start_group "$g"
  done
  if [[ -n $1 ]]; then
    # At 5 s the user is reaching for the cube's knob, or pushing it. The display is lost at 7 s,
    # as the plate relocates to the cube's -y face (joint 4 at about 2 rad/s), and the monitor's
    # host records joint states, setpoints and the arm's status from 1.5 s before it to 1 s after
    # (before a killed display's successor writes).
    if [[ $1 == display ]]; then
      sleep 5.5
      record_across_the_loss
    else
      sleep 3.5
    fi
    sleep 1.5
    case ${2:-stop} in
      link)
        ip -n "$tag-${host[$1]}" link set eth0 down
        sleep 2
        ip -n "$tag-${host[$1]}" link set eth0 up
        ip -n "$tag-${host[$1]}" route add 224.0.0.0/4 dev eth0 ;;  # (gone with the link)
      kill)
        kill -KILL "${pid[$1]}"
        wait "${pid[$1]}" 2>/dev/null
        echo "=== killed, started again" >>"$work/$1.log"
        sleep 1
        start_group "$1" ;;
      *)
        kill -STOP "${pid[$1]}"
        sleep 2
        kill -CONT "${pid[$1]}" ;;
    esac
  fi
  # The robot's group ends with the user's script (stop_when_done); the others are stopped after.
  for _ in $(seq 90); do kill -0 "${pid[robot]}" 2>/dev/null || break; sleep 1; done
  sleep 1
  for g in display vision monitor robot; do kill -INT "${pid[$g]}" 2>/dev/null; done
  for g in display vision monitor robot; do wait "${pid[$g]}" 2>/dev/null; done
}

failures=0
check() {  # check <what> <command...>: counts a failure, prints the logs
  local what=$1
  shift
  if "$@"; then
    echo "$what"
  else
    echo "FAILED: $what"
    for g in robot display vision monitor; do echo "--- $g"; grep -v "no component of this pipeline publishes" "$work/$g.log" | head -60; done
    failures=$((failures + 1))
  fi
}
script_done() { grep -Eq "script done: 2 reach\(es\)" "$work/robot.log"; }
hits() { grep -o "script done: .*" "$work/robot.log"; }
# The arm's loss of its setpoint stream, from the monitor's records (hold_after_loss.py): within 3
# of the stream's periods as recorded (250 Hz, 4 ms; 5-18 ms on this 2-core machine running four
# hosts and a build, so measured, not assumed), noticed at the arm's first tick after the timeout,
# and no joint sped up once the tracker stopped carrying the arm on along the last setpoint (for
# one period from its arrival, as the arm saw it).
arm_held_within_3_periods() {  # arm_held_within_3_periods <what happened>
  local checks line
  wait  # (the monitor's records)
  checks=$(python3 "$src/tests/net/hold_after_loss.py" "$work/joints.yaml" "$work/setpoints.yaml" "$work/statuses.yaml")
  while IFS= read -r line; do
    check "$1: ${line#FAILED: }" test "${line#FAILED: }" = "$line"
  done <<<"$checks"
  check "$1: the arm named the lost display's process" \
    grep -q "setpoint stream lost: .* from 'supervisor/[a-z]*' in process 'demo-hosts/display/[0-9]*'" <<<"$checks"
}

# 1. The scripted run across the hosts.
run_display ""
check "the user's script ran to its end across four hosts: $(hits)" script_done
check "the display switched to admittance on a touch (h2), from the wrist's force (h3)" \
  grep -q "surface -> admittance: touch" "$work/display.log"
check "no DDS endpoint was refused between the hosts (QoS, ownership)" \
  bash -c "! grep -h 'refused' '$work'/*.log"
check "the monitor on h4 judged the contacts: $(grep -o '[0-9]* contact(s), [0-9]* hit(s)' "$work/monitor.log")" \
  grep -q "contact(s), [1-9][0-9]* hit(s)" "$work/monitor.log"
check "the monitor on h4 read the one-writer setpoint (sensor to setpoint: $(grep -o 'wrench): p50 [0-9.]* ms' "$work/monitor.log"))" \
  grep -q "sensor sample to setpoint (wrench)" "$work/monitor.log"

# 2. The display's group frozen for 2 s.
run_display display
arm_held_within_3_periods "display frozen"
check "display frozen: the robot's process named it by the setpoint's DDS deadline (12 ms)" \
  grep -q "topic 'robot/setpoint': no sample for its deadline (12 ms) from 'demo-hosts/display/" "$work/robot.log"
check "display thawed: the supervisor started the arm again through idle -> surface" \
  bash -c "grep -q \"cleared the input fault 'setpoint stream lost\" '$work/robot.log' &&
           grep -A2 'fault -> idle' '$work/display.log' | grep -q 'idle -> surface'"
check "display frozen and thawed, the user's script ran to its end: $(hits)" script_done

# 3. The robot's group frozen for 2 s.
run_display robot
check "robot frozen: the supervisor held ($(grep -o -m1 'fault: no wrist reading for [0-9.]* s' "$work/display.log"))" \
  grep -q "> fault: no wrist reading" "$work/display.log"
check "robot frozen: the display's process named it by the wrist reading's DDS deadline (30 ms)" \
  grep -q "topic 'robot/wrench': no sample for its deadline (30 ms) from 'demo-hosts/robot/" "$work/display.log"
check "robot thawed: the arm held (its stream lost while it was frozen) until the supervisor started it again" \
  bash -c "grep -q \"cleared the input fault 'setpoint stream lost\" '$work/robot.log' &&
           grep -A2 'fault -> idle' '$work/display.log' | grep -q 'idle -> surface'"
stale=$(grep -c "rejected a sample: stale" "$work/robot.log")
check "robot thawed: the setpoints that waited for it were refused as stale, one warning for all ($stale)" test "$stale" -le 1
check "robot frozen and thawed, the user's script ran to its end: $(hits)" script_done

# 4. The vision group frozen for 2 s.
run_display vision
check "vision frozen and thawed, the user's script ran to its end: $(hits)" script_done
check "vision frozen: the display's process named it by the hand's DDS deadline (50 ms)" \
  grep -q "topic 'hand/position': no sample for its deadline (50 ms) from 'demo-hosts/vision/" "$work/display.log"
# (The 250 Hz stream may still be lost once to a scheduling stall of this busy machine, vision or
# not: what the freeze must not do is hold the display. The same goes for the planner's own
# fault, its joint states or device pose overdue: those come from the robot's host, not the
# vision's (in a full ctest run the robot's process once stalled over 50 ms while vision was
# frozen, its wrist reading late 74 times: the planner held, alone of the run's checks).)
never_held_for_vision() {
  local holds
  holds=$(grep -E '> fault: .*(hand|planner)' "$work/display.log" | grep -v 'no joint state or device pose')
  [ -z "$holds" ] && return 0
  echo "the display held: $(head -3 <<<"$holds")"
  return 1
}
check "vision frozen: the display never held for the hand or the planner" never_held_for_vision

# 5. Each group's link down for 2 s.
run_display display link
arm_held_within_3_periods "display cut off"
check "display reconnected: the supervisor started the arm again through idle -> surface" \
  bash -c "grep -q \"cleared the input fault 'setpoint stream lost\" '$work/robot.log' &&
           grep -A3 'fault -> idle' '$work/display.log' | grep -q 'idle -> surface'"
check "display cut off and reconnected, the user's script ran to its end: $(hits)" script_done
run_display robot link
check "robot cut off: the display's process named it by the wrist reading's DDS deadline (30 ms)" \
  grep -q "topic 'robot/wrench': no sample for its deadline (30 ms) from 'demo-hosts/robot/" "$work/display.log"
check "robot cut off: the supervisor held, and started the arm again once it was back" \
  bash -c "grep -q '> fault: no wrist reading' '$work/display.log' &&
           grep -q \"cleared the input fault 'setpoint stream lost\" '$work/robot.log'"
check "robot cut off and reconnected, the user's script ran to its end: $(hits)" script_done
run_display vision link
check "vision cut off: the display's process named it by the hand's DDS deadline (50 ms)" \
  grep -q "topic 'hand/position': no sample for its deadline (50 ms) from 'demo-hosts/vision/" "$work/display.log"
check "vision cut off and reconnected, the user's script ran to its end: $(hits)" script_done
# 6. Each group killed (SIGKILL) and started again after 1 s.
run_display display kill
arm_held_within_3_periods "display killed"
check "display restarted: its setpoint writer owned the topic once the killed one lost its liveliness (0.5 s) or missed its deadline (not after its 5 s lease)" \
  grep -Eq "topic 'robot/setpoint': its writer 'demo-hosts/display/.*(lost its liveliness|missed its deadline; 'demo-hosts/display/.* owns it now)" "$work/robot.log"
check "display restarted: its supervisor started the arm again (request, hold where it stands, idle -> surface)" \
  bash -c "grep -q \"cleared the input fault 'setpoint stream lost\" '$work/robot.log' &&
           sed -n '/=== killed/,\$p' '$work/display.log' | grep -A3 'fault -> idle' | grep -q 'idle -> surface'"
check "display killed and restarted, the user's script ran to its end: $(hits)" script_done
run_display robot kill
check "robot killed: the supervisor held ($(grep -o -m1 'fault: no wrist reading for [0-9.]* s' "$work/display.log"))" \
  grep -q "> fault: no wrist reading" "$work/display.log"
check "robot restarted elsewhere (parked): the supervisor's first setpoint was where the arm stood, none refused" \
  bash -c "! sed -n '/=== killed/,\$p' '$work/robot.log' | grep -q 'setpoint rejected'"
check "robot restarted: the display started again through idle -> surface" \
  bash -c "grep -A3 'fault -> idle' '$work/display.log' | grep -q 'idle -> surface'"
check "robot killed and restarted, its user's script ran to its end: $(hits)" script_done
run_display vision kill
check "vision killed and restarted, the user's script ran to its end: $(hits)" script_done
check "vision killed: the display never held for the hand or the planner" never_held_for_vision
exit $((failures > 0))
