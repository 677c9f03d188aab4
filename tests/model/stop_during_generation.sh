# SPDX-License-Identifier: GPL-2.0-or-later
# Sourced by the CTests that press Ctrl-C while icgp generates a viewpoint model; $out is
# the test's folder, holding the command's stdout.txt and stderr.txt.
# fail MESSAGE: prints it and the command's output, and exits 1.
# stop_at_first_progress PID: waits for the generation's first progress line with the time
# left, sends SIGINT to PID and checks that it ends with exit status 130.
. "$(dirname "${BASH_SOURCE[0]}")/../cli/interrupt_on_line.sh"
fail() { echo "FAIL: $1"; cat "$out/stdout.txt" "$out/stderr.txt"; exit 1; }
stop_at_first_progress() {
  interrupt_on_line "$1" "$out/stderr.txt" 'views, .* s left' || fail "no progress line with the time left within 120 s"
  cat "$out/stderr.txt"
  [ "$interrupted_status" -eq 130 ] || fail "exit status $interrupted_status, expected 130"
}
