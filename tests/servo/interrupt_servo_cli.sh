#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Ctrl-C on a batch of servo trials: sends SIGINT once the first trial has ended, and checks
# that `icgp servo` stops at its next step with exit status 130, prints the table of the
# trials done and writes them to the summary, marked interrupted.
# Usage: interrupt_servo_cli.sh ICGP SCENARIO OUT
set -u
icgp=$1 scenario=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
"$icgp" servo "$scenario" --tracker oracle --trials 200 --out "$out" --summary "$out/summary.json" \
  >"$out/stdout.txt" 2>"$out/stderr.txt" &
. "$(dirname "$0")/../cli/interrupt_on_line.sh"
if ! interrupt_on_line $! "$out/stderr.txt" '^trial 1/200'; then
  echo "FAIL: no trial ended within 120 s"; cat "$out/stderr.txt"; exit 1
fi
status=$interrupted_status
cat "$out/stdout.txt" "$out/stderr.txt"
fail() { echo "FAIL: $1"; exit 1; }
[ "$status" -eq 130 ] || fail "exit status $status, expected 130"
grep -Eq '^icgp: interrupted: [0-9]+ of 200 trials done' "$out/stderr.txt" || fail "no 'interrupted' line"
done=$(sed -nE 's/^icgp: interrupted: ([0-9]+) of 200.*/\1/p' "$out/stderr.txt")
[ "$done" -ge 1 ] && [ "$done" -lt 200 ] || fail "$done trials done"
grep -Eq "^oracle \(ground truth\) +$done " "$out/stdout.txt" || fail "the table does not hold the $done trials done"
grep -q '"interrupted": true' "$out/summary.json" || fail "summary.json is not marked interrupted"
grep -Eq "\"trials\": $done," "$out/summary.json" || fail "summary.json does not count $done trials"
echo "icgp servo interrupt test passed: $done of 200 trials done, exit status 130"
