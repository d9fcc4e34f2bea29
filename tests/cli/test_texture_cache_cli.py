#!/usr/bin/env python3
"""The CLI's texture cache (docs/gltf.md "Texture cache"), all in folders
under the test output, never the user's cache:
  - --texture-cache DIR: the .glb is the same bytes with the cache off,
    cold (the folder gains a file per texture) and warm, and the same as
    an ivy's with its own key;
  - BANYAN_TEXTURE_CACHE=DIR and, with neither, $XDG_CACHE_HOME/banyan/
    textures are used the same way; BANYAN_TEXTURE_CACHE=off and
    --texture-cache off store nothing;
  - a cut cache file is rewritten and the .glb stays the same;
  - --texture-cache '' is a bad command line (exit 2).

    test_texture_cache_cli.py <banyan cli> <out dir>
"""
import os
import shutil
import subprocess
import sys

FAILS = []


def check(ok, what):
    if not ok:
        FAILS.append(what)
        print("FAIL: " + what)


def run(cli, out, extra, env_set):
    env = {k: v for k, v in os.environ.items() if k not in ("BANYAN_TEXTURE_CACHE", "XDG_CACHE_HOME")}
    env["HOME"] = os.path.dirname(out)  # never the user's: ~/.cache would land in the test output
    env.update(env_set)
    args = [cli, "keyaki", "--set", "levels=7", "--texture-size", "128", "-o", out] + extra
    r = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
    return r.returncode, (open(out, "rb").read() if r.returncode == 0 else b""), r.stderr


def btc(folder):
    return sorted(f for f in os.listdir(folder) if f.endswith(".btc")) if os.path.isdir(folder) else []


def main():
    cli, top = sys.argv[1], sys.argv[2]
    base = os.path.join(top, "texture_cache_cli")
    shutil.rmtree(base, ignore_errors=True)
    os.makedirs(base)
    out = os.path.join(base, "tree.glb")

    rc, off, err = run(cli, out, ["--texture-cache", "off"], {})
    check(rc == 0 and len(off) > 1000, "cache off: written (%s)" % err.strip())
    check(btc(os.path.join(base, ".cache", "banyan", "textures")) == [], "--texture-cache off: nothing under HOME")

    d = os.path.join(base, "flag")
    rc, cold, err = run(cli, out, ["--texture-cache", d], {})
    check(rc == 0 and cold == off, "--texture-cache DIR, cold: the uncached bytes (%s)" % err.strip())
    files = btc(d)
    check(len(files) == 2, "cold: a file for the leaves and one for the bark, got %s" % files)
    rc, warm, _ = run(cli, out, ["--texture-cache", d], {})
    check(rc == 0 and warm == off, "--texture-cache DIR, warm: the uncached bytes")

    # A cut file: passed over, the same .glb, the file rewritten whole.
    if files:
        f = os.path.join(d, files[0])
        whole = open(f, "rb").read()
        with open(f, "wb") as fh:
            fh.write(whole[:len(whole) // 2])
        rc, again, _ = run(cli, out, ["--texture-cache", d], {})
        check(rc == 0 and again == off, "a cut cache file: the uncached bytes")
        check(open(f, "rb").read() == whole, "a cut cache file is rewritten whole")

    e = os.path.join(base, "env")
    for k in range(2):
        rc, got, _ = run(cli, out, [], {"BANYAN_TEXTURE_CACHE": e})
        check(rc == 0 and got == off, "BANYAN_TEXTURE_CACHE=DIR, run %d: the uncached bytes" % k)
    check(len(btc(e)) == 2, "BANYAN_TEXTURE_CACHE=DIR holds the files")

    x = os.path.join(base, "xdg")
    for k in range(2):
        rc, got, _ = run(cli, out, [], {"XDG_CACHE_HOME": x})
        check(rc == 0 and got == off, "XDG_CACHE_HOME, run %d: the uncached bytes" % k)
    check(len(btc(os.path.join(x, "banyan", "textures"))) == 2, "$XDG_CACHE_HOME/banyan/textures holds the files")

    o = os.path.join(base, "env_off")
    rc, got, _ = run(cli, out, ["--texture-cache", o], {"BANYAN_TEXTURE_CACHE": "off"})
    check(rc == 0 and got == off and not os.path.exists(o), "BANYAN_TEXTURE_CACHE=off wins over --texture-cache DIR")

    rc, _, err = run(cli, out, ["--texture-cache", ""], {})
    check(rc == 2 and "--texture-cache" in err, "--texture-cache '' refused with exit 2 (%d: %s)" % (rc, err.strip()))

    shutil.rmtree(base, ignore_errors=True)
    print("test_texture_cache_cli: %d failed" % len(FAILS))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
