"""Builds the installable add-on: target/skelfit_blender.zip (Blender: Preferences > Add-ons >
Install..., then enable "Rigging: skelfit").

Usage (from the repository root): python3 integrations/blender/make_zip.py [OUT.zip]
"""

import os
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = "skelfit_blender"


def build(out):
    """Writes the package folder into ``out`` (files sorted, fixed timestamps) and returns it."""
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    source = os.path.join(HERE, PACKAGE)
    names = sorted(n for n in os.listdir(source) if n.endswith(".py"))
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in names:
            info = zipfile.ZipInfo(f"{PACKAGE}/{name}", date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = 0o644 << 16
            with open(os.path.join(source, name), "rb") as handle:
                archive.writestr(info, handle.read(), zipfile.ZIP_DEFLATED)
    return out


if __name__ == "__main__":
    default = os.path.join(HERE, "..", "..", "target", "skelfit_blender.zip")
    path = build(os.path.normpath(sys.argv[1] if len(sys.argv) > 1 else default))
    print(path)
