#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
# A stand-in for Blender (ICGP_BLENDER) that answers the Cycles backend's first three
# requests and then crashes, as a real Blender may mid-run.
echo "Blender (stand-in) starting"
n=0
while read line; do
  n=$((n + 1))
  if [ $n -gt 3 ]; then
    echo "Segmentation fault (stand-in, request $n)"
    exit 139
  fi
  echo ok >&3
done
