# How a test run installs the zip as a user would: a new user folder, then the extension or the
# legacy add-on from the zip. Sourced: `install_zip ZIP extension|legacy` exports HOME (the new
# user folder), SOFTSHADOW_ZIP and SOFTSHADOW_ADDON_MODULE (the module tests enable).
# SPDX-License-Identifier: GPL-3.0-or-later
install_zip() {
  local zip=$1 mode=$2 blender=${BLENDER:-blender}
  export HOME; HOME=$(mktemp -d)
  unset SOFTSHADOW_LIB SOFTSHADOW_ADDON_PATH SOFTSHADOW_BUILD_DIR XDG_CONFIG_HOME BLENDER_USER_SCRIPTS
  local installed
  case "$mode" in
    extension)
      "$blender" --background --factory-startup --command extension install-file -r user_default \
        -e "$zip" >"$HOME/install.log" 2>&1
      installed=$?
      export SOFTSHADOW_ADDON_MODULE=bl_ext.user_default.softshadow ;;
    legacy)
      "$blender" --background --factory-startup --python-exit-code 1 --python-expr \
        "import bpy; bpy.ops.preferences.addon_install(filepath=r'$zip'); bpy.ops.wm.save_userpref()" \
        >"$HOME/install.log" 2>&1
      installed=$?
      export SOFTSHADOW_ADDON_MODULE=softshadow ;;
    *) echo "install_zip: mode must be extension or legacy, not '$mode'" >&2; return 2 ;;
  esac
  if [ "$installed" -ne 0 ]; then  # (the install command's own exit code, not the export's)
    echo "FAIL installing $zip as $mode (exit $installed)"; sed 's/^/    /' "$HOME/install.log"; return 1
  fi
  export SOFTSHADOW_ZIP="$zip"
  echo "installed $(basename "$zip") as $mode in $("$blender" --version 2>/dev/null | head -n 1)"
}
