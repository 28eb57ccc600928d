#!/bin/sh
# Regenerates the Python LCM types from the .lcm files here (lcm-gen from the lcm package).
set -e
cd "$(dirname "$0")"
out=$(mktemp -d)
lcm-gen --python --ppath "$out" *.lcm
cp "$out"/tegrasp/*.py .
rm -r "$out"
