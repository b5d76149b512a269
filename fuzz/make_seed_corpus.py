#!/usr/bin/env python3
"""Seeds the fuzz targets' corpora from the test data (docs/fuzzing.md).

  map/     every map in maps/ and tests/data/maps/ (good and broken)
  mesh/    every mesh in tests/data/meshes/ and its hostile/ corpus, behind the byte that picks its format
  policy/  the policy files given with --policies (peg-paper writes some), the broken configurations, and
           the crash inputs kept in fuzz/regressions/policy/

Files in fuzz/regressions/<target>/ (inputs that once crashed a target) are copied into every run's corpus.

Usage: fuzz/make_seed_corpus.py OUT_DIR [--policies DIR]
"""

import argparse
import pathlib
import shutil

EXTENSIONS = [".obj", ".stl", ".ply", ".off", ".gltf", ".glb", ".3ds"]  # fuzz_mesh_import.cpp's order


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--policies")
    args = parser.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(args.out)
    for target in ("map", "mesh", "policy"):
        (out / target).mkdir(parents=True, exist_ok=True)
    n = 0
    for folder in (root / "maps", root / "tests/data/maps", root / "tests/data/maps/broken", root / "tests/collision"):
        for f in sorted(folder.rglob("*.yaml")):
            shutil.copy(f, out / "map" / f"{f.parent.name}_{f.name}")
            n += 1
    for folder in (root / "tests/data/meshes", root / "tests/data/meshes/hostile"):
        for f in sorted(folder.iterdir()):
            ext = f.suffix.lower()
            if ext in EXTENSIONS:
                (out / "mesh" / f"{folder.name}_{f.name}").write_bytes(bytes([EXTENSIONS.index(ext)]) + f.read_bytes())
                n += 1
    sources = sorted((root / "tests/data/configs/broken").glob("*.json"))
    if args.policies:
        sources += sorted(pathlib.Path(args.policies).glob("*.json"))
    for f in sources:
        shutil.copy(f, out / "policy" / f.name)
        n += 1
    for target in ("map", "mesh", "policy"):
        kept = root / "fuzz" / "regressions" / target
        if kept.is_dir():
            for f in sorted(kept.iterdir()):
                shutil.copy(f, out / target / f"regression_{f.name}")
                n += 1
    print(f"wrote {n} seed files into {out}")


if __name__ == "__main__":
    main()
