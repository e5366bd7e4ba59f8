#!/usr/bin/env bash
# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0
#
# The colcon-wasm demo in one command: install what is missing, build the
# bundled demo workspace (demo/src) with `colcon build --wasm`, serve it and
# print the URL to open.
#
#   scripts/demo.sh [--port N] [--host ADDR] [--build-only]
#
# Environment: COLCON_WASM_VENV (default: .venv in the repository) is the
# Python virtual environment colcon-wasm is installed into.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="${COLCON_WASM_VENV:-$repo/.venv}"
port=8000
host=127.0.0.1
serve=1
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port="$2"; shift 2 ;;
    --host) host="$2"; shift 2 ;;
    --build-only) serve=0; shift ;;
    -h|--help) sed -n '5,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "demo.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
  esac
done

say() { printf '\033[1m==> %s\033[0m\n' "$*"; }

# 1. System tools: Emscripten, Node.js, CMake, a C++ compiler, Python venv.
missing=()
command -v emcc >/dev/null || [ -x /usr/share/emscripten/emcc ] || missing+=(emscripten)
command -v node >/dev/null || missing+=(nodejs)
command -v cmake >/dev/null || missing+=(cmake)
command -v c++ >/dev/null || missing+=(g++)
python3 -c 'import venv, ensurepip' 2>/dev/null || missing+=(python3-venv)
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    say "Installing ${missing[*]} (apt-get)"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}"
  else
    echo "demo.sh: missing ${missing[*]}; install them, e.g.:" >&2
    echo "  sudo apt-get install ${missing[*]}" >&2
    echo "  (or Emscripten from emsdk: https://emscripten.org/docs/getting_started/)" >&2
    exit 1
  fi
fi

# 2. colcon-wasm itself, in a virtual environment.
if [ ! -x "$venv/bin/colcon-wasm" ]; then
  say "Installing colcon-wasm into $venv"
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --upgrade pip
  "$venv/bin/pip" install -q "$repo"
fi
export PATH="$venv/bin:$PATH"

# 3. Build the demo workspace to WebAssembly.
say "Building the demo workspace (demo/src) with colcon build --wasm"
cd "$repo/demo"
nice -n 10 colcon build --wasm --event-handlers console_cohesion+

# 4. Serve it.
if [ "$serve" = 1 ]; then
  say "Serving the launcher page"
  echo "Open http://$host:$port/ and press 'Run' next to talker and listener,"
  echo "or open http://$host:$port/?run=demo_nodes/talker&run=demo_nodes/listener"
  exec colcon-wasm serve --install-base install_wasm --host "$host" --port "$port"
fi
echo "Built: $repo/demo/install_wasm (serve it with: colcon-wasm serve --install-base demo/install_wasm)"
