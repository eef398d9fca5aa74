#!/usr/bin/env bash
# Installs what is missing, builds, and starts Wisp on its built-in head and hairstyle.
# Extra arguments go to the program.
set -euo pipefail

cd "$(dirname "$0")/.."
scripts/setup.sh
if [ -x build/app/wisp ]; then
  exec build/app/wisp "$@"
fi
# Until the editor lands: the headless simulation on the default head.
exec build/app/wisp-cli simulate --steps 240 "$@"
