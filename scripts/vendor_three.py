#!/usr/bin/env python3
"""
Re-vendor three.js for the review page (``inertia-kit view``): install the pinned npm packages
into a temporary directory, bundle ``three`` with its ``OrbitControls`` addon into one minified
classic script (an IIFE that defines the global ``THREE``), and write it, with a header saying
what it is and how it was made, to ``inertia_kit/view/assets/three.min.js``, and three's licence
to ``three.LICENSE`` next to it.

Needs node and npm (and the npm registry) at vendoring time only; the page never fetches
anything. Run from anywhere: ``python3 scripts/vendor_three.py``. To move to another version,
change the pins below, run it, and check the page in a browser (``pytest tests/view``).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

THREE_VERSION = "0.187.0"
ESBUILD_VERSION = "0.28.2"

ASSETS = Path(__file__).resolve().parent.parent / "inertia_kit" / "view" / "assets"

# the bundle's entry: all of three plus the one addon the page uses, under one namespace
ENTRY = """\
export * from "three";
export { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
"""

HEADER = """\
/* three.js {three} (MIT, see three.LICENSE) with OrbitControls, bundled for inertia-kit's review
 * page by esbuild {esbuild}: npm packages three@{three} and esbuild@{esbuild}, one minified classic
 * script defining the global THREE. Do not edit: re-vendor with `python3 scripts/vendor_three.py`
 * (pins at its top). */
"""


def _run(command: list[str], cwd: Path) -> None:
    print("+", " ".join(command), file=sys.stderr)
    subprocess.run(command, cwd=cwd, check=True)


def main() -> int:
    if shutil.which("npm") is None or shutil.which("node") is None:
        print("vendor_three: node and npm are needed (apt-get install nodejs npm)", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="vendor-three-") as scratch:
        work = Path(scratch)
        (work / "package.json").write_text(json.dumps({"private": True}), encoding="utf-8")
        _run(
            [
                "npm", "install", "--no-audit", "--no-fund", "--save-exact",
                f"three@{THREE_VERSION}", f"esbuild@{ESBUILD_VERSION}",
            ],
            work,
        )  # fmt: skip
        (work / "entry.js").write_text(ENTRY, encoding="utf-8")
        bundle = work / "three.min.js"
        _run(
            [
                str(work / "node_modules" / ".bin" / "esbuild"), "entry.js", "--bundle",
                "--minify", "--format=iife", "--global-name=THREE", "--target=es2020",
                "--legal-comments=none", f"--outfile={bundle}",
            ],
            work,
        )  # fmt: skip
        installed = json.loads((work / "node_modules/three/package.json").read_text("utf-8"))
        if installed["version"] != THREE_VERSION:
            print(f"vendor_three: npm installed three {installed['version']}", file=sys.stderr)
            return 2
        header = HEADER.format(three=THREE_VERSION, esbuild=ESBUILD_VERSION)
        ASSETS.mkdir(parents=True, exist_ok=True)
        (ASSETS / "three.min.js").write_text(header + bundle.read_text("utf-8"), encoding="utf-8")
        shutil.copyfile(work / "node_modules/three/LICENSE", ASSETS / "three.LICENSE")
    print(f"vendor_three: wrote {ASSETS / 'three.min.js'} and three.LICENSE", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
