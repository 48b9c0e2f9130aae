#!/usr/bin/env python3
"""Shows that check_layering.py can fail: copies engine/ to a temporary folder, checks that the
copy passes, plants a back-edge (base/ including render/, the first layer including a later
one) and asserts that the check then exits 1 naming it; likewise a gRPC header, a folder
missing from the table and an installed tool including the lab's testing/. Python 3 standard library only.
"""

import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "check_layering.py")
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))


def run(root):
    result = subprocess.run([sys.executable, CHECK, "--root", root], capture_output=True,
                            text=True, check=False)
    return result.returncode, result.stdout + result.stderr


def expect(condition, message, output):
    if not condition:
        print(f"FAIL: {message}\n--- check_layering.py said:\n{output}")
        sys.exit(1)


def plant(root, relative, line):
    path = os.path.join(root, "engine", relative)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "a", encoding="utf-8") as f:
        f.write(f"\n{line}\n")


def main():
    with tempfile.TemporaryDirectory(prefix="layering-") as tmp:
        copy = os.path.join(tmp, "repo")
        shutil.copytree(os.path.join(REPO, "engine"), os.path.join(copy, "engine"),
                        ignore=shutil.ignore_patterns("data"))
        code, out = run(copy)
        expect(code == 0, "the unchanged copy of engine/ should pass", out)

        plant(copy, "base/image.h", '#include "render/renderer.h"')
        code, out = run(copy)
        expect(code == 1, "a planted back-edge base/ -> render/ should fail the check", out)
        expect("engine/base/image.h" in out and "back-edge base/ -> render/" in out,
               "the failure should name the file and the back-edge", out)

        shutil.rmtree(os.path.join(copy, "engine"))
        shutil.copytree(os.path.join(REPO, "engine"), os.path.join(copy, "engine"),
                        ignore=shutil.ignore_patterns("data"))
        plant(copy, "scene/scene.h", "#include <grpcpp/grpcpp.h>")
        plant(copy, "newstage/thing.h", '#include "base/image.h"')
        code, out = run(copy)
        expect(code == 1, "a gRPC include and an unlisted folder should fail the check", out)
        expect("includes gRPC" in out and "engine/newstage/" in out,
               "the failure should name the gRPC include and the unlisted folder", out)

        shutil.rmtree(os.path.join(copy, "engine"))
        shutil.copytree(os.path.join(REPO, "engine"), os.path.join(copy, "engine"),
                        ignore=shutil.ignore_patterns("data"))
        plant(copy, "tools/aperture_tex_main.cc", '#include "testing/grazing_plane.h"')
        code, out = run(copy)
        expect(code == 1, "an installed tool including testing/ should fail the check", out)
        expect("engine/tools/aperture_tex_main.cc" in out and "tools/ includes testing/" in out,
               "the failure should name the tool and the lab folder", out)
    print("check_layering.py passes on engine/ and fails on a planted back-edge, a gRPC include, "
          "an unlisted folder and a tool including testing/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
