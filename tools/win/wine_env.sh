# Sourced by the Windows test scripts: a private wine prefix (made once,
# outside the repository), no wine debug output, no display.
export WINEPREFIX=${WINEPREFIX:-${BANYAN_WIN_CACHE:-$HOME/.cache/banyan/win}/wineprefix}
export WINEDEBUG=${WINEDEBUG:--all}
export WINEDLLOVERRIDES=${WINEDLLOVERRIDES:-mscoree,mshtml=}
unset DISPLAY
# Debian's wine64 lives in /usr/lib/wine; its wrapper is not on PATH.
command -v wine64 >/dev/null || export PATH=$PATH:/usr/lib/wine
if [ ! -f "$WINEPREFIX/system.reg" ]; then
  mkdir -p "$WINEPREFIX"
  wine64 wineboot --init >/dev/null 2>&1 || true
  wineserver -w 2>/dev/null || true
fi
