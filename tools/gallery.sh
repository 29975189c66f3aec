#!/bin/sh
# Renders the README gallery into a folder (default docs/gallery):
#   - seed 002's Figures 5.1-5.4 equivalents: one fBm, cascade, hybrid and ridged planet each,
#     shaded by height only (tools/gallery/*.toml), from orbit and from 600 km;
#   - a descent on the default planet: orbit -> 100 km -> 10 km -> 1 km -> 2 m, at noon, at
#     sunset, at dusk and at the end of nautical twilight (sky, clouds, water and stars: issue 4;
#     the last two at auto exposure, issue 21), the first four beside the same views of the earth
#     preset before issue 10;
#   - the moon and mars presets from the ground, the moon from orbit;
#   - the system (issue 8) and its eclipses (issue 23);
#   - earth's city lights at night from orbit, at dusk, and from 30 km; its airglow from 400 km;
#     at auto exposure, its cities from 400 km and the terminator from 12,000 km;
#   - issue 11's matrix: earth, mars and the moon at five altitudes, noon and low sun (half size);
#   - seed 000's figures remade (issue 13): random faults after 1, 10, 100 and 1,000 steps,
#     midpoint displacement after 1, 3, 5 and 7 levels, and its eight colouring schemes;
#   - the system scene, and the ringed giant with its air (issue 23).
# Usage: tools/gallery.sh [OUTPUT_DIR] [WIDTHxHEIGHT]   (run from the repository root after a build)
set -eu
out=${1:-docs/gallery}
size=${2:-960x540}
planet=${PLANET:-./build/release/apps/planet}
[ -x "$planet" ] || { echo "gallery: $planet not found; build first (./tools/setup.sh)" >&2; exit 1; }
mkdir -p "$out"
render() {  # NAME ARGS...
  name=$1; shift
  echo "gallery: $out/$name.png"
  "$planet" render --size "$size" --out "$out/$name.png" "$@" > /dev/null
}
for type in fbm cascade hybrid ridged; do
  render "fig_$type" --preset "tools/gallery/$type.toml" --camera 25,-40,1.4e7 --sun 150,50
  render "fig_${type}_600km" --preset "tools/gallery/$type.toml" --camera 25,-40,6e5,30,-35 --sun 150,30
done
# Descent onto a mountain range of the default planet (earth) at 45° N: the eroded ranges of a
# belt, seen from orbit, 100 km, 10 km, 1 km above the ground and 2 m, at noon and at sunset.
# The same views of the earth preset as it was before issue 10 (tools/gallery/earth_before_issue10.toml)
# make the before/after pairs. Positions chosen from `planet stats` and `planet height`.
before=tools/gallery/earth_before_issue10.toml
for preset in earth before; do
  p=earth; [ $preset = before ] && p=$before
  render ${preset}_1_orbit --preset $p --camera 40,80,8e6 --sun 150,45
  render ${preset}_2_100km --preset $p --camera 45.25,81.4,1e5,90,-30 --sun 150,35
  render ${preset}_3_10km --preset $p --camera 45.25,82.6,1e4,90,-12 --sun 150,35
  render ${preset}_4_1km --preset $p --camera 45.25,83.0,4300,90,-20 --sun 150,35
done
render descent_5_2m --camera 45.3,83.0,0,90,-2 --sun 150,35
render descent_6_2m_sunset --camera 45.3,83.0,0,90,0 --sun 270,3
render sea_2m_noon --camera 20,-30,2,90,5 --sun 135,50
render sea_2m_sunset --camera 20,-30,2,135,3 --sun 135,1
render dusk_2m --camera 45.3,83.0,0,0,4 --sun 30,-9 --exposure auto
render night_2m --camera 45.3,83.0,0,0,4 --sun 30,-12 --exposure auto
render moon_orbit --preset moon --camera -20,40,4e6 --sun 100,40
render moon_ground --preset moon --camera -20,40,2,0,-15 --sun 100,12
render mars_ground --preset mars --camera -5,140,2,60,5 --sun 100,30
render mars_orbit --preset mars --camera 20,-100,1.2e7 --sun 120,40
# City lights (issue 14): the night side from 12,000 km (the sun 60 deg below the horizon at the
# nadir), the terminator at dusk with the lights coming on, a coast's cities from 30 km.
render lights_night_orbit --camera 20,-30,1.2e7 --sun 135,-60
render lights_dusk_orbit --camera 20,-30,1.2e7 --sun 135,-3
render lights_night_30km --camera 2,-28,3e4,0,-30 --sun 30,-30
render airglow_orbit --camera 0,-150,4e5,0,-12 --sun 30,-60 --exposure auto
# At auto exposure (the viewer's): a coast's cities from 400 km under the airglow, and the
# terminator from 12,000 km with the night side exposed for its lights.
render lights_400km_auto --camera 2,-28,4e5,0,-20 --sun 30,-30 --exposure auto
render terminator_orbit_auto --camera 20,-30,1.2e7 --sun 30,-30 --exposure auto
# The system (planet render --scene system, issue 8): from the Moon's surface to Terra's, at one
# time: Terra in the Moon's sky, Terra from 1,000 km above the Moon and from 30,000 km, 400 km
# over Terra, and the ringed giant with the Moon in Terra's afternoon sky.
t=66500
render system_1_moon_ground --scene system --time $t --camera Moon:1,162,-1e5,88.4,14
render system_2_moon_1000km --scene system --time $t --camera Moon:1,162,1e6 --look-at Terra
render system_3_terra_30000km --scene system --time $t --camera Terra:6.7,162.9,3e7,0,-90
render system_4_terra_400km --scene system --time $t --camera Terra:10,170,4e5,270,-30
render system_5_terra_ground --scene system --time $t --camera Terra:5,172,0 --look-at Giant
render system_giant --scene system --time 30000 --camera Terra:89,0,3e7 --look-at Giant --fov 20
# Eclipses in the system (issue 23, at 640x360): the Moon's shadow on Terra from 8,000 km and
# from 400 km inside it looking out, the Moon half inside Terra's umbra, and wholly inside it
# at a long exposure (red with the light Terra's air bends into its shadow; system.toml).
for eclipse in "solar:7867740:Terra:0.04,127.86,8e6,0,-90" "solar_400km:7867740:Terra:0.04,131,4e5,90,-25" \
  "lunar:7938860:Terra:0.27,2.02,2e7 --look-at Moon --fov 10" \
  "lunar_total:7941160:Terra:0.27,2.02,2e7 --look-at Moon --fov 10 --exposure 20000"; do
  name=${eclipse%%:*}; rest=${eclipse#*:}; time=${rest%%:*}; camera=${rest#*:}
  echo "gallery: $out/system_eclipse_$name.png"
  # shellcheck disable=SC2086 # the camera and its options split into words
  "$planet" render --size 640x360 --scene system --time "$time" --camera $camera \
    --out "$out/system_eclipse_$name.png" > /dev/null
done
# The giant's air and its rings in it (issue 23, point 4): from Terra's distance, and the limb
# from 42,000 km with the rings passing behind it through the haze.
render giant_rings_far --scene system --time 30000 --camera Terra:89,0,3e7 --look-at Giant --fov 12 --exposure 5
render giant_rings_limb --scene system --time 30000 --camera Giant:10,-71,4.2e7,88,-53 --fov 8 --exposure 5
# Issue 11's matrix: earth, mars and the moon from orbit (8,000 km), 400 km, 10 km, 1 km and
# 2 m above the ground below, at noon (sun 60° up) and at low sun (5°), at half size, for
# comparison with photographs
# (docs/gallery/matrix_BODY_ALTITUDE_SUN.png).
matrix_size=$(echo "$size" | awk -Fx '{ printf "%dx%d", $1 / 2, $2 / 2 }')
for body in earth:45.3,83.0 mars:-5,140 moon:-20,40; do
  preset=${body%%:*}; at=${body#*:}
  ground=$("$planet" height --preset "$preset" --at "$at")
  for view in orbit:8e6,0,-90 400km:4e5,90,-40 10km:1e4,90,-12 1km:1000,90,-15 2m:2,90,-5; do
    name=${view%%:*}; camera=${view#*:}
    above=${camera%%,*}
    camera=$(awk -v g="$ground" -v a="$above" 'BEGIN { printf "%.1f", g + a }'),${camera#*,}
    for sun in noon:150,60 low:270,5; do
      echo "gallery: $out/matrix_${preset}_${name}_${sun%%:*}.png"
      "$planet" render --size "$matrix_size" --preset "$preset" --camera "$at,$camera" --sun "${sun#*:}" \
        --out "$out/matrix_${preset}_${name}_${sun%%:*}.png" > /dev/null
    done
  done
done
# Seed 000's figures (issue 13): faults after 1, 10, 100 and 1,000 steps and MPD after 1, 3, 5
# and 7 levels (tools/gallery/seed000_*.toml with the count written in), and the earth preset
# in each of seed 000's eight colouring schemes, without air and clouds (half size).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for count in 1 10 100 1000; do
  amplitude=$(awk -v n=$count 'BEGIN { printf "%.0f", 1000 / sqrt(n) }')
  sed -e "s/= COUNT/= $count/" -e "s/= AMPLITUDE/= $amplitude/" tools/gallery/seed000_faults.toml > "$work/faults.toml"
  render seed000_faults_$count --preset "$work/faults.toml" --camera 0,60,1e7 --sun 150,50
done
for levels in 1 3 5 7; do
  sed -e "s/= LEVELS/= $levels/" tools/gallery/seed000_mpd.toml > "$work/mpd.toml"
  render seed000_mpd_$levels --preset "$work/mpd.toml" --camera 30,20,1e7 --sun 150,50
done
for scheme in altitude altitude_perturbed noise altitude_noise turbulence earth_like gradient moon_like; do
  # The earth preset with the scheme, its ground colours (the scheme's palette instead), air
  # and clouds left out.
  awk -v scheme=$scheme '
    /^\[/ { skip = ($0 == "[atmosphere]" || $0 == "[clouds]") }
    skip { next }
    /^scheme = / { print "scheme = \"" scheme "\""; next }
    /^(lowland|highland|cliff|snow) = / { next }
    { print }' engine/planet/presets/earth.toml > "$work/$scheme.toml"
  echo "gallery: $out/seed000_scheme_$scheme.png"
  "$planet" render --size "$matrix_size" --preset "$work/$scheme.toml" --camera 20,-30,8e6 --sun 0,60 \
    --out "$out/seed000_scheme_$scheme.png" > /dev/null
done
echo "gallery: done ($out)"
