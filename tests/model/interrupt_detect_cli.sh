#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Ctrl-C while `icgp track --init detect` waits for its first detection on a cold cache:
# sends SIGINT once the viewpoint models' generation has printed its first progress line,
# and checks that the command stops with exit status 130, saying so, and leaves no
# temporary file of a model being written in the cache folder.
# Usage: interrupt_detect_cli.sh ICGP SEQUENCE OUT
set -u
icgp=$1 sequence=$2 out=$3
rm -rf "$out" && mkdir -p "$out/cache"
printf 'cache_dir: %s\n' "$out/cache" >"$out/config.yaml"
"$icgp" track --sequence "$sequence" --init detect --config "$out/config.yaml" >"$out/stdout.txt" 2>"$out/stderr.txt" &
. "$(dirname "$0")/stop_during_generation.sh"
stop_at_first_progress $!
grep -q '^icgp: stopped on request' "$out/stderr.txt" || fail "no 'stopped on request' line"
partial=$(find "$out/cache" -type f -name '*.tmp.*' | wc -l)
[ "$partial" -eq 0 ] || fail "$partial half-written files left in the cache folder: $(ls "$out/cache")"
echo "icgp track --init detect interrupt test passed: exit status 130, no half-written cache file"
