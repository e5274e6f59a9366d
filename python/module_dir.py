"""Prints where the running interpreter finds modules installed under PREFIX, then 'yes' if that
folder is on its sys.path as it starts, else 'no' (a module there then needs PYTHONPATH).

usage: python3 module_dir.py PREFIX

The first entry of sys.path that is PREFIX/lib*/.../site- or dist-packages wins (lib*: so that
/usr/local/lib/... is not taken for the prefix /usr): Debian's
python3 searches PREFIX/lib/python3/dist-packages for /usr and PREFIX/lib/python3.X/dist-packages
for /usr/local, a venv or pyenv interpreter its own site-packages. Otherwise the platlib of
sysconfig's posix_prefix scheme under PREFIX.
"""
import os
import sys
import sysconfig


def main():
    prefix = os.path.realpath(sys.argv[1])
    for entry in sys.path:
        real = os.path.realpath(entry) if entry else ""
        if not real.startswith(prefix + os.sep):
            continue
        parts = os.path.relpath(real, prefix).split(os.sep)
        if parts[0].startswith("lib") and parts[-1] in ("site-packages", "dist-packages"):
            print(real)
            print("yes")
            return
    paths = sysconfig.get_paths("posix_prefix", vars={"base": prefix, "platbase": prefix})
    print(paths["platlib"])
    print("no")


main()
