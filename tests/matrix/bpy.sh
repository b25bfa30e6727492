# How the version matrix gets Blender releases that Debian does not package: the `bpy` wheels of
# PyPI (Blender as a Python module, Python 3.11), each in its own cached virtual environment, with
# a `blender` wrapper that runs tests/matrix/bpy_blender.py. Sourced by tests/matrix/run.sh.
# SPDX-License-Identifier: GPL-3.0-or-later
BPY_CACHE=${SOFTSHADOW_BPY_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/softshadow}
# The LTS releases studios pin that no Debian suite has (exact versions: the cache is per version).
BPY_VERSIONS=${SOFTSHADOW_BPY_VERSIONS:-4.2.23 4.5.15}

bpy_python() {  # a Python 3.11 (the only Python the 4.2 and 4.5 wheels are built for)
  local py
  for py in "${SOFTSHADOW_BPY_PYTHON:-}" python3.11 /usr/bin/python3.11 python3; do
    [ -n "$py" ] && command -v "$py" >/dev/null 2>&1 || continue
    if "$py" -c 'import sys, venv; sys.exit(sys.version_info[:2] != (3, 11))' 2>/dev/null; then
      command -v "$py"; return 0
    fi
  done
  return 1
}

bpy_blender() {  # bpy_blender VERSION -> prints the wrapper's path; installs the wheel when missing
  local version=$1 venv="$BPY_CACHE/bpy-${1%.*}" py here
  here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  if ! "$venv/bin/python" -c "import sys, bpy; sys.exit(bpy.app.version_string.split()[0] != '$version')" \
       >/dev/null 2>&1; then
    py=$(bpy_python) || { echo "no Python 3.11 with venv for the bpy wheels" >&2; return 1; }
    rm -rf "$venv"; mkdir -p "$BPY_CACHE"
    if ! { "$py" -m venv "$venv" && "$venv/bin/pip" install -q --disable-pip-version-check \
           "bpy==$version"; } >"$BPY_CACHE/bpy-$version.log" 2>&1; then
      tail -n 5 "$BPY_CACHE/bpy-$version.log" >&2
      rm -rf "$venv"
      return 1
    fi
  fi
  # Written on every run: it names this checkout's driver.
  cat >"$venv/bin/blender" <<WRAPPER
#!/usr/bin/env bash
export SOFTSHADOW_BLENDER="\$0"
exec "$venv/bin/python" "$here/bpy_blender.py" "\$@"
WRAPPER
  chmod +x "$venv/bin/blender"
  echo "$venv/bin/blender"
}
