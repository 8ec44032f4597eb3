#!/bin/sh
# `qorient sim`: options, errors naming the map's file and line, the "listening" contract.
Q=${QORIENT:-build/qorient}
pass=0; fail=0
tmp=${TMPDIR:-/tmp}/qorient-sim-cli.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT INT TERM
ok() { pass=$((pass + 1)); }
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }

"$Q" sim --help >"$tmp/out" 2>&1 && grep -q -- '--fault-share' "$tmp/out" && ok || ko "--help"
"$Q" sim >/dev/null 2>"$tmp/err"; [ $? -eq 2 ] && grep -q -- '--map FILE is required' "$tmp/err" && ok || ko "missing --map"
printf '[joint.a]\nslave = 1\naddress = 0\ntype = int16\nspeed = 3\n' >"$tmp/bad.ini"
"$Q" sim --map "$tmp/bad.ini" --duration 0 >/dev/null 2>"$tmp/err"; rc=$?
[ $rc -eq 2 ] && grep -q "bad.ini:5: unknown key 'speed'" "$tmp/err" && ok || ko "bad map (rc $rc): $(cat "$tmp/err")"
"$Q" sim --map examples/maps/six_int32.ini --fault wobble >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "bad --fault"
"$Q" sim --map examples/maps/six_int32.ini --fault-share 0.5 >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "share without kind"
"$Q" sim --map examples/maps/six_int32.ini --fault-share 1.5 --fault drop >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "share > 1"
"$Q" sim --map examples/maps/six_int32.ini --listen udp://x:1 --duration 0 >/dev/null 2>&1; [ $? -eq 2 ] && ok || ko "bad --listen"
"$Q" sim --map examples/maps/six_int32.ini --listen tcp://:0 --fault delay:5 --fault-after 3 \
    --seed 9 --lag 0.1 --log "$tmp/log.csv" --duration 0.1 >"$tmp/out" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -Eq '^listening tcp://127\.0\.0\.1:[1-9][0-9]*$' "$tmp/out" &&
   grep -q '^requests 0 target_writes 0 faults 0 connections 0 bad_frames 0$' "$tmp/out" &&
   [ "$(cat "$tmp/log.csv")" = "t_s,request,slave,joint_index,joint,value" ]; then ok
else ko "run for 0.1 s (rc $rc): $(cat "$tmp/out")"; fi
"$Q" sim --help | grep -q 'one master at a time' && ok || ko "--help does not say it serves one master at a time"
"$Q" sim --help | grep -q -- '--lag-dist' && ok || ko "--help does not document --lag-dist"
"$Q" sim --map examples/maps/six_int32.ini --lag-dist 0.5:1ms,x --duration 0 >/dev/null 2>"$tmp/err"; rc=$?
[ $rc -eq 2 ] && grep -q "bad --lag-dist" "$tmp/err" && ok || ko "bad --lag-dist (rc $rc)"
"$Q" sim --map examples/maps/six_int32.ini --lag-dist 0.97:0-0.2ms,0.03:5-12ms --listen tcp://localhost:0 \
    --duration 0 >"$tmp/out" 2>&1 && grep -Eq '^listening tcp://localhost:[1-9][0-9]*$' "$tmp/out" && ok ||
    ko "localhost: $(cat "$tmp/out")"
# IPv6 loopback (skipped where the machine has none)
if [ -e /proc/net/if_inet6 ] && grep -q '^0*1 ' /proc/net/if_inet6; then
    "$Q" sim --map examples/maps/six_int32.ini --listen 'tcp://[::1]:0' --duration 0 >"$tmp/out" 2>&1 &&
        grep -Eq '^listening tcp://\[::1\]:[1-9][0-9]*$' "$tmp/out" && ok || ko "[::1]: $(cat "$tmp/out")"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
