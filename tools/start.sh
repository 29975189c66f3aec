#!/usr/bin/env bash
# The README's main job, after tools/setup.sh has built planet: the real-time viewer where a
# display exists, otherwise a headless render of the default planet to planet.png.
set -euo pipefail
cd "$(dirname "$0")/.."
planet=./build/${PLANET_PRESET:-release}/apps/planet
if [[ ! -x $planet ]]; then
  echo "planet: $planet is not built yet: run ./tools/setup.sh first" >&2
  exit 1
fi
if [[ -n ${DISPLAY:-} ]]; then
  exec "$planet" view
fi
echo "planet: no display (DISPLAY is not set), so no viewer window: rendering the default planet headless" >&2
exec "$planet" render --out planet.png
