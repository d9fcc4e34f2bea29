#!/usr/bin/env python3
"""The add-on's Windows x64 packages from a cross-build (tools/win/build.sh):

  BUILD/banyan_extension_windows-x64.zip  the Blender 4.2+ extension: the
      package's files at the root, blender_manifest.toml with
      platforms = ["windows-x64"], lib/ and presets/;
  BUILD/banyan_windows-x64.zip            the legacy add-on: banyan/ with
      banyan/lib/ and banyan/presets/, no manifest.

lib/ holds banyan.dll, banyan_vdb.dll and every DLL they import (stripped), found by
following objdump's import tables from BUILD; only Windows' own DLLs are
left out (SYSTEM_DLLS). A DLL that is imported but neither there nor
Windows' own stops the packaging. The Linux packages are CMake's
(blender_addon/CMakeLists.txt) and do not change.

usage: package.py BUILD_DIR [--check ZIP]
  --check ZIP  checks a package instead: its manifest (for an extension)
               and that every DLL a DLL in it imports is in it or Windows'.
"""
import io
import os
import re
import subprocess
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
OBJDUMP = "x86_64-w64-mingw32-objdump"
# DLLs every Windows x64 has (what the mingw runtime and the libraries use).
SYSTEM_DLLS = {"kernel32.dll", "msvcrt.dll", "user32.dll", "advapi32.dll", "psapi.dll", "shell32.dll",
               "ole32.dll", "oleaut32.dll", "gdi32.dll", "ws2_32.dll", "bcrypt.dll", "ntdll.dll",
               "shlwapi.dll", "version.dll", "winmm.dll", "dbghelp.dll"}
ROOTS = ["banyan.dll", "banyan_vdb.dll"]


def imports(data):
    """The DLL names a PE file imports (objdump -p)."""
    out = subprocess.run([OBJDUMP, "-p", "-"], input=data, capture_output=True, check=False).stdout
    if not out:  # objdump reads no stdin: through a file
        import tempfile
        with tempfile.NamedTemporaryFile(suffix=".dll") as f:
            f.write(data)
            f.flush()
            out = subprocess.run([OBJDUMP, "-p", f.name], capture_output=True, check=True).stdout
    return re.findall(r"DLL Name: (\S+)", out.decode())


def closure(build):
    """lib/'s files: the roots and what they import, transitively."""
    have = {n.lower(): n for n in os.listdir(build) if n.lower().endswith(".dll")}
    todo, seen, missing = list(ROOTS), [], []
    while todo:
        name = todo.pop()
        if name.lower() in (s.lower() for s in seen):
            continue
        if name.lower() not in have:
            missing.append(name)
            continue
        seen.append(have[name.lower()])
        with open(os.path.join(build, have[name.lower()]), "rb") as f:
            for dep in imports(f.read()):
                if dep.lower() not in SYSTEM_DLLS and not dep.lower().startswith("api-ms-win-"):
                    todo.append(dep)
    if missing:
        sys.exit("package.py: imported but not in %s: %s" % (build, ", ".join(sorted(set(missing)))))
    return sorted(seen)


def stripped(path):
    """The DLL's bytes without its symbol tables and debug sections (as Debian's packages ship)."""
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        out = os.path.join(t, os.path.basename(path))
        subprocess.run([OBJDUMP.replace("objdump", "strip"), "--strip-unneeded", "-o", out, path], check=True)
        return open(out, "rb").read()


def package_files():
    """(path inside the package, bytes) of the add-on's Python package, without lib/ and caches."""
    root = os.path.join(REPO, "blender_addon", "banyan")
    out = []
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if x != "__pycache__" and not (d == root and x == "lib"))
        for f in sorted(files):
            p = os.path.join(d, f)
            out.append((os.path.relpath(p, root).replace(os.sep, "/"), open(p, "rb").read()))
    return out


def windows_manifest(text):
    new, n = re.subn(r'(?m)^platforms = \[.*\]$', 'platforms = ["windows-x64"]', text)
    if n != 1:
        sys.exit("package.py: blender_manifest.toml has no single platforms line")
    new = new.replace("# libbanyan.so (lib/) is built for Linux x86-64 only.",
                      "# This package's lib/ (banyan.dll and its DLLs) is built for Windows x64.")
    return new


def write_zip(path, entries):
    with zipfile.ZipFile(path + ".tmp", "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in entries:
            info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = 0o644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    os.replace(path + ".tmp", path)


def build_packages(build):
    libs = closure(build)
    lib_entries = [("lib/" + n, stripped(os.path.join(build, n))) for n in libs]
    lib_entries.append(("lib/bundled.txt", ("".join(n + "\n" for n in libs if n not in ROOTS)).encode()))
    presets = []
    pdir = os.path.join(REPO, "presets")
    for d, dirs, files in os.walk(pdir):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(d, f)
            presets.append(("presets/" + os.path.relpath(p, pdir).replace(os.sep, "/"), open(p, "rb").read()))
    pkg = package_files()
    ext = []
    for name, data in pkg:
        if name == "blender_manifest.toml":
            data = windows_manifest(data.decode()).encode()
        ext.append((name, data))
    ext += lib_entries + presets
    legacy = [("banyan/" + n, d) for n, d in pkg if n != "blender_manifest.toml"]
    legacy += [("banyan/" + n, d) for n, d in lib_entries + presets]
    e = os.path.join(build, "banyan_extension_windows-x64.zip")
    z = os.path.join(build, "banyan_windows-x64.zip")
    write_zip(e, ext)
    write_zip(z, legacy)
    print("%s: %d DLLs (%s)" % (e, len(libs), ", ".join(libs)))
    print(z)
    return e, z


def check(path):
    """0 when the package is whole: manifest (extension) and every import inside or Windows'."""
    bad = []
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        prefix = "banyan/" if "banyan/__init__.py" in names else ""
        if not prefix:
            m = z.read("blender_manifest.toml").decode()
            for want in ('platforms = ["windows-x64"]', 'id = "banyan"', 'type = "add-on"'):
                if want not in m:
                    bad.append("manifest lacks " + want)
            try:
                import tomllib
                tomllib.loads(m)
            except ImportError:
                pass
            except Exception as e:  # a manifest Blender could not read
                bad.append("manifest is not TOML: %s" % e)
        dlls = {n[len(prefix) + 4:].lower(): n for n in names if n.startswith(prefix + "lib/") and n.endswith(".dll")}
        for root in ROOTS:
            if root not in dlls:
                bad.append("no lib/" + root)
        for low, n in sorted(dlls.items()):
            for dep in imports(z.read(n)):
                d = dep.lower()
                if d not in dlls and d not in SYSTEM_DLLS and not d.startswith("api-ms-win-"):
                    bad.append("%s imports %s, which is not in the package" % (n, dep))
    for b in bad:
        print("package.py: %s: %s" % (path, b))
    print("%s: %s" % (path, "ok" if not bad else "%d problems" % len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[2] == "--check":
        sys.exit(check(sys.argv[3]))
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    for p in build_packages(sys.argv[1]):
        if check(p):
            sys.exit(1)
