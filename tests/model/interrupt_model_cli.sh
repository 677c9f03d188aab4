#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Ctrl-C during model generation: sends SIGINT once `icgp model` has printed its first
# progress line (with the time left), and checks that it stops at the next view with exit
# status 130, saying so, and leaves no cache file, whole or partial, in the cache folder.
# Usage: interrupt_model_cli.sh ICGP MESH OUT
set -u
icgp=$1 mesh=$2 out=$3
rm -rf "$out" && mkdir -p "$out/cache"
"$icgp" model "$mesh" --cache-dir "$out/cache" >"$out/stdout.txt" 2>"$out/stderr.txt" &
. "$(dirname "$0")/stop_during_generation.sh"
stop_at_first_progress $!
grep -q '^icgp: stopped on request while generating the region+depth model' "$out/stderr.txt" || fail "no 'stopped' line"
left=$(find "$out/cache" -type f | wc -l)
[ "$left" -eq 0 ] || fail "$left files left in the cache folder: $(ls "$out/cache")"
echo "icgp model interrupt test passed: exit status 130, no cache file left"
