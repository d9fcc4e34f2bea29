#!/bin/sh
# The CLI never destroys an output file: a full disk (ulimit -f
# with SIGXFSZ ignored: write fails with EFBIG) or a run killed mid-write
# (SIGXFSZ at its default) leaves the old .glb / .png byte for byte, a
# symlink stays a link, and a bad -o is refused before anything is
# generated. Files go to OUT/cli_output/.
bin="$1"; src="$2"; out="$3/cli_output"
pass=0; fail=0
ok() { pass=$((pass+1)); }
no() { fail=$((fail+1)); echo "FAIL: $*"; }
temps() { find "$1" -maxdepth 1 -name '.*.tmp' | wc -l; }
# killed CMD...: CMD under the limit with SIGXFSZ at its default (an inner
# sh reports the death, to /dev/null); the status is 128 + SIGXFSZ.
killed() { sh -c 'trap - XFSZ; ulimit -f 100; "$@"' sh "$@" >/dev/null 2>&1; }
rm -rf "$out"; mkdir -p "$out"

# The old file and the bigger new one (about 60 KB and 940 KB); the limit
# is 100 blocks (50 KB in dash, 100 KB in bash), under both.
"$bin" tube -o "$out/plant.glb" >/dev/null || no "tube"
cp "$out/plant.glb" "$out/old.bin"
big="tube --set sides=256"

# Full disk: exit 1 naming the file, the old file as it was, no temp file.
msg=$( (trap '' XFSZ; ulimit -f 100; "$bin" $big -o "$out/plant.glb") 2>&1); rc=$?
[ $rc = 1 ] && echo "$msg" | grep -q "plant.glb" && ok || no "full disk: rc $rc, $msg"
cmp -s "$out/plant.glb" "$out/old.bin" && ok || no "full disk: the old .glb changed"
[ "$(temps "$out")" = 0 ] && ok || no "full disk: a temporary file was left"

# Killed mid-write (SIGXFSZ): the old file as it was; the temporary file may
# stay (the process had no chance to remove it), named .plant.glb.XXXXXX.tmp.
killed "$bin" $big -o "$out/plant.glb"; rc=$?
[ $rc -gt 128 ] && ok || no "killed: rc $rc, expected death by SIGXFSZ"
cmp -s "$out/plant.glb" "$out/old.bin" && ok || no "killed: the old .glb is cut or gone"
for t in "$out"/.*.tmp; do
  [ -e "$t" ] || continue
  case "$(basename "$t")" in .plant.glb.??????.tmp) ok ;; *) no "killed: odd temporary file $t" ;; esac
  rm -f "$t"
done

# Through a symlink: a failed write keeps link and target; a good one
# replaces the target whole (the same bytes as a direct write).
ln -s plant.glb "$out/link.glb"
(trap '' XFSZ; ulimit -f 100; "$bin" $big -o "$out/link.glb") >/dev/null 2>&1
[ -L "$out/link.glb" ] && [ "$(readlink "$out/link.glb")" = plant.glb ] && ok || no "full disk via link: link gone"
cmp -s "$out/plant.glb" "$out/old.bin" && ok || no "full disk via link: the target changed"
"$bin" $big -o "$out/link.glb" >/dev/null && "$bin" $big -o "$out/direct.glb" >/dev/null || no "write via link"
[ -L "$out/link.glb" ] && ok || no "write via link: the link was replaced by a file"
cmp -s "$out/plant.glb" "$out/direct.glb" && ok || no "write via link: the target is not the whole new file"
[ "$(temps "$out")" = 0 ] && ok || no "link: a temporary file was left"

# An unwritable folder (as nobody when run as root): refused naming -o,
# the old file (itself writable) as it was.
mkdir -p "$out/ro"; cp "$out/old.bin" "$out/ro/plant.glb"; chmod 666 "$out/ro/plant.glb"; chmod 555 "$out/ro"
as=""
[ "$(id -u)" = 0 ] && command -v setpriv >/dev/null && as="setpriv --reuid=65534 --regid=65534 --clear-groups"
if [ "$(id -u)" != 0 ] || [ -n "$as" ]; then
  msg=$($as "$bin" tube -o "$out/ro/plant.glb" 2>&1); rc=$?
  [ $rc = 2 ] && echo "$msg" | grep -q -- "-o $out/ro/plant.glb: folder '$out/ro' is not writable" && ok ||
    no "unwritable folder: rc $rc, $msg"
  cmp -s "$out/ro/plant.glb" "$out/old.bin" && ok || no "unwritable folder: the old .glb changed"
fi
chmod 755 "$out/ro"

# A bad -o is refused before generating: no progress line on a terminal,
# no stats, exit 2, the message names -o and the path.
check_o() { # check_o NEEDLE PATH
  msg=$("$bin" avenue --preset "$src/presets/avenue_boulevard.json" --stats -o "$2" 2>&1); rc=$?
  [ $rc = 2 ] && echo "$msg" | grep -qF -- "-o $2: " && echo "$msg" | grep -qF -- "$1" &&
    ! echo "$msg" | grep -q '"triangles"' && ok ||
    no "-o $2: rc $rc, $msg"
}
check_o "folder '/nonexistent/dir' does not exist" /nonexistent/dir/x.glb
mkdir -p "$out/ro.glb"
check_o "'$out/ro.glb' is a folder" "$out/ro.glb"
check_o "'$out/old.bin' is not a folder" "$out/old.bin/x.glb"
check_o "must end in .glb (binary glTF), .gltf (JSON glTF), .usda or .usd (USD text)" "$out/x.obj"
check_o "convert it to a crate file with OpenUSD's usdcat" "$out/x.usdc"
check_o "the file name is 256 bytes" "$out/$(printf '%0252d' 0).glb"
if command -v script >/dev/null; then
  msg=$(script -qec "'$bin' avenue --preset '$src/presets/avenue_boulevard.json' -o /nonexistent/dir/x.glb" /dev/null 2>&1)
  echo "$msg" | grep -q -- "-o /nonexistent/dir/x.glb" && ! echo "$msg" | grep -q '%' && ok ||
    no "-o checked after generating began: $msg"
fi

# PNG textures: a bad -o folder first, then a full disk leaves every old
# PNG as it was, and a kill leaves no cut PNG.
msg=$("$bin" textures -o /nonexistent/dir --size 64 2>&1); rc=$?
[ $rc = 2 ] && echo "$msg" | grep -qF -- "-o /nonexistent/dir: folder '/nonexistent/dir' does not exist" && ok ||
  no "textures -o: rc $rc, $msg"
mkdir -p "$out/png" "$out/png_old"
"$bin" textures -o "$out/png" --size 64 >/dev/null || no "textures --size 64"
cp "$out/png"/*.png "$out/png_old/"
msg=$( (trap '' XFSZ; ulimit -f 100; "$bin" textures -o "$out/png" --size 512) 2>&1); rc=$?
[ $rc = 1 ] && echo "$msg" | grep -q "File too large" && ok || no "textures full disk: rc $rc, $msg"
killed "$bin" textures -o "$out/png" --size 512; rc=$?
[ $rc -gt 128 ] && ok || no "textures killed: rc $rc"
rm -f "$out/png"/.*.tmp
for f in "$out/png_old"/*.png; do
  cmp -s "$f" "$out/png/$(basename "$f")" && ok || no "textures: $(basename "$f") changed by a failed write"
done
[ "$(ls "$out/png" | wc -l)" = "$(ls "$out/png_old" | wc -l)" ] && ok || no "textures: files appeared or vanished"

echo "cli_output: $pass passed, $fail failed"
[ $fail = 0 ]
