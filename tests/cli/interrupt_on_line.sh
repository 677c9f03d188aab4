# SPDX-License-Identifier: GPL-2.0-or-later
# Sourced by the CTests that press Ctrl-C on an icgp command.
# interrupt_on_line PID FILE REGEX: waits until FILE (the command's output) has a line
# matching REGEX (the wait is bounded at 120 s, not timed), then sends SIGINT to PID and
# waits for it, leaving its exit status in $interrupted_status. Returns 1, having killed PID,
# when no such line came.
interrupt_on_line() {
  local pid=$1 file=$2 regex=$3
  for _ in $(seq 1200); do
    grep -Eq "$regex" "$file" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if ! grep -Eq "$regex" "$file"; then
    kill -KILL "$pid" 2>/dev/null
    return 1
  fi
  kill -INT "$pid"
  interrupted_status=0
  wait "$pid" || interrupted_status=$?
}
