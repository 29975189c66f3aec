#!/usr/bin/env bash
# Installs the Debian 12 packages planet needs (only those missing), then configures and
# builds it with a CMake preset (default: release; PLANET_PRESET=debug|asan|fuzz for the others).
# Installing needs root: run as root or with sudo; otherwise the script lists what is missing
# and stops.
set -euo pipefail
cd "$(dirname "$0")/.."

# Compiler and build; Vulkan loader, lavapipe (Vulkan on the CPU) and the validation layers;
# glslang for GLSL -> SPIR-V at build time; libraries; GoogleTest; libnoise (the peer noise
# library `planet bench noise` compares against); stb (PNG files for renders and golden images);
# matplotlib (the frame-time plot of `planet bench --plot`, drawn by python3); ffmpeg (the videos
# of `planet render --path`; its tests read them back with ffprobe); GLFW and Dear ImGui for the
# viewer (`planet view`), and Xvfb, the virtual display its test runs under.
packages=(
  build-essential cmake ninja-build
  libvulkan-dev mesa-vulkan-drivers
  vulkan-validationlayers
  glslang-tools spirv-tools
  libglm-dev libfmt-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev
  libgtest-dev
  libnoise-dev
  libstb-dev
  python3-matplotlib
  ffmpeg
  libglfw3-dev libimgui-dev
  xvfb xauth xdotool
)
preset=${PLANET_PRESET:-release}
# The fuzz preset (tools/fuzz.sh) builds the parsers' libFuzzer targets with clang.
if [[ $preset == fuzz ]]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if ((${#missing[@]})); then
  if [[ $EUID -ne 0 ]]; then
    echo "planet setup: missing Debian packages: ${missing[*]}" >&2
    echo "Installing them needs root. Run: sudo $0   (or: sudo apt-get install ${missing[*]})" >&2
    exit 1
  fi
  echo "planet setup: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

echo "planet setup: configuring and building (preset $preset)"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
