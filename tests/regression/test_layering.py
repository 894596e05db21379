#!/usr/bin/python3
"""The pipeline's layering (docs/developing.md, "Architecture"): a folder of src/peridot/ includes only the
folders listed before it, never one after. Fails naming every include that points up."""
import argparse
import glob
import os
import re
import sys

# The order of docs/developing.md's table; a new folder is added there and here.
ORDER = ["core", "state", "deck", "geometry", "neighbor", "loads", "correspondence", "materials", "damage",
         "contact", "parallel", "output", "solvers"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", required=True)
    parser.add_argument("--peridot")  # unused: every python test is given it
    parser.add_argument("--work")
    a = parser.parse_args()
    rank = {folder: i for i, folder in enumerate(ORDER)}
    root = os.path.join(a.source, "src", "peridot")
    folders = sorted(d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)))
    unknown = [d for d in folders if d not in rank]
    if unknown:
        print("folders missing from ORDER (and from docs/developing.md):", ", ".join(unknown))
        return 1
    upward = []
    for path in sorted(glob.glob(os.path.join(root, "*", "*"))):
        folder = os.path.basename(os.path.dirname(path))
        for number, line in enumerate(open(path, encoding="utf-8"), 1):
            m = re.match(r'\s*#include "peridot/(\w+)/', line)
            if m and rank[m.group(1)] > rank[folder]:
                upward.append(f"{os.path.relpath(path, a.source)}:{number}: {folder}/ includes {m.group(1)}/")
    for line in upward:
        print(line)
    print(f"{len(folders)} folders, {len(upward)} includes of a folder below in the pipeline")
    return 1 if upward else 0


if __name__ == "__main__":
    sys.exit(main())
